#include "backend_choice.h"

#include <algorithm>
#include <stdexcept>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "solvers/registry.h"

namespace coons {

namespace {

// The operator the α searches solve, on the interior of `b` (a member inside the family's range).
solvers::GridStencil alpha_family_stencil(const Boundary& b) {
  return mask_stencil(alpha_mask(-0.1), std::max(b.m - 1, 1), std::max(b.n - 1, 1));
}

}  // namespace

SearchBackendCheck check_search_backend(const solvers::SolverInfo& requested, const Boundary& b, bool indefinite) {
  if (indefinite && requested.definite_only)
    return {false,
            requested.name + " needs a positive definite system; bounds outside [-0.25, 0.25] need another solver"};
  if (!requested.needs_matrix) {
    // a grid-stencil backend must take a member of the 3x3 family: otherwise a search through it
    // would fail at every evaluation or be answered by another evaluator under its name
    solvers::LinearOperator op;
    op.stencil = alpha_family_stencil(b);
    const auto solver = solvers::make_solver(requested.name);
    if (solver && solver->analyze(op) == solvers::SolveStatus::kNotApplicable)
      return {false, requested.name + " does not solve the 3x3 alpha family (" + solver->summary().message + ")"};
  }
  return {true, {}};
}

const solvers::SolverInfo& search_backend(const solvers::SolverInfo* requested, const Boundary& b, bool indefinite) {
  if (requested) {
    if (const SearchBackendCheck check = check_search_backend(*requested, b, indefinite); !check.applicable)
      throw std::invalid_argument("search_backend: " + check.reason + " (check_search_backend before searching)");
    return *requested;
  }
  const solvers::SolverInfo* pick = solvers::find_solver(solvers::choose_auto_solver(alpha_family_stencil(b)));
  if (pick && (!indefinite || !pick->definite_only)) return *pick;
  return solvers::default_matrix_solver(false);
}

SearchBackendCheck check_weight_search_backend(const solvers::SolverInfo& requested) {
  if (solvers::accepts_matrix(requested)) return {true, {}};
  return {false, requested.name +
                     " works from the grid stencil only; the search refills one assembled system per evaluation and "
                     "needs a backend that works from that matrix (e.g. cholmod, eigen-ldlt, gmres)"};
}

const solvers::SolverInfo& weight_search_backend(const solvers::SolverInfo* requested) {
  if (requested && solvers::accepts_matrix(*requested)) return *requested;
  return solvers::default_matrix_solver(true);
}

}  // namespace coons
