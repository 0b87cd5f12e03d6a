// Parametrised mask families and their derivatives, for searching the best mask.
//   alpha:  the Farin–Hansford family, d = α, e_i = e_j = 1/4 − α      (d/dα = (−1, −1, 1))
//   mu:     the anisotropic mask of ∫‖p_uv‖² + μ∫‖∇p‖² at degree (m, n) (docs/math.md §3, §4)
//   gamma:  the symmetric 3×3 family at fixed α: e_i = 1/4 − α + γ, e_j = 1/4 − α − γ, so that
//           (α, γ) spans every affine-invariant symmetric mask 4α + 2e_i + 2e_j = 1.
// Sensitivity: with the boundary fixed, A(p) N(p) = B(p) gives A · dN/dp = (dA/dp-free form)
//   dN/dp = A⁻¹ [ e_i'·E_i(N) + e_j'·E_j(N) + d'·K(N) ]   (neighbour sums over the full net),
// which for the α family is docs/math.md's A · dN/dα = K(N) − E(N).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <Eigen/Core>

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"

namespace coons {

//! A mask and the derivative of its three weights with respect to the family's parameter.
struct MaskPoint {
  Mask9 mask;
  Mask9 derivative;
};

MaskPoint alpha_family(double alpha);
MaskPoint mu_family(int m, int n, double mu);
//! μ on a compressed scale s ∈ [0, 1): μ = mn·s/(1 − s), so that a uniform scan in s covers
//! μ from 0 to many times mn (searches over μ use this; the derivative is with respect to s).
MaskPoint mu_family_compressed(int m, int n, double s);
double mu_of_compressed(int m, int n, double s);
double compressed_of_mu(int m, int n, double mu);

//! The compressed scale of one μ search over [lower, upper] (μ). mu(s) is exact at the bounds' own
//! compressed values and clamped into [lower, upper] elsewhere: mn·s/(1 − s) rounds, and the bound
//! 1000·mn = 21000 of a 3×7 net came back as μ* = 21000.000000000713, beyond it.
struct MuScale {
  int m = 1, n = 1;
  double lower = 0, upper = 0;
  [[nodiscard]] double s_lower() const { return compressed_of_mu(m, n, lower); }
  [[nodiscard]] double s_upper() const { return compressed_of_mu(m, n, upper); }
  [[nodiscard]] double mu(double s) const;
};

//! Derivative with respect to γ at fixed α.
MaskPoint gamma_family(double alpha, double gamma);

//! The right-hand side of A · dN/dp = …: #interior by 3, with dmask the derivative of the weights
//! and N the full net (boundary included).
Eigen::MatrixX3d mask_sensitivity_rhs(const ControlNet& net, const Mask9& dmask);

}  // namespace coons
