// The multigrid and GMRES backends behind the LinearSolver life cycle (one column of x, y, z at a
// time; iterations reported are the largest over the three):
//   mg      geometric multigrid V-cycles as a stationary iteration (multigrid.h), matrix-free;
//   mg-cg   conjugate gradients preconditioned by one symmetric V-cycle (symmetric stencils only);
//   gmres   restarted GMRES(50), right-preconditioned by a V-cycle when a grid operator is given,
//           else by an incomplete LU (ILUT) of the matrix; for nonsymmetric and indefinite systems.
// The grid operator is LinearOperator::grid (a 3×3 or 5×5 stencil with a free mask) or, without it,
// the 3×3 LinearOperator::stencil. mg and mg-cg report not_applicable for a matrix alone;
// analyze() does the checks, factorize() builds the hierarchy (Galerkin coarse operators, line
// factorisations) or the ILU.
// Based on: see multigrid.h and gmres.h.
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_mg(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_mg_cg(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_gmres(const SolverOptions& options);

}  // namespace coons::solvers
