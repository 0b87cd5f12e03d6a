#include "backend_choice.h"

#include <algorithm>

#include "coons/io/input_error.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "solvers/registry.h"

namespace coons {

const solvers::SolverInfo& search_backend(const solvers::SolverInfo* requested, const Boundary& b, bool indefinite) {
  if (!requested) {
    const auto stencil = mask_stencil(alpha_mask(-0.1), std::max(b.m - 1, 1), std::max(b.n - 1, 1));
    const solvers::SolverInfo* pick = solvers::find_solver(solvers::choose_auto_solver(stencil));
    if (pick && (!indefinite || !pick->definite_only)) return *pick;
    return *solvers::find_solver("eigen-lu");
  }
  if (indefinite && requested->definite_only)
    throw InputError(
        "command line", "--solver",
        requested->name + " needs a positive definite system; bounds outside [-0.25, 0.25] need another solver");
  if (!requested->needs_matrix) {
    // a grid-stencil backend must take a member of the 3x3 family (alpha = -0.1): separable-banded
    // takes only alpha = -1/4 and fast5 only 5x5 stencils, so a search through them would either
    // fail at every evaluation or be answered by another evaluator under their name
    const auto stencil = mask_stencil(alpha_mask(-0.1), std::max(b.m - 1, 1), std::max(b.n - 1, 1));
    solvers::LinearOperator op;
    op.stencil = stencil;
    const auto solver = solvers::make_solver(requested->name);
    if (solver && solver->analyze(op) == solvers::SolveStatus::kNotApplicable)
      throw InputError("command line", "--solver",
                       requested->name + " does not solve the 3x3 alpha family (" + solver->summary().message + ")");
  }
  return *requested;
}

const solvers::SolverInfo& weight_search_backend(const solvers::SolverInfo* requested, bool fallback) {
  if (requested && solvers::accepts_matrix(*requested)) return *requested;
  if (requested && !fallback)
    throw InputError(
        "command line", "--solver",
        requested->name +
            " works from the grid stencil only; the search refills one assembled system per evaluation and "
            "needs a backend that works from that matrix (e.g. cholmod, eigen-ldlt, gmres)");
  const solvers::SolverInfo* cholmod = solvers::find_solver("cholmod");
  return cholmod ? *cholmod : *solvers::find_solver("eigen-ldlt");
}

}  // namespace coons
