// Exact energies of a tensor B-spline surface (docs/math.md §10), as sums of squares:
//   E(a, b) = ∫∫ ‖∂^a_u ∂^b_v s‖² = Σ_spans Σ_g Σ_h w_g w_h ‖∂^a_u ∂^b_v s(u_g, v_h)‖²,
// Gauss–Legendre with p − a + 1 (q − b + 1) nodes per knot span, exact for the piecewise
// polynomial integrand of degree ≤ 2(p − a) (2(q − b)). The derivative values come from the
// derivative's own control net (A3.3: differences of the control points over knot spans, a B-spline
// of degree p − a on the knots without their first and last a), not from the derivatives of the
// basis applied to the points: so they lose no digits to a large offset of the net (a B-spline
// F(u) + G(v) at 1e6 has twist 0, not −0.12), and an energy is never below 0.
// The named energies combine E(a, b) as for Bézier surfaces (coons/metrics/energies.h): twist
// E(1,1), Dirichlet E(1,0) + E(0,1), thin plate E(2,0) + 2E(1,1) + E(0,2),
// E3 E(3,0) + 3E(2,1) + 3E(1,2) + E(0,3). Integrals over the surface's parameter domain.
// Sizes: O(count_u·count_v·(p + q)) per energy (banded samplings, no count × count matrix).
// Based on: L. Piegl, W. Tiller, The NURBS Book (1997), A2.3 (basis functions), A3.3 (derivative
// control points); G. H. Golub, J. H. Welsch, Calculation of Gauss quadrature rules,
// Math. Comp. 23 (1969).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "coons/surfaces/bspline_surface.h"

namespace coons {

//! The control points of the a-th derivative of Σ_i X.row(i) N_{i,p} on `knots` (#count + p + 1):
//! (count − a) rows, the coefficients of N_{i+a,p−a} on the same knots (A3.3:
//! P^(k)_i = (p − k + 1)/(t_{i+p+1} − t_{i+k}) · (P^(k−1)_{i+1} − P^(k−1)_i), 0 where that
//! function's support is empty). a > p: no rows.
Eigen::MatrixXd bspline_derivative_points(const Eigen::VectorXd& knots, int degree, const Eigen::MatrixXd& X, int a);

//! E(a, b) of the surface (0 when a > p or b > q); never below 0.
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

}  // namespace coons
