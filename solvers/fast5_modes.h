// fast5, per-mode factorisation: after the sine transform along j the fast5 operator without its
// boundary-column correction splits into one symmetric pentadiagonal Toeplitz matrix per mode q,
//   M_q = (a ν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I   (rows × rows, P = toeplitz(6, −4, 1), D = tridiag(−1, 2, −1)),
// factored here by banded LDLᵀ without pivoting (M_q is definite). The factors converge down the
// rows, so only the rows above convergence are stored: sizes #rows·#cols at most, 4 % of it at
// N = 1023. A solve (solve_chunk) sweeps one chunk of modes down the rows and back up in a buffer
// of #rows × chunk per right-hand side, reading a stored row or the limits directly; the modes
// are independent, so chunks may run on different threads.
// Based on: G. H. Golub & C. F. Van Loan, Matrix Computations, §4.3 (banded LDLᵀ).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "fast5_rows.h"

namespace coons::solvers::fast5_detail {

//! sqrt(2/(n+1))·sin(kπ/(n+1)), k = 1..n: the orthonormal DST-I of e_1 (#n).
Eigen::VectorXd first_sine_column(int n);

//! 2 − 2cos(kπ/(n+1)), k = 1..n: the eigenvalues of tridiag(−1, 2, −1) (#n).
Eigen::VectorXd second_difference_eigenvalues(int n);

// The banded LDLᵀ factors of M_q for every mode q, row by row. M_q is Toeplitz, so its factors
// converge geometrically down the rows (after about 40/√ν_q rows, ν_q the mode's eigenvalue):
// from row r_q on they equal their limit to the last bit, and only the rows above are stored.
// Row r keeps the modes q < active[r] (the ones not yet converged there; active is
// non-increasing), contiguous from offset[r]; the others read the limit.
struct ModeFactors {
  int rows = 0, cols = 0;
  std::vector<int> active;
  std::vector<std::size_t> offset;
  std::vector<double> inv_d, l1, l2;              // stored part
  std::vector<double> lim_inv_d, lim_l1, lim_l2;  // limits, one per mode
};

//! The factors of row r at mode q, stored or the limit: {1/d, l1, l2}.
std::array<double, 3> mode_factor(const ModeFactors& f, int r, int q);

//! The factors of M_q for the modes ν = nu (#cols) of the fourth-order stencil a·C + b·T, rows each,
//! on up to `threads` threads (OpenMP; the same on any count). The modes q < first are not factored
//! (their entries read zero: no sweep may take them; fast5 solves them in closed form).
ModeFactors factor_modes(double a, double b, const Eigen::VectorXd& nu, int rows, int threads, int first = 0);

//! The right-hand side of a solve_chunk, row r, mode q, right-hand side c: hats[c][r·cols + q]
//! (hats[c] = nullptr: edges[c]'s row r at mode q, fast5_rows.h, with the sine vectors s0 and s1
//! of the columns 0 and 1; both nullptr: zero) + sign·(z_even(r, c) t_even[q] + z_odd(r, c)
//! t_odd[q]), the sources U z on the boundary columns in the sine basis (z = nullptr: none).
struct SweepInput {
  std::array<const double*, 3> hats{};
  std::array<const EdgeRows*, 3> edges{};
  const double* s0 = nullptr;
  const double* s1 = nullptr;
  const std::array<Eigen::MatrixXd, 2>* z = nullptr;
  double sign = 1;
  const double* t_even = nullptr;  //!< t_q on the even modes q, 0 on the odd ones (#cols)
  const double* t_odd = nullptr;
  const double* t = nullptr;  //!< t_q on every mode (#cols): with it, edge rows are read in one pass (down_edge_rows)
};

//! Where solve_chunk puts M⁻¹ of its input: grid[c] (rows × cols, row-major; nullptr: nowhere)
//! gets it (add = false) or adds it (add = true). grid[c] may be in.hats[c]: a row of the chunk is
//! read before it is written.
struct ChunkOutput {
  std::array<double*, 3> grid{};
  bool add = false;
};

//! One row of the way down (L⁻¹) at the modes [b0, b1), three right-hand sides at once: w[c] (that
//! row of right-hand side c, from mode b0) = the input of grid row r (see SweepInput) − l1·(the row
//! `stride` doubles before) − l2·(the row 2·stride before), with the factors of elimination step e
//! (the factor rows e − 1 and e − 2; min(e, 2) rows before). zeros: b1 − b0 zeros; scratch: 3·(b1 − b0).
//! A negative stride runs the rows backwards (the way down from the bottom, fast5_twisted.h).
void down_row(const ModeFactors& f, int e, int r, int b0, int b1, int count, const SweepInput& in,
              const std::array<double*, 3>& w, std::ptrdiff_t stride, const double* zeros, double* scratch);

//! One row of the way up at the modes [b0, b1): o[c] = y[c]·inv_d − l1·(the row `stride` doubles
//! after o[c]) − l2·(the row 2·stride after), with the factors of row e; `rows` ∈ {0, 1, 2} rows after.
void up_row_into(const ModeFactors& f, int e, int b0, int b1, const std::array<double*, 3>& o,
                 const std::array<const double*, 3>& y, std::ptrdiff_t stride, int rows);

//! up_row_into in place: w[c] = w[c]·inv_d − l1·(the row `stride` doubles after) − l2·(2·stride
//! after), the same bits.
void up_row(const ModeFactors& f, int e, int b0, int b1, const std::array<double*, 3>& w, std::ptrdiff_t stride,
            int rows);

//! M⁻¹ of the input for the modes [b0, b1) (b0 even) and right-hand sides c < count ≤ 3: down the
//! rows into buf and back up in it (buf: 3·rows·(b1 − b0) doubles, small enough to stay in the
//! cache; the three right-hand sides are swept together), then into the output. dot(r, 2k·c + 2m + p) = Σ v(q)·sines(q,
//! m) over the chunk's modes q of parity p, v = row r of the chunk's new values (the grid's with a grid, M⁻¹ of the
//! input otherwise), k = sines.cols(): a partial sum, the same whichever thread solves the chunk. The modes are
//! independent: chunks may run on different threads.
void solve_chunk(const ModeFactors& f, int b0, int b1, int count, const SweepInput& in, const ChunkOutput& out,
                 double* buf, const Eigen::MatrixXd& sines, Eigen::MatrixXd& dot);

}  // namespace coons::solvers::fast5_detail
