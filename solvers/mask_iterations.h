// The classical mask iterations of the literature, matrix-free on the grid stencil:
//   jacobi        replace every point by its mask average at once;
//   gauss-seidel  sweep the grid in order, using new values at once, with over-relaxation
//                 factor ω = SolverOptions::sor_omega (ω = 1: Gauss–Seidel, 1 < ω < 2: SOR).
// Jacobi diverges for every α < 0 on large enough grids (docs/math.md §3): the iteration watches its
// residual and stops with status `diverged` once it has grown 10⁸-fold (or ends above where it
// started), so it never loops on or prints NaN. Gauss–Seidel converges on every positive definite
// system, slowly (O(N²) sweeps at α = −1/4). Both stop at iteration_limit(options, #unknowns,
// 1000, 1e8) sweeps (64×64 net: 26,000) or at SolverOptions::time_limit_seconds (the clock is
// read every 10 sweeps) with status `not_converged` and the residual reached, and earlier when the
// residual, at most 1e-9, has set no new low for max(1000, 10·(rows + cols)) sweeps (stagnated at
// the rounding floor, e.g. under a tolerance of 1e-300).
// Based on: R. S. Varga, Matrix Iterative Analysis, Prentice-Hall (1962); G. Farin, D. Hansford,
// Discrete Coons patches, CAGD 16 (1999).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_jacobi(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_gauss_seidel(const SolverOptions& options);

}  // namespace coons::solvers
