// An exact solver for separable operators with five points per axis on a rows × cols grid
// (unknowns row-major, k = i·cols + j, zero values outside the grid):
//
//   A = P ⊗ Q,   P = toeplitz(p0, p1, p2) (rows × rows),   Q = toeplitz(q0, q1, q2) (cols × cols),
//   (A x)(i,j) = Σ_{|a|,|b| ≤ 2} p_|a| q_|b| x(i+a, j+b),
//
// symmetric banded Toeplitz factors with half-bandwidth 2 (pentadiagonal; p2 = 0 gives the
// tridiagonal case). Since A⁻¹ = P⁻¹ ⊗ Q⁻¹, each column of B, viewed as a rows × cols matrix R,
// is solved as X = P⁻¹ R Q⁻¹. When R comes from data rings (zero between the two edge columns
// but in at most 8 full rows), X is a sum of at most 12 outer products of 1-D solves, written in
// one pass (separable_outer_products.h). Any other R takes two sweeps over the grid: Q⁻¹ on blocks of 8 grid rows
// (read from B into a cols × 8 tile whose recurrences run across the 8 rows, vectorised, and written to X: the
// transposes are fused into the forward and the backward sweep), then P⁻¹ in place on strips of
// 128 columns (forward and back while the strip is in cache). Both sweeps' units (row blocks,
// strips, of all three columns) are independent and shared among SolverOptions::threads (OpenMP;
// the same result bit for bit on any count). factorize = banded LDLᵀ of P and Q without pivoting
// (O(rows + cols)); solve = O(rows·cols) per column of B, no fill, no memory beyond X and O(rows + cols). Exact up
// to rounding, and on c1-coons data more accurate than a sparse LDLᵀ of A (whose κ grows like
// k⁸, against k⁴ per factor here); LDLᵀ without pivoting is
// backward stable for definite factors (e.g. the fourth difference 1, −4, 6, −4, 1), so only
// those are solved: pivots of both signs, or a zero pivot (|d_k| ≤ 1e-14·max|diagonal|) before
// the last, mean an indefinite factor and kNotApplicable (A is then indefinite: use a pivoting
// solver); a zero last pivot after pivots of one sign is a singular factor, kSingular. The solver never reads the
// assembled matrix: it is constructed with the operator, and uses op.matrix (when given) only for
// the size check and the residual of the LinearSolver life cycle.
// Based on: R. E. Lynch, J. R. Rice & D. H. Thomas, Direct solution of partial difference equations
// by tensor product methods, Numer. Math. 6 (1964) 185–199; G. H. Golub & C. F. Van Loan,
// Matrix Computations, §4.3 (banded LDLᵀ).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "linear_solver.h"
#include "stencil_operator.h"

namespace coons::solvers {

struct SeparableBandedOperator {
  int rows = 0;                            //!< grid points along i
  int cols = 0;                            //!< grid points along j
  std::array<double, 3> along_i{1, 0, 0};  //!< p0, p1, p2: diagonal and the two off-diagonals of P
  std::array<double, 3> along_j{1, 0, 0};  //!< q0, q1, q2 of Q

  [[nodiscard]] Eigen::Index size() const { return Eigen::Index(rows) * cols; }
};

//! The assembled operator (#size by #size, compressed, column-major): for tests and references.
Eigen::SparseMatrix<double> separable_banded_matrix(const SeparableBandedOperator& op);

//! LDLᵀ of a symmetric pentadiagonal Toeplitz matrix of size k: L unit lower with two
//! sub-diagonals l1 (#k−1), l2 (#k−2), D = d (#k).
struct BandedLdlt {
  Eigen::VectorXd d, l1, l2;
};

//! kSuccess when the factor is definite (pivots of one sign); kSingular when it is semidefinite
//! and singular (a zero last pivot); kNotApplicable when it is indefinite (LDLᵀ without pivoting
//! is then unsafe: pivots of both signs, or a zero pivot before the last).
SolveStatus banded_ldlt(const std::array<double, 3>& diagonals, int k, BandedLdlt& f);

//! X = A⁻¹ B (#size by 3) in one call (factorize and solve) on `threads` threads (1 without
//! OpenMP; the result does not depend on the count). B and X may not alias. A status of
//! banded_ldlt() other than kSuccess is returned as it is.
SolveStatus separable_banded_solve(const SeparableBandedOperator& op, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X,
                                   int threads = 1);

//! The same as a LinearSolver (name "separable-banded"): factorize ignores the values of op and
//! uses the operator given here; analyze reports kNotApplicable when op's size is not rows·cols.
std::unique_ptr<LinearSolver> make_separable_banded_solver(const SeparableBandedOperator& op,
                                                           const SolverOptions& options = {});

//! The registry's "separable-banded": reads the operator from op.grid (3×3 or 5×5, every point
//! free) or op.stencil at analyze/factorize; kNotApplicable when the stencil is not separable.
std::unique_ptr<LinearSolver> make_separable_banded(const SolverOptions& options = {});

//! The stencil as P ⊗ Q when it is separable (w(a, b) = u(a)·v(b) to 1e-12 relative, u and v
//! symmetric) and every grid point is free; nullopt otherwise.
std::optional<SeparableBandedOperator> separable_operator(const StencilOperator& grid);
//! The same for op.grid, else op.stencil; nullopt when op has neither.
std::optional<SeparableBandedOperator> separable_operator(const LinearOperator& op);

}  // namespace coons::solvers
