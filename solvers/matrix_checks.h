// Checks of an assembled matrix before it goes to a library preconditioner: Eigen's
// IncompleteCholesky and hypre's BoomerAMG crash or abort the process on a matrix with an empty
// row or column, and the diagonal preconditioners divide by the diagonal. O(nnz).
#pragma once

#include <Eigen/SparseCore>
#include <string>

#include "linear_solver.h"

namespace coons::solvers {

//! kSingular with "row K is empty: the matrix is singular" (or column K) when a row or column of A
//! has no non-zero; with `need_diagonal`, kNotApplicable with "the diagonal is zero at row K: the
//! preconditioner needs it"; otherwise kSuccess. The reason goes to *why.
SolveStatus check_preconditioner_matrix(const Eigen::SparseMatrix<double>& A, bool need_diagonal, std::string* why);

}  // namespace coons::solvers
