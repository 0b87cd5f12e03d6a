// fast5, the boundary values g without a sweep. g, the right-hand side of the capacitance system,
// is Σ_q t_q·M_q⁻¹ b̂(·, q) over the modes q of one parity (b̂: the sine transform of b along j).
// When b's rows are zero off the columns 0, 1, cols−2 and cols−1 but for a few full rows (mask
// data: the four next to the frame), b's 2-D sine transform has rank (full rows + 4):
//   F = Σ_e S_i e_e ⊗ w_e + Σ_{j ∈ {0, 1, cols−2, cols−1}} β̂_j ⊗ s_j,
// w_e the transform of full row e along j, β̂_j the transform along i of column j (off the full
// rows), s_j = S_j e_j. In the sine basis along i, M_q = Λ_q + α_q σσᵀ on each parity block of p
// (fast5_capacitance.h), and by Sherman–Morrison
//   ĝ(p) = Σ_q t_q F(p, q)/λ_pq − σ_p Σ_q (t_q γ_q/λ_pq) Σ_m σ_m F(m, q)/λ_mq,
// which, since the block's G has the columns c_q Λ_q⁻¹σ (c_q² = t_q² γ_q), is
//   ĝ = Σ_e (σ̃_e/σ) ⊙ G x_e + β̂⁽⁰⁾ ⊙ K₀ + β̂⁽¹⁾ ⊙ K₁ − G z,
//   x_e(q) = t_q w_e(q)/c_q,   z(q) = (Gᵀ F(·, q))/t_q,
// with σ̃_e = S_i e_e, K_j(p) = Σ_q t_q s_j(q)/λ_pq from the set-up, and the mirrored rows and
// columns (e and rows−1−e, j and cols−1−j) combined per parity; row 0's term, σ̃_0/σ = 1/√2,
// goes into z's product. One pass over G for Gᵀ (the key rows' σ̃_e and two vectors per
// right-hand side) and one for G (one vector per key row e > 0 and right-hand side, and z):
// O(rows·cols·(keys + 3)) flops, no sweep of the grid.
// Based on: P. E. Bjørstad, Fast numerical solution of the biharmonic Dirichlet problem on
// rectangles, SIAM J. Numer. Anal. 20 (1983) 59–71 (the capacitance formulation), and the
// Sherman–Morrison formula.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "fast5_capacitance.h"
#include "fast5_rows.h"
#include "sine_transform.h"

namespace coons::solvers::fast5_detail {

//! One right-hand side in the form above, for one block's parity of p: key rows (e ≤ rows−1−e, the
//! same list for every right-hand side), rows[k] = w_e + (−1)^{p parity}·w_{rows−1−e} over those
//! of the two that are full (#cols, all modes q), and beta_hat (#rows × 4) the transforms along i
//! of the columns 0, 1, cols−2, cols−1 on the other rows.
struct BoundarySource {
  std::vector<Eigen::VectorXd> rows;
  Eigen::MatrixXd beta_hat;
};

//! The sources of the right-hand sides edges[0 .. count) (fast5_rows.h, their full rows
//! transformed along j): keys = the key rows min(e, rows−1−e) of their full rows e (sorted, the same
//! for all), sources[ppar][c] their BoundarySource for each parity of p; along_i the transform of
//! length rows. False, and nothing formed, when there are more than max_keys key rows.
bool boundary_sources(const EdgeRows* edges, int count, detail::SineTransform& along_i, std::size_t max_keys,
                      std::vector<int>& keys, std::array<std::vector<BoundarySource>, 2>& sources);

//! ĝ on the block `blk` of parities (qpar, ppar) (#modes of the block × sources.size()): t is
//! √2·S_j e₁ over all modes q (#cols), s0 and s1 the orthonormal sine vectors S_j e₀, S_j e₁ of the
//! grid columns 0 and 1 (#cols each), keys the key rows, grid_rows the number of grid rows.
Eigen::MatrixXd boundary_values(const CapacitanceBlock& blk, int qpar, const Eigen::VectorXd& t, const double* s0,
                                const double* s1, const std::vector<int>& keys, int grid_rows,
                                const std::vector<BoundarySource>& sources);

}  // namespace coons::solvers::fast5_detail
