// Fill the interior of a boundary with the solution of a 3×3 mask system, with any backend of the
// solver registry: assemble (matrix only if the backend needs it), analyze, factorize, solve.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <string>

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

struct MaskSolveResult {
  ControlNet net;                 //!< the boundary with the solved interior (zeros on failure)
  solvers::SolveSummary summary;  //!< status, iterations, residual, seconds
};

//! Precondition: `solver` names a registered backend (see solvers::find_solver).
MaskSolveResult solve_mask_net(const Boundary& boundary, const Mask9& mask,
                               const std::string& solver,
                               const solvers::SolverOptions& options = {});

}  // namespace coons
