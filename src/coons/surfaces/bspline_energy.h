// Exact energies of a tensor B-spline surface by piecewise Gram matrices (docs/math.md §10):
//   G^a[i][k] = ∫ N^{(a)}_{i,p}(u) N^{(a)}_{k,p}(u) du, summed over the knot spans with
//   Gauss–Legendre of p + 1 nodes per span (exact: the integrand has degree ≤ 2p there),
//   E(a, b) = ∫∫ ‖∂^a_u ∂^b_v s‖² = Σ_xyz Σ G_u^a[i][k] G_v^b[j][l] b_ij b_kl.
// The named energies combine E(a, b) as for Bézier surfaces (coons/metrics/energies.h): twist
// E(1,1), Dirichlet E(1,0) + E(0,1), thin plate E(2,0) + 2E(1,1) + E(0,2),
// E3 E(3,0) + 3E(2,1) + 3E(1,2) + E(0,3). Integrals over the surface's parameter domain.
// Sizes: G^a is #count by #count (banded: zero beyond p off the diagonal).
// Based on: L. Piegl, W. Tiller, The NURBS Book (1997), A2.3 (basis derivatives); G. H. Golub,
// J. H. Welsch, Calculation of Gauss quadrature rules, Math. Comp. 23 (1969).
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "coons/surfaces/bspline_surface.h"

namespace coons {

//! G^a of the B-spline basis of degree p on `knots` (a > p: zero).
Eigen::MatrixXd bspline_gram(const Eigen::VectorXd& knots, int degree, int order);

//! E(a, b) of the surface (0 when a > p or b > q).
double bspline_energy(const BSplineSurface& s, int a, int b);

//! The symmetric bilinear form of E(a, b) for two nets on the same knots and degrees
//! (E(X + hY) = E(X) + 2h·form(X, Y) + h²E(Y)); `s` gives the knots and degrees.
double bspline_energy_form(const BSplineSurface& s, const ControlNet& X, const ControlNet& Y, int a, int b);

//! Σ weight·E(a, b) with the weights of (a, b) as pairs {a, b, weight}.
struct BSplineEnergyTerm {
  int a = 0, b = 0;
  double weight = 1;
};
double bspline_combined_energy(const BSplineSurface& s, const std::vector<BSplineEnergyTerm>& terms);
double bspline_combined_energy_form(const BSplineSurface& s, const ControlNet& X, const ControlNet& Y,
                                    const std::vector<BSplineEnergyTerm>& terms);

std::vector<BSplineEnergyTerm> bspline_twist_terms();
std::vector<BSplineEnergyTerm> bspline_dirichlet_terms();
std::vector<BSplineEnergyTerm> bspline_thin_plate_terms();
std::vector<BSplineEnergyTerm> bspline_e3_terms();

//! Gauss–Legendre nodes and weights on [0, 1] with k nodes (Golub–Welsch).
std::pair<Eigen::VectorXd, Eigen::VectorXd> gauss_legendre_unit(int k);

}  // namespace coons
