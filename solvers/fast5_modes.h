// fast5, per-mode factorisation: after the sine transform along j the fast5 operator without its
// boundary-column correction splits into one symmetric pentadiagonal Toeplitz matrix per mode q,
//   M_q = (a ν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I   (rows × rows, P = toeplitz(6, −4, 1), D = tridiag(−1, 2, −1)),
// factored here by banded LDLᵀ without pivoting (M_q is definite). The factors converge down the
// rows, so only the rows above convergence are stored: sizes #rows·#cols at most, 4 % of it at
// N = 1023; FactorRow rebuilds one full row (#cols) of the factors at a time for the sweeps.
// Based on: G. H. Golub & C. F. Van Loan, Matrix Computations, §4.3 (banded LDLᵀ).
#pragma once

#include <Eigen/Core>
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

// Full rows of the factors, kept up to date as a sweep moves one row at a time (only the stored
// modes are copied; the rest keep the limit).
class FactorRow {
 public:
  explicit FactorRow(const ModeFactors& f) : f_(f), inv_d(f.lim_inv_d), l1(f.lim_l1), l2(f.lim_l2), active_(0) {}
  //! Makes inv_d, l1, l2 the factors of row r.
  void seek(int r);
  const ModeFactors& f_;
  std::vector<double> inv_d, l1, l2;

 private:
  int active_;
};

//! The factors of M_q for the modes ν = nu (#cols) of the fourth-order stencil a·C + b·T, rows each.
ModeFactors factor_modes(double a, double b, const Eigen::VectorXd& nu, int rows);

}  // namespace coons::solvers::fast5_detail
