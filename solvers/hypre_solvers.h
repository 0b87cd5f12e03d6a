// The hypre backends (built with hypre and MPI only), behind the LinearSolver life cycle. Each
// solves the three columns one after another with one set-up; iterations reported are the largest
// over the columns, the residual the true one of the whole solution.
//   hypre-amg   BoomerAMG (one V-cycle, HMIS coarsening, symmetric hybrid Gauss-Seidel) as the
//               preconditioner of PCG when the matrix is symmetric and not known to be indefinite,
//               of GMRES(50) otherwise; on the assembled matrix, through the IJ interface.
//   hypre-pfmg  PCG preconditioned by one PFMG V-cycle (semicoarsening, Galerkin coarse grids,
//               weighted Jacobi), on the grid stencil through the Struct interface;
//   hypre-smg   the same with one SMG V-cycle (semicoarsening with line solves: more robust for
//               anisotropy, costlier per iteration).
// Struct backends take LinearOperator::grid (3×3 or 5×5 weights) or else the 3×3 stencil; the
// points of a free mask's fixed set become identity rows with zero right-hand side and zero
// couplings (the free unknowns' system is unchanged, still symmetric). Symmetric stencils only.
// Under mpirun every rank calls the backend with the whole operator; each rank hands hypre its
// block of matrix rows (grid rows for Struct) and every rank gets the whole solution back.
// Based on: R. D. Falgout, U. M. Yang, hypre: a library of high performance preconditioners,
// ICCS 2002; S. F. Ashby, R. D. Falgout, A parallel multigrid preconditioned conjugate gradient
// algorithm for groundwater flow simulations, Nucl. Sci. Eng. 124 (1996) (PFMG).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

std::unique_ptr<LinearSolver> make_hypre_amg(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_hypre_pfmg(const SolverOptions& options);
std::unique_ptr<LinearSolver> make_hypre_smg(const SolverOptions& options);

}  // namespace coons::solvers
