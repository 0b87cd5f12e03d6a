// The multigrid and GMRES backends behind the LinearSolver life cycle (one column of x, y, z at a
// time; iterations reported are the largest over the three):
//   mg      geometric multigrid V-cycles as a stationary iteration (multigrid.h), matrix-free,
//           symmetric stencils only (one line sweep per side at radius 1, two at radius 2);
//   mg-cg   conjugate gradients preconditioned by one symmetric V-cycle (symmetric stencils only);
//   gmres   restarted GMRES(50), right-preconditioned by a V-cycle on a symmetric grid operator,
//           else by an incomplete LU (ILUT) of the matrix (assembled from the grid if not given):
//           for nonsymmetric and indefinite systems. Geometric multigrid with R = Pᵀ diverged on
//           an upwinded convection stencil from 127x127 on, where ILUT needed 7 to 13 iterations.
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
