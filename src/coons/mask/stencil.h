// Symmetric 3×3 and 5×5 masks as stencils: the equation at a free point (i, j) is
//
//   Σ_{|a|,|b| ≤ r} W(a, b) · b_{i+a, j+b} = 0,   W(0, 0) = 1 (centre normalised), r = 1 or 2,
//
// i.e. the mask b_ij = −Σ_{(a,b) ≠ 0} W(a, b) b_{i+a,j+b}. Affine invariance is Σ W = 0. A stencil
// is "symmetric" when W(a, b) = W(−a, −b): exactly what makes the system matrix symmetric (the
// named masks are also symmetric under each reflection, W(a, b) = W(−a, b) = W(a, −b)).
// weights(r + a, r + b) = W(a, b): rows run along i (u), columns along j (v).
//
// Named stencils (unnormalised form, then divided by the centre):
//   alpha_stencil(Mask9):  centre 1, W(±1, 0) = −e_i, W(0, ±1) = −e_j, W(±1, ±1) = −d (docs/math.md §3).
//   c1_coons_stencil():    δ⁴ ⊗ δ⁴, δ⁴ = (1, −4, 6, −4, 1): Δ⁴_i Δ⁴_j b = 0 (centre 36).
//   biharmonic_stencil():  13 points: centre 20, edges −8, diagonals 2, distance-2 axial 1.
//   c1_family_stencil(w):  the Euler–Lagrange operator of
//       E_w(b) = w·Σ‖Δ^{2,2}b‖² + (1−w)·(Σ‖Δ^{2,0}b‖² + 2Σ‖Δ^{1,1}b‖² + Σ‖Δ^{0,2}b‖²),
//     the sums over every position where the forward difference fits in the net.
//   Derivation: for a forward difference with stencil s (e.g. Δ² = (1, −2, 1)), ∂/∂b_ij of
//   Σ‖Δ_s b‖² is 2·(s ⋆ s)·b at (i, j), s ⋆ s the autocorrelation, whenever every shifted copy of
//   s that covers (i, j) fits in the net — for the terms above that is 2 ≤ i ≤ m−2 and
//   2 ≤ j ≤ n−2, i.e. every free point of a problem with two data rings, and every free point whose
//   5×5 stencil stays in the net. The autocorrelations are
//       (1, −2, 1) ⋆ (1, −2, 1) = (1, −4, 6, −4, 1) = δ⁴,   (1, −1) ⋆ (1, −1) = (−1, 2, −1) = −δ²,
//   so (Δ^{2,2})ᵀΔ^{2,2} = δ⁴ ⊗ δ⁴ = C (the c1-coons stencil, centre 36),
//       (Δ^{2,0})ᵀΔ^{2,0} + 2(Δ^{1,1})ᵀΔ^{1,1} + (Δ^{0,2})ᵀΔ^{0,2} = δ⁴ ⊗ e + 2 δ² ⊗ δ² + e ⊗ δ⁴ = T,
//   T = [0 0 1 0 0; 0 2 −8 2 0; 1 −8 20 −8 1; 0 2 −8 2 0; 0 0 1 0 0] (the biharmonic stencil, e the
//   unit impulse). The Euler–Lagrange equations of E_w are therefore (w·C + (1−w)·T) b = 0:
//
//       W_w = (w·C + (1−w)·T) / (20 + 16w),   centre 36w + 20(1−w) = 20 + 16w,
//       W_w(0,0) = 1;  W_w(±1,0) = W_w(0,±1) = (−24w − 8(1−w))/(20+16w) = −(8 + 16w)/(20 + 16w);
//       W_w(±1,±1) = (16w + 2(1−w))/(20+16w) = (2 + 14w)/(20 + 16w);
//       W_w(±2,0) = W_w(0,±2) = (6w + (1−w))/(20+16w) = (1 + 5w)/(20 + 16w);
//       W_w(±2,±1) = W_w(±1,±2) = −4w/(20 + 16w);   W_w(±2,±2) = w/(20 + 16w).
//   w = 1 gives C/36 (c1-coons), w = 0 gives T/20 (biharmonic); dW_w/dw = (20C − 36T)/(20 + 16w)².
//   Every W_w (w ∈ [0, 1]) is positive semidefinite as a convolution (it is a sum of
//   autocorrelations), so its symbol is ≥ 0 and every free set gives a positive definite system.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700 (masks as
// energy minimisers); P. Salvi, quadfit (5×5 masks with two rings).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <utility>

#include "coons/mask/mask9.h"

namespace coons {

struct Stencil {
  int radius = 1;           //!< 1 (3×3) or 2 (5×5)
  Eigen::MatrixXd weights;  //!< (2·radius+1) square, weights(radius + a, radius + b) = W(a, b)

  //! W(a, b) for |a|, |b| ≤ radius.
  [[nodiscard]] double at(int a, int b) const { return weights(radius + a, radius + b); }
  [[nodiscard]] int size() const { return 2 * radius + 1; }
};

//! A stencil from raw weights (3×3 or 5×5) divided by their centre. Precondition: the centre is
//! non-zero. A 5×5 array whose outer ring is zero stays 5×5 (see trimmed()).
Stencil make_stencil(const Eigen::MatrixXd& raw);

//! The same stencil with radius 1 when its outer ring is zero.
Stencil trimmed(const Stencil& s);

//! The 3×3 α / μ / (α, γ) families as stencils.
Stencil alpha_stencil(const Mask9& mask);
//! Back to a Mask9, when the stencil is 3×3 and reflection-symmetric (nullopt otherwise).
std::optional<Mask9> to_mask9(const Stencil& s);

Stencil c1_coons_stencil();
Stencil biharmonic_stencil();
//! w ∈ [0, 1] (other w give a valid stencil but not an energy minimiser).
Stencil c1_family_stencil(double w);
//! dW_w/dw (centre 0): the derivative of c1_family_stencil's weights (for searches over w).
Eigen::MatrixXd c1_family_stencil_derivative(double w);

//! Σ W: 0 for an affine-invariant stencil.
double weight_sum(const Stencil& s);
//! max |W(a, b) − W(−a, −b)|: 0 for a symmetric stencil.
double symmetry_defect(const Stencil& s);

//! The symbol σ(θ, φ) = Σ W(a, b) cos(aθ + bφ) (real for a symmetric stencil): the eigenvalue of
//! the stencil on the infinite grid for the wave e^{i(aθ + bφ)}.
double stencil_symbol(const Stencil& s, double theta, double phi);

//! True when min σ ≥ −tolerance: σ on a 256 × 256 grid of [0, 2π)² (0 and π among the points),
//! then a damped Newton descent from each local minimum of those samples, which finds a dip
//! narrower than the grid spacing (a file stencil whose σ dips to −8e-9 between two samples near
//! θ = 0 was taken as ≥ 0, and its singular system solved into garbage).
//! σ ≥ 0 means xᵀ A_F x = (2π)⁻² ∫ σ |x̂|² > 0 for every finite free set F and x ≠ 0 (x̂ a
//! non-zero trigonometric polynomial; σ, with mean W(0,0) = 1, vanishes only on a null set), so
//! every free set gives a positive definite system. For arbitrary stencils this is a search, not a
//! proof; for the named ones σ ≥ 0 holds exactly (α ∈ [−1/4, 1/4] and the C1 family).
bool symbol_nonnegative(const Stencil& s, double tolerance = 1e-12);

//! W = u vᵀ (a separable stencil: c1-coons, the α = −1/4 Coons mask): the two symmetric factors
//! (u along i, v along j, each #2·radius+1), or nullopt when the rank exceeds 1 (relative 1e-13).
std::optional<std::pair<Eigen::VectorXd, Eigen::VectorXd>> separable_factors(const Stencil& s);

}  // namespace coons
