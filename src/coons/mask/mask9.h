// Symmetric 3×3 masks: b_ij = e_i·(b_{i−1,j} + b_{i+1,j}) + e_j·(b_{i,j−1} + b_{i,j+1}) + d·K_ij,
// K_ij the sum of the four diagonal neighbours. Affine invariance: 2e_i + 2e_j + 4d = 1.
//
// alpha_mask(α):           d = α, e_i = e_j = β = 1/4 − α (α = −1/4 Coons, α = 0 Laplace).
// anisotropic_mask(m,n,μ): the discretisation of ∫‖p_uv‖² + μ∫(‖p_u‖² + ‖p_v‖²) (docs/math.md §3):
//                          D = 4mn + 2μ(m/n + n/m), d = −mn/D, e_i = (2mn + μm/n)/D,
//                          e_j = (2mn + μn/m)/D; for m = n, α(n) = −n²/(4(n² + μ)) (docs/math.md §4).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <cmath>
#include <vector>

#include "solvers/grid_stencil.h"

namespace coons {

struct Mask9 {
  double edge_i = 0.25;  //!< weight of the two neighbours along i (u)
  double edge_j = 0.25;  //!< weight of the two neighbours along j (v)
  double diag = 0;       //!< weight of the four diagonal neighbours

  //! 2e_i + 2e_j + 4d − 1: zero for an affine-invariant mask.
  [[nodiscard]] double affine_defect() const { return 2 * edge_i + 2 * edge_j + 4 * diag - 1; }
  //! The mask reproduces constants (to rounding): its net moves with its boundary, so it may be
  //! solved for the boundary moved to its centre (solve_mask_net, run_sweep).
  [[nodiscard]] bool reproduces_constants() const { return std::abs(affine_defect()) <= 1e-14; }
};

//! The Farin–Hansford one-parameter family.
Mask9 alpha_mask(double alpha);

//! The largest |α| (and |c| of the triangular family) that the command line and the searches
//! accept. The weights α and 1/4 − α enter products of two weights (the pivots of the structured
//! solvers, the closed-form eigenvalues) and squared residuals, which overflow from about 1e154 on:
//! `fast` called the well-conditioned system of the dome singular at α = 1e160, and at 1e308 the
//! singularity check named four points that do not decouple. 1e60, the bound of coordinates
//! (io/json_file.h), keeps a weight times a coordinate, and its square, far from overflow; every
//! backend that applies solves the dome at ±1e60 (the others report indefiniteness).
inline constexpr double kMaxAlpha = 1e60;

//! The eigenvalue of the mask system for the sine mode with cp = cos(pπ/m), cq = cos(qπ/n):
//! λ = 1 − 2e_i·cp − 2e_j·cq − 4d·cp·cq.
inline double mask9_eigenvalue(const Mask9& mask, double cp, double cq) {
  return 1 - 2 * mask.edge_i * cp - 2 * mask.edge_j * cq - 4 * mask.diag * cp * cq;
}

//! min|λ| / max|λ| over the eigenvalues of the mask system on the full (m−1)×(n−1) interior with
//! one fixed ring: λ_pq = 1 − 2e_i·cos(pπ/m) − 2e_j·cos(qπ/n) − 4d·cos(pπ/m)·cos(qπ/n) (the sine
//! modes diagonalise it; docs/math.md §3). 0 for a singular system; 1 when there is no interior.
double mask9_eigenvalue_ratio(const Mask9& mask, int m, int n);
//! The α in (lower, upper) where the α family's system on the (m−1)×(n−1) interior is singular:
//! where λ_pq of alpha_mask(α) vanishes, α = (s/2 − 1)/(2s − 4cp·cq), s = cp + cq, for some mode;
//! increasing, each once (values within 1e-12 relative merged, and of a bound: not inside). None
//! lies in [−1/4, 1/4].
std::vector<double> alpha_family_singular_alphas(int m, int n, double lower, double upper);
//! A mask system with mask9_eigenvalue_ratio at most this is taken as (near) singular: `solve`
//! then looks for the points that decouple, and the α search does not evaluate there.
constexpr double kNearSingularEigenvalueRatio = 1e-6;

//! The anisotropic mask of the energy ∫‖p_uv‖² + μ∫‖∇p‖² at degree (m, n); μ ≥ 0.
Mask9 anisotropic_mask(int m, int n, double mu);

//! α of the isotropic family that belongs to μ at degree n: −n²/(4(n² + μ)).
double alpha_from_mu(int n, double mu);

//! μ that gives α at degree n (inverse of alpha_from_mu; α ∈ [−1/4, 0)): μ = −n²(1 + 4α)/(4α).
double mu_from_alpha(int n, double alpha);

//! The mask as the operator I − mask on an interior grid of rows × cols points.
solvers::GridStencil mask_stencil(const Mask9& mask, int rows, int cols);

}  // namespace coons
