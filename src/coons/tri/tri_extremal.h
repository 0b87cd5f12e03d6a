// Energy extremals of triangular Bézier nets: the interior that minimises the exact Dirichlet,
// thin-plate or twist energy of tri_energy.h for a given boundary (the "functional extremal"
// way of filling a triangle, as opposed to the mask family). With E(P) = Σ_xyz P_cᵀ K P_c,
// K = Σ Dᵀ G D (#(n+1)(n+2)/2 square, D derivative operators, G the Bernstein Gram matrix), the
// minimiser solves K_II X = −K_IB P_B (#interior by 3), a small dense symmetric positive definite
// system (n ≤ 30 or so; n = 20 has 171 unknowns).
// Based on: J. Monterde, Bézier surfaces of minimal area: the Dirichlet approach, CAGD 21 (2004)
// (extremals of the Dirichlet functional as a linear system in the control points); the triangular
// case is "Arnal et al., 2003" as cited by A. Arnal, A. Lluch, Coons triangular Bézier surfaces
// (SciTePress, 2010), of which only the abstract and introduction were read.
#pragma once

#include <Eigen/Core>

#include "coons/tri/tri_net.h"

namespace coons::tri {

enum class TriEnergy { kDirichlet, kThinPlate, kTwist };

//! The parameter triangle: corners of b[n][0][0], b[0][n][0], b[0][0][n] in the plane. The default
//! is the reference triangle of tri_energy.h; equilateral() has unit sides and the symmetries of
//! the index triangle (there the Dirichlet and thin-plate energies are symmetric under i, j, k).
struct TriDomain {
  Eigen::Vector2d v1{1, 0}, v2{0, 1}, v3{0, 0};
  static TriDomain equilateral() { return {{1, 0}, {0.5, 0.8660254037844386}, {0, 0}}; }
  [[nodiscard]] double area() const;
  //! ∂/∂x and ∂/∂y of the plane as barycentric directions (columns 0 and 1).
  [[nodiscard]] Eigen::Matrix<double, 3, 2> cartesian_directions() const;
};

//! K with E(P) = Σ_xyz P_cᵀ K P_c for the energy `kind` at degree n (row order), over `domain`
//! (the twist is taken in barycentric directions and only scales with the area).
Eigen::MatrixXd tri_energy_hessian(int n, TriEnergy kind, const TriDomain& domain = {});

//! The net with the boundary of `frame` and the interior minimising `kind` (n < 3: the frame).
TriNet minimize_tri_energy(const TriNet& frame, TriEnergy kind, const TriDomain& domain = {});

}  // namespace coons::tri
