// fast5, per-mode factorisation: after the sine transform along j the fast5 operator without its
// boundary-column correction splits into one symmetric pentadiagonal Toeplitz matrix per mode q,
//   M_q = (a ν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I   (rows × rows, P = toeplitz(6, −4, 1), D = tridiag(−1, 2, −1)),
// factored here by banded LDLᵀ without pivoting (M_q is definite). The factors converge down the
// rows, so only the rows above convergence are stored: sizes #rows·#cols at most, 4 % of it at
// N = 1023. The sweeps (down and up the rows, #rows × #cols per right-hand side) read a stored
// row or the limits directly, one range of modes at a time (the modes are independent).
// Based on: G. H. Golub & C. F. Van Loan, Matrix Computations, §4.3 (banded LDLᵀ).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

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

//! The factors of M_q for the modes ν = nu (#cols) of the fourth-order stencil a·C + b·T, rows each.
ModeFactors factor_modes(double a, double b, const Eigen::VectorXd& nu, int rows);

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

//! The right-hand side of a downward sweep, row r, mode q: y(r, q) + sign·(z_even(r, c) t_even[q]
//! + z_odd(r, c) t_odd[q]) for right-hand side c; y = hats (rows × cols each) or zero (nullptr),
//! the sources U z on the boundary columns in the sine basis (z = nullptr: none).
struct SweepInput {
  const RowMajor* hats = nullptr;
  const std::array<Eigen::MatrixXd, 2>* z = nullptr;
  double sign = 1;
  const double* t_even = nullptr;  //!< t_q on the even modes q, 0 on the odd ones (#cols)
  const double* t_odd = nullptr;
};

//! Down the rows for the modes [q0, q1): work[c] = L⁻¹ (the input), c < count, row after row, a
//! row in chunks of `chunk` modes (q0 a multiple of it). The modes are independent: disjoint
//! ranges may run on different threads.
void sweep_down(const ModeFactors& f, int q0, int q1, int chunk, int count, const SweepInput& in, RowMajor* work);

//! Up the rows for the modes [q0, q1): work[c] ← (LD)⁻ᵀ work[c], completing M⁻¹ of the input;
//! with add (non-null) add[c] += the result. For each chunk [b, b + chunk) of the modes,
//! out[b / chunk](r, k·c + ·) = that part of row r of the result (of add[c] when given) times the
//! same rows of dots (#cols by k): partial sums, the same whatever range a chunk was swept in.
void sweep_up(const ModeFactors& f, int q0, int q1, int chunk, int count, RowMajor* work, RowMajor* add,
              const Eigen::MatrixXd& dots, Eigen::MatrixXd* out);

}  // namespace coons::solvers::fast5_detail
