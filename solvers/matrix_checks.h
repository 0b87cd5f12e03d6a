// Checks of an assembled matrix before it goes to a library preconditioner: Eigen's
// IncompleteCholesky and hypre's BoomerAMG crash or abort the process on a matrix with an empty
// row or column, and the diagonal preconditioners divide by the diagonal. O(nnz).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <functional>
#include <optional>
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

//! The relative rise of the diagonal, A + δ·diag(|a_kk|), with which semidefinite_verdict looks
//! at a matrix whose factorisation stopped. Far above the rounding of a Cholesky factorisation
//! (about n·ε of the diagonal), so a singular semidefinite A raised factors.
inline constexpr double kSemidefiniteShift = 1e-10;

//! A (square, a copy) with each diagonal entry a_kk raised by δ·|a_kk|: the same pattern, so a
//! symbolic analysis of A serves it. Invariant under a diagonal scaling D A D.
Eigen::SparseMatrix<double> raise_diagonal(Eigen::SparseMatrix<double> A, double delta);

//! The smallest eigenvalue of the symmetric A relative to its diagonal (of D^{-1/2} A D^{-1/2},
//! D = diag(|a_kk|) > 0), as inverse iteration with the raised matrix finds it, and the rounding
//! bound of that figure. `solve_raised` returns (A + δ·D)⁻¹ B for three columns.
struct ScaledEigenvalue {
  double value = 0;     //!< the smallest Rayleigh quotient xᵀAx / xᵀDx of the iterates (≥ the true one)
  double rounding = 0;  //!< (m + √n)·ε·|x|ᵀ|A||x| / xᵀDx, m the most entries of a row of A
};
ScaledEigenvalue smallest_scaled_eigenvalue(
    const Eigen::SparseMatrix<double>& A, const std::function<Eigen::MatrixX3d(const Eigen::MatrixX3d&)>& solve_raised);

//! The verdict on a symmetric A whose Cholesky-type factorisation stopped at a pivot ≤ 0, which
//! alone cannot tell the singular semidefinite [[1, 2], [2, 4]] from the regular indefinite
//! [[0, 1], [1, 0]] or [[1, 1], [1, 1 − 1e-11]]. `raised`: nullopt when A raised by
//! kSemidefiniteShift (raise_diagonal) did not factor with positive pivots (then an eigenvalue lies
//! below −δ: indefinite), else the smallest scaled eigenvalue found with it. kNotPositiveDefinite
//! when that is negative beyond its rounding; kSingular when it is not (zero to working precision,
//! or positive where the factorisation of A still failed), or when A has an empty row. *message
//! gets the reason, after `stopped` (what the factorisation said).
SolveStatus semidefinite_verdict(const Eigen::SparseMatrix<double>& A, const std::optional<ScaledEigenvalue>& raised,
                                 const std::string& stopped, std::string* message);

//! kSingular with "row K is empty: the matrix is singular" (or column K) when a row or column of A
//! has no non-zero; with `need_diagonal`, kNotApplicable with "the diagonal is zero at row K (counting from 0): the
//! preconditioner needs it"; otherwise kSuccess. The reason goes to *why.
SolveStatus check_preconditioner_matrix(const Eigen::SparseMatrix<double>& A, bool need_diagonal, std::string* why);

}  // namespace coons::solvers
