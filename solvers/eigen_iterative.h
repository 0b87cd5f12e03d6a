// Eigen's Krylov solvers behind the LinearSolver life cycle (one column of x, y, z at a time):
//   cg          ConjugateGradient, no preconditioner
//   cg-jacobi   ConjugateGradient, diagonal preconditioner
//   cg-ic       ConjugateGradient, incomplete Cholesky (IncompleteCholesky, AMD)
//   bicgstab    BiCGSTAB with an incomplete LU (IncompleteLUT)
// CG needs a positive definite operator: when the grid stencil is known, its exact smallest
// eigenvalue is checked in factorize and a non-positive one is reported, not iterated on.
// Iterations per column are limited by iteration_limit(options, #unknowns, 20, 2e10) and, when
// SolverOptions::time_limit_seconds is set, by the clock (read between chunks of iterations that
// double from 1000). Above the automatic limit or under a time limit, a column whose true
// residual, at most 1e-9, has not fallen by 10 % over three chunks stops as stagnated
// (not_converged) with its lowest iterate.
// Based on: M. R. Hestenes, E. Stiefel, Methods of conjugate gradients for solving linear systems,
// J. Res. NBS 49 (1952); H. A. van der Vorst, Bi-CGSTAB, SIAM J. Sci. Stat. Comput. 13 (1992).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_cg(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_cg_jacobi(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_cg_ic(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_bicgstab(const SolverOptions& options);

}  // namespace coons::solvers
