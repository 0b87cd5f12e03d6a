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

//! The relative rise of the diagonal, A + δ·diag(|a_kk|), by which semidefinite_verdict tells a
//! singular positive semidefinite matrix from an indefinite one. Far above the rounding of a
//! Cholesky factorisation (about n·ε of the diagonal), far below the eigenvalues of a regular
//! definite matrix that the factorisation could have refused.
inline constexpr double kSemidefiniteShift = 1e-10;

//! A (square, a copy) with each diagonal entry a_kk raised by δ·|a_kk|: the same pattern, so a
//! symbolic analysis of A serves it. Invariant under a diagonal scaling D A D.
Eigen::SparseMatrix<double> raise_diagonal(Eigen::SparseMatrix<double> A, double delta);

//! The verdict on a symmetric A whose Cholesky-type factorisation stopped at a pivot ≤ 0, which
//! alone cannot tell the singular semidefinite [[1, 2], [2, 4]] from the regular indefinite
//! [[0, 1], [1, 0]]. `raised_is_definite`: whether A raised by kSemidefiniteShift
//! (raise_diagonal) factored with every pivot positive. kSingular when it did (A is positive
//! semidefinite and singular to that tolerance) or when A has an empty row; kNotPositiveDefinite
//! otherwise. *message gets the reason, after `stopped` (what the factorisation said).
SolveStatus semidefinite_verdict(const Eigen::SparseMatrix<double>& A, bool raised_is_definite,
                                 const std::string& stopped, std::string* message);

//! kSingular with "row K is empty: the matrix is singular" (or column K) when a row or column of A
//! has no non-zero; with `need_diagonal`, kNotApplicable with "the diagonal is zero at row K: the
//! preconditioner needs it"; otherwise kSuccess. The reason goes to *why.
SolveStatus check_preconditioner_matrix(const Eigen::SparseMatrix<double>& A, bool need_diagonal, std::string* why);

}  // namespace coons::solvers
