// fast5, the lowest modes in closed form: M_q⁻¹ (fast5_modes.h) for the modes q < Q along j by the
// sine transform along i and Sherman–Morrison, instead of banded LDLᵀ. With S the orthonormal
// DST-I along i (S·D_i·S = diag μ) and P_i = D_i² + E_i,
//   S M_q S = Λ_q + α_q·(σσᵀ on each parity block of p),   λ_pq = a μ_p² ν_q² + b (μ_p + ν_q)²,
// α_q = a ν_q² + b, σ = √2·S e₁, so per parity block
//   M_q⁻¹ = S (Λ⁻¹ − c_q Λ⁻¹σ σᵀΛ⁻¹) S,   c_q = α_q / (1 + α_q σᵀΛ⁻¹σ).
// Why: κ(M_q) grows like (N/(q+1))⁴ (about 1e11 for q = 0 at N = 1023), and banded LDLᵀ has a
// forward error of κ·ε on these modes. That error, on the boundary columns, is what left fast5's
// first solve with a relative residual of 6e-6 there and made it correct the result with two more
// whole-grid sweeps. The closed form has no such amplification (every quotient is of an exact
// eigenvalue), and from q = Q on κ(M_q) is (Q+1)⁴ times smaller.
// Cost: 2·Q transforms of length rows per right-hand side and O(rows·Q) flops.
// Based on: P. E. Bjørstad, Fast numerical solution of the biharmonic Dirichlet problem on
// rectangles, SIAM J. Numer. Anal. 20 (1983) 59–71 (the sine basis and the rank-one boundary term).
#pragma once

#include <Eigen/Core>

#include "fast5_modes.h"
#include "sine_transform.h"

namespace coons::solvers::fast5_detail {

//! The closed form of M_q⁻¹ for the modes q < modes (sizes: rows × modes each).
struct LowModes {
  int rows = 0, cols = 0, modes = 0;
  Eigen::MatrixXd inv_lambda;  //!< 1/λ_pq (rows × modes)
  Eigen::MatrixXd coupling;    //!< σ_p/λ_pq · √c_q (rows × modes): the rank-one term is its outer product
  Eigen::VectorXd sigma;       //!< σ_p (#rows)
};

//! The closed form for the modes q < min(modes, #nu) of a·C + b·T: mu (#rows), nu (#cols) the
//! eigenvalues of D along i and j; on up to `threads` threads (OpenMP; the same on any count).
LowModes low_modes(double a, double b, const Eigen::VectorXd& mu, const Eigen::VectorXd& nu, int modes,
                   int threads = 1);

//! What solve_chunk does (same input, output and dots), for the modes [first, last) of [0, lm.modes)
//! (last < 0: to lm.modes) by the closed form; along_i: the DST-I of length rows (not shared with
//! another thread during the call). The modes are independent: two calls on disjoint ranges may run
//! at once (their dots are partial sums over their own modes).
void solve_low_modes(const LowModes& lm, detail::SineTransform& along_i, int count, const SweepInput& in,
                     const ChunkOutput& out, const Eigen::MatrixXd& sines, Eigen::MatrixXd& dot, int first = 0,
                     int last = -1);

}  // namespace coons::solvers::fast5_detail
