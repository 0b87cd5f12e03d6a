#include "matrix_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

namespace coons::solvers {

SolveStatus check_preconditioner_matrix(const Eigen::SparseMatrix<double>& A, bool need_diagonal, std::string* why) {
  std::vector<char> row_used(std::size_t(A.rows()), 0), col_used(std::size_t(A.cols()), 0);
  std::vector<char> diagonal(std::size_t(std::min(A.rows(), A.cols())), 0);
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) {
      if (it.value() == 0) continue;
      row_used[std::size_t(it.row())] = col_used[std::size_t(it.col())] = 1;
      if (it.row() == it.col()) diagonal[std::size_t(it.row())] = 1;
    }
  const auto fail = [&](SolveStatus status, const std::string& reason) {
    if (why) *why = reason;
    return status;
  };
  for (std::size_t r = 0; r < row_used.size(); ++r)
    if (!row_used[r])
      return fail(SolveStatus::kSingular,
                  "row " + std::to_string(r) + " (counting from 0) is empty: the matrix is singular");
  for (std::size_t c = 0; c < col_used.size(); ++c)
    if (!col_used[c])
      return fail(SolveStatus::kSingular,
                  "column " + std::to_string(c) + " (counting from 0) is empty: the matrix is singular");
  if (need_diagonal)
    for (std::size_t r = 0; r < diagonal.size(); ++r)
      if (!diagonal[r])
        return fail(SolveStatus::kNotApplicable, "the diagonal is zero at row " + std::to_string(r) +
                                                     " (counting from 0): the preconditioner needs it");
  return SolveStatus::kSuccess;
}

Eigen::SparseMatrix<double> raise_diagonal(Eigen::SparseMatrix<double> A, double delta) {
  A.makeCompressed();
  double* values = A.valuePtr();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (int p = outer[k]; p < outer[k + 1]; ++p)
      if (inner[p] == k) values[p] += delta * std::abs(values[p]);
  return A;
}

ScaledEigenvalue smallest_scaled_eigenvalue(
    const Eigen::SparseMatrix<double>& A,
    const std::function<Eigen::MatrixX3d(const Eigen::MatrixX3d&)>& solve_raised) {
  const auto lower = A.selfadjointView<Eigen::Lower>();  // the triangle the factorisations read
  const Eigen::VectorXd d = A.diagonal().cwiseAbs();
  // three fixed start vectors (a generic one meets every eigenvector), two steps of inverse
  // iteration for the pencil (A, D): x ← (A + δD)⁻¹ D x. An eigenvalue λ of the scaled matrix is
  // weighted by 1/(λ + δ) per step: 1e10 for a zero one against 1e3 for one of 1e-3.
  std::mt19937_64 generator(20261204);
  std::uniform_real_distribution<double> uniform(-1, 1);
  Eigen::MatrixX3d X(A.rows(), 3);
  for (Eigen::Index k = 0; k < X.size(); ++k) X.data()[k] = uniform(generator);
  for (int step = 0; step < 2; ++step) {
    X = solve_raised(d.asDiagonal() * X);
    for (int c = 0; c < 3; ++c)
      if (const double norm = X.col(c).lpNorm<Eigen::Infinity>(); norm > 0 && std::isfinite(norm)) X.col(c) /= norm;
  }
  const Eigen::MatrixX3d ax = lower * X;
  const Eigen::SparseMatrix<double> absolute = A.cwiseAbs();
  const Eigen::MatrixX3d abs_ax = absolute.selfadjointView<Eigen::Lower>() * X.cwiseAbs();
  Eigen::Index most = 0;  // entries of the fullest row (column: A is symmetric)
  for (Eigen::Index k = 0; k < A.outerSize(); ++k) most = std::max<Eigen::Index>(most, A.col(k).nonZeros());
  const double gamma = (double(most) + std::sqrt(double(A.rows()))) * std::numeric_limits<double>::epsilon();
  ScaledEigenvalue smallest{std::numeric_limits<double>::infinity(), 0};
  for (int c = 0; c < 3; ++c) {
    const double scale = X.col(c).cwiseAbs2().dot(d);
    if (!(scale > 0) || !std::isfinite(scale)) continue;
    const double value = X.col(c).dot(ax.col(c)) / scale;
    if (std::isfinite(value) && value < smallest.value)
      smallest = {value, gamma * X.col(c).cwiseAbs().dot(abs_ax.col(c)) / scale};
  }
  return smallest;
}

SolveStatus semidefinite_verdict(const Eigen::SparseMatrix<double>& A, const std::optional<ScaledEigenvalue>& raised,
                                 const std::string& stopped, std::string* message) {
  const auto say = [&](SolveStatus status, const std::string& why) {
    if (message) *message = stopped + "; " + why;
    return status;
  };
  if (std::string empty; check_preconditioner_matrix(A, false, &empty) == SolveStatus::kSingular)
    return say(SolveStatus::kSingular, empty);
  std::ostringstream text;
  text << "with its diagonal raised by " << kSemidefiniteShift << " of itself ";
  if (!raised) return say(SolveStatus::kNotPositiveDefinite, text.str() + "it still does not factor: indefinite");
  if (!std::isfinite(raised->value))  // (the raised factor solved to nothing finite: nothing learnt)
    return say(SolveStatus::kNotPositiveDefinite, text.str() + "it factors, but inverse iteration found no eigenvalue");
  text << "it factors, and inverse iteration with it finds the smallest eigenvalue relative to the diagonal at "
       << raised->value << " (rounding " << raised->rounding << "): ";
  if (raised->value < -raised->rounding) return say(SolveStatus::kNotPositiveDefinite, text.str() + "indefinite");
  return say(SolveStatus::kSingular, text.str() + "singular to working precision");
}

}  // namespace coons::solvers
