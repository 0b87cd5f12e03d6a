// A surface sampled on a k × k grid with the fields one looks at: unit normals, mean and Gaussian
// curvature, twist magnitude ‖r_uv‖ and, when a reference surface is given, the distance to it
// (closest point on the reference, by a grid search and Newton's method in its (u, v)).
// Grid convention (docs/formats.md): sample a·k + b is r(a/(k−1), b/(k−1)).
// Based on: M. P. do Carmo, Differential Geometry of Curves and Surfaces (1976), §3-3 (curvatures);
// closest points by Newton's method on ½‖r(u,v) − p‖² with clamping to [0, 1]².
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>

#include "coons/surfaces/surface.h"

namespace coons {

struct SurfaceSamples {
  int k = 0;                       //!< k × k grid
  Eigen::MatrixX3d points;         //!< #k² by 3, row a·k + b
  Eigen::MatrixX3d normals;        //!< unit r_u × r_v (NaN where singular)
  Eigen::VectorXd mean_curvature;  //!< H (NaN where singular)
  Eigen::VectorXd gaussian_curvature;
  Eigen::VectorXd twist;                               //!< ‖r_uv‖
  std::optional<Eigen::VectorXd> distance;             //!< to the reference surface (closest point)
  std::optional<Eigen::VectorXd> parametric_distance;  //!< ‖r(u,v) − r_ref(u,v)‖
};

//! k ≥ 2.
SurfaceSamples sample_grid(const Surface& s, int k);
//! The same grid over any surface given by its point function r(s, t), (s, t) ∈ [0, 1]²; k ≥ 2.
SurfaceSamples sample_grid(const std::function<SurfacePoint(double, double)>& point, int k);

//! Fills distance and parametric_distance.
void add_reference_distance(SurfaceSamples& samples, const Surface& reference);

//! The closest point of s to p: its parameters and distance (local minimum from the best of a
//! 33 × 33 grid of starting points).
struct ClosestPoint {
  double u = 0, v = 0, distance = 0;
};
ClosestPoint closest_point(const Surface& s, const Eigen::RowVector3d& p);

}  // namespace coons
