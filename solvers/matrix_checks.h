// Checks of an assembled matrix before it goes to a library preconditioner: Eigen's
// IncompleteCholesky and hypre's BoomerAMG crash or abort the process on a matrix with an empty
// row or column, and the diagonal preconditioners divide by the diagonal. O(nnz).
#pragma once

#include <Eigen/SparseCore>
#include <cmath>
#include <string>

#include "linear_solver.h"

namespace coons::solvers {

//! A pivot d of an LDLᵀ (or L_kk² of an LLᵀ) counts as zero at most this fraction of its own
//! diagonal entry a_kk of A: d = a_kk − (what the earlier rows explain of it) cancelled to 13 digits.
//! Measured against the diagonal, not the largest pivot, the test does not change under a diagonal
//! scaling D A D (diag(1, 1e-20) and a Laplacian scaled by 10^±8 row by row were called singular).
inline constexpr double kSingularPivot = 1e-13;

//! is_zero_pivot: |d| ≤ kSingularPivot·|a_kk|, or, where a_kk = 0 (indefinite), of the largest |pivot|.
inline bool is_zero_pivot(double d, double a_kk, double largest_pivot) {
  return std::abs(d) <= kSingularPivot * (a_kk != 0 ? std::abs(a_kk) : largest_pivot);
}

//! kSingular with "row K is empty: the matrix is singular" (or column K) when a row or column of A
//! has no non-zero; with `need_diagonal`, kNotApplicable with "the diagonal is zero at row K: the
//! preconditioner needs it"; otherwise kSuccess. The reason goes to *why.
SolveStatus check_preconditioner_matrix(const Eigen::SparseMatrix<double>& A, bool need_diagonal, std::string* why);

}  // namespace coons::solvers
