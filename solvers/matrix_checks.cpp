#include "matrix_checks.h"

#include <algorithm>
#include <cmath>
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
        return fail(SolveStatus::kNotApplicable,
                    "the diagonal is zero at row " + std::to_string(r) + ": the preconditioner needs it");
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

SolveStatus semidefinite_verdict(const Eigen::SparseMatrix<double>& A, bool raised_is_definite,
                                 const std::string& stopped, std::string* message) {
  std::string empty;
  if (check_preconditioner_matrix(A, false, &empty) == SolveStatus::kSingular) {
    if (message) *message = stopped + "; " + empty;
    return SolveStatus::kSingular;
  }
  std::ostringstream shift;
  shift << kSemidefiniteShift;
  if (raised_is_definite) {
    if (message)
      *message = stopped + "; with its diagonal raised by " + shift.str() +
                 " of itself the matrix factors with positive pivots: it is positive semidefinite and singular "
                 "(to that tolerance)";
    return SolveStatus::kSingular;
  }
  if (message)
    *message = stopped + "; with its diagonal raised by " + shift.str() +
               " of itself it still does not factor: the matrix is indefinite";
  return SolveStatus::kNotPositiveDefinite;
}

}  // namespace coons::solvers
