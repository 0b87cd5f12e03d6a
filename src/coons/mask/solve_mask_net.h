// Fill the interior of a boundary with the solution of a 3×3 mask system, with any backend of the
// solver registry: assemble (matrix only if the backend needs it), analyze, factorize, solve.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <string>

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

struct MaskSolveResult {
  ControlNet net;                 //!< the boundary with the solved interior (zeros on failure)
  solvers::SolveSummary summary;  //!< status, iterations, residual, seconds
};

//! `solver` is a backend of the registry (solvers::available_solvers(); names are looked up at the edge).
MaskSolveResult solve_mask_net(const Boundary& boundary, const Mask9& mask, const solvers::SolverInfo& solver,
                               const solvers::SolverOptions& options = {});

}  // namespace coons
