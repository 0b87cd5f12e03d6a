// Exact energies of triangular Bézier surfaces over the reference triangle
// T = {(x, y): x, y ≥ 0, x + y ≤ 1} with (u, v, w) = (x, y, 1 − x − y), so the corners
// b[n][0][0], b[0][n][0], b[0][0][n] sit at (1, 0), (0, 1), (0, 0) and ∂x = D_(1,0,−1), ∂y = D_(0,1,−1):
//   Dirichlet   ∫_T ‖p_x‖² + ‖p_y‖²,
//   thin plate  ∫_T ‖p_xx‖² + 2‖p_xy‖² + ‖p_yy‖²,
//   twist       (1/3) Σ_m ∫_T ‖D_(e_a − e_m) D_(e_b − e_m) p‖², {a, b, m} = {1, 2, 3}: the mixed
//               derivative ∫‖p_xy‖² of the rectangular case, averaged over the three choices of the
//               corner at the right angle (m = 3 is ∫_T ‖p_xy‖²), so that it is symmetric under
//               every permutation of i, j, k,
//   E3          ∫_T ‖p_xxx‖² + 3‖p_xxy‖² + 3‖p_xyy‖² + ‖p_yyy‖² (the squared Frobenius norm of the
//               third-derivative tensor, as thin plate is that of the Hessian; the rectangle's E3 of
//               docs/math.md §5 in the same form).
// Each is Σ_xyz Cᵀ G C over derivative nets C, with the triangular Bernstein Gram matrix
//   G^n_αβ = ∫_T B^n_α B^n_β = C(n,α)·C(n,β) / C(2n,α+β) / ((2n+1)(2n+2))  (C multinomial),
// #(n+1)(n+2)/2 square in the row order of tri_net.h. Discrete energies: the same sums of squares of
// the net's own differences (without the factors n, n(n−1)). Quadrature: Gauss–Legendre after the
// Duffy map (x, y) = (s, (1 − s)t), for the checks.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), ch. 17 (Bernstein polynomials
// on triangles, products and integrals).
#pragma once

#include <Eigen/Core>

#include "coons/tri/tri_mask.h"
#include "coons/tri/tri_net.h"

namespace coons::tri {

//! ∂/∂x and ∂/∂y on the reference triangle as barycentric directions.
inline Eigen::Vector3d direction_x() { return {1, 0, -1}; }
inline Eigen::Vector3d direction_y() { return {0, 1, -1}; }

//! G^n: ∫_T B^n_α B^n_β over the reference triangle (area 1/2), row order.
Eigen::MatrixXd tri_bernstein_gram(int n);

//! ∫_T ⟨p_X, p_Y⟩ for two nets of the same degree (Σ_xyz X_cᵀ G Y_c).
double tri_inner_product(const TriNet& X, const TriNet& Y);

double tri_dirichlet_energy(const TriNet& net);
double tri_thin_plate_energy(const TriNet& net);
double tri_twist_energy(const TriNet& net);
double tri_e3_energy(const TriNet& net);

//! Σ_{|β|=n−1} ‖b_{β+e1} − b_{β+e3}‖² + ‖b_{β+e2} − b_{β+e3}‖².
double tri_discrete_dirichlet_energy(const TriNet& net);
//! Σ_{|β|=n−2} ‖Δxx b‖² + 2‖Δxy b‖² + ‖Δyy b‖², Δx b_β = b_{β+e1} − b_{β+e3}, Δy likewise.
double tri_discrete_thin_plate_energy(const TriNet& net);
//! (1/3) Σ_m Σ_β ‖Δ_(a,m) Δ_(b,m) b‖² (the discrete form of the twist above).
double tri_discrete_twist_energy(const TriNet& net);

//! Gauss–Legendre with k nodes per direction after the Duffy map: k² points in T, weights summing to
//! 1/2; exact for polynomials of total degree ≤ 2k − 2.
struct TriQuadratureRule {
  Eigen::MatrixX2d xy;
  Eigen::VectorXd weights;
};
TriQuadratureRule duffy_gauss_legendre(int k);

//! Every metric of a triangular `solve` report, computed once.
struct TriNetMetrics {
  double dirichlet_energy = 0, thin_plate_energy = 0, twist_energy = 0, e3_energy = 0;
  double discrete_dirichlet_energy = 0, discrete_thin_plate_energy = 0, discrete_twist_energy = 0;
  double mask_residual = 0;
};
TriNetMetrics tri_net_metrics(const TriNet& net, const TriMask& mask);

}  // namespace coons::tri
