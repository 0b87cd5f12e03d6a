// The separable solve X = P⁻¹ R Q⁻¹ (separable_banded_solver.h) of a right-hand side that comes
// from data rings, as a sum of outer products. A column R of B (rows × cols, row-major) whose rows
// are zero in columns 2..cols−3, apart from at most kMaxFullRows full rows, is
//
//   R = Σ_e a_e e_eᵀ + Σ_r e_r b_rᵀ,   e ∈ {0, 1, cols−2, cols−1},   r ∈ the full rows,
//
// (a_e: column e on the other rows, b_r: row r): the right-hand side of a system with two data
// rings has this form, with four full rows next to the frame. Then
//
//   X = Σ_e (P⁻¹ a_e)(Q⁻¹ e_e)ᵀ + Σ_r (P⁻¹ e_r)(Q⁻¹ b_r)ᵀ,
//
// 2K one-dimensional solves (K = 4 + full rows ≤ 12) and one pass that writes X, K multiply-adds
// per point (AVX2 with fused multiply-adds where the processor has them), instead of two sweeps
// over the grid. The fast solver's α = −1/4 path (kronecker_solver.h) does the same with one ring.
// Sizes: K·(rows + cols) doubles besides X.
// Based on: R. E. Lynch, J. R. Rice & D. H. Thomas, Direct solution of partial difference
// equations by tensor product methods, Numer. Math. 6 (1964) 185–199.
#pragma once

#include <optional>
#include <vector>

#include "separable_banded_solver.h"

namespace coons::solvers::detail {

//! Full rows up to which a column is solved as a sum of outer products (beyond it the two sweeps
//! of separable_banded_solve() cost less).
constexpr int kMaxFullRows = 8;

//! The form above of a column b (rows × cols, row-major): its full rows, ascending, and, from the
//! same read, the largest magnitude of the column (NaN when a value is a NaN or an infinity).
struct OuterForm {
  std::vector<int> full_rows;
  double largest = 0;
};
//! b's form, read on `threads` threads (OpenMP); nullopt when it has none (more than kMaxFullRows
//! full rows: B is then not read to the end; or cols < 5).
std::optional<OuterForm> outer_form(const double* b, int rows, int cols, int threads = 1);

//! x = P⁻¹ R Q⁻¹ for the column R = b of form `form`, on `threads` threads (OpenMP; the same bits
//! on any count). fi, fj: banded_ldlt() of P (rows) and Q (cols), both kSuccess.
void solve_outer_products(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const OuterForm& form,
                          const double* b, double* x, int threads = 1);
//! The same when b has the form above; false, writing nothing, otherwise.
bool solve_outer_products(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const double* b, double* x,
                          int threads = 1);

}  // namespace coons::solvers::detail
