// Eigen's Krylov solvers behind the LinearSolver life cycle (one column of x, y, z at a time):
//   cg          ConjugateGradient, no preconditioner
//   cg-jacobi   ConjugateGradient, diagonal preconditioner
//   cg-ic       ConjugateGradient, incomplete Cholesky (IncompleteCholesky, AMD)
//   bicgstab    BiCGSTAB with an incomplete LU (IncompleteLUT)
// CG needs a positive definite operator: when the grid stencil is known, its exact smallest
// eigenvalue is checked in factorize and a non-positive one is reported, not iterated on.
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

//! The iteration limit an iterative backend uses: options.max_iterations, or when that is 0,
//! a limit that grows with the number of unknowns (CG needs O(N²) at α = −1/4 on an N×N grid).
//! `per_unknown` sets the growth (the stationary mask iterations need far more sweeps than CG).
int iteration_limit(const SolverOptions& options, Eigen::Index unknowns, int per_unknown = 20);

}  // namespace coons::solvers
