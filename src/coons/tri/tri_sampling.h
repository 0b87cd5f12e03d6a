// A triangular Bézier surface sampled on the regular triangular grid of K points per side
// (K(K+1)/2 points, the row order of tri_net.h: row r = 0 … K−1, within a row s = 0 … K−1−r,
// barycentric (u, v, w) = (K−1−r−s, s, r)/(K−1)), its (K−1)² triangles, unit normals and curvatures
// in the parameters (x, y) = (u, v) of the reference triangle (tri_energy.h). Where p_x × p_y
// vanishes (a degenerate corner) the normal and the curvatures are undefined: they are 0 and
// `singular` is 1 there.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), ch. 17 (de Casteljau,
// directional derivatives); the curvatures from the fundamental forms (ch. 22).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "coons/tri/tri_net.h"

namespace coons::tri {

struct TriSurfaceSamples {
  int k = 0;                 //!< points per side
  Eigen::MatrixX3d points;   //!< #K(K+1)/2 by 3, row order
  Eigen::MatrixX3d normals;  //!< unit normals (0 where singular)
  Eigen::VectorXd mean_curvature, gaussian_curvature;
  Eigen::VectorXi singular;                   //!< 1 where the normal is undefined
  std::vector<std::array<int, 3>> triangles;  //!< (K−1)² triangles, counter-clockwise in (x, y)
};

//! The barycentric coordinates of sample (r, s) of a K-point grid.
Eigen::Vector3d tri_sample_uvw(int k, int r, int s);

//! The (K−1)² triangles of the triangular grid with K points per side over `k` (row order):
//! upward ones (r, s), (r, s+1), (r+1, s) and downward ones (r, s+1), (r+1, s+1), (r+1, s).
std::vector<std::array<int, 3>> tri_grid_triangles(int k);

//! Samples the surface of `net` (K ≥ 2).
TriSurfaceSamples sample_tri_surface(const TriNet& net, int k);

}  // namespace coons::tri
