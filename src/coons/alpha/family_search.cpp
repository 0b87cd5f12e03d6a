#include "family_search.h"

#include "coons/alpha/search_run.h"
#include "coons/alpha/stencil_family_objective.h"
#include "coons/mask/mask9.h"
#include "coons/mask/stencil.h"

namespace coons {

bool WeightSearchOptions::is_valid(std::string* why) const {
  if (!search.is_valid(why)) return false;
  if (!(search.lower >= 0 && search.upper <= 1)) {
    if (why) *why = "the C1 family's weight is searched in [0, 1]";
    return false;
  }
  return true;
}

AlphaSearchSummary search_weight(const StencilProblem& problem, const Objective& objective,
                                 const solvers::SolverInfo& solver, const WeightSearchOptions& options,
                                 const solvers::SolverOptions& solver_options) {
  AlphaSearchSummary refused;
  refused.status = SearchStatus::kNotApplicable;
  refused.evaluator = "factorize and solve";
  if (std::string why; !options.is_valid(&why)) {
    refused.message = "options: " + why;
    return refused;
  }
  // every w has the same support and a symbol ≥ 0 (stencil.h), so one check covers the family
  const std::vector<ProblemIssue> issues = check_stencil_problem(problem, c1_family_stencil(0.5));
  if (!issues.empty()) {
    refused.message = issues.front().field + ": " + issues.front().reason;
    return refused;
  }
  if (!solver.needs_matrix) {
    refused.message = "solver: " + solver.name + " does not solve from the matrix; the 5x5 stencil needs one";
    return refused;
  }
  StencilFamilyObjective f(problem, objective, solver, solver_options);
  AlphaSearchSummary s = detail::search_impl(f, options.search);
  s.evaluator = "factorize and solve";
  return s;
}

AlphaSearchSummary search_alpha_on_problem(const StencilProblem& problem, const Objective& objective,
                                           const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                           const solvers::SolverOptions& solver_options) {
  AlphaSearchSummary refused;
  refused.status = SearchStatus::kNotApplicable;
  refused.evaluator = "factorize and solve";
  if (std::string why; !options.is_valid(&why)) {
    refused.message = "options: " + why;
    return refused;
  }
  // every α has the 3×3 support, so one check covers the family (and α = −0.1 is definite)
  const std::vector<ProblemIssue> issues = check_stencil_problem(problem, alpha_stencil(alpha_mask(-0.1)));
  if (!issues.empty()) {
    refused.message = issues.front().field + ": " + issues.front().reason;
    return refused;
  }
  if (!solver.needs_matrix) {
    refused.message = "solver: " + solver.name + " does not solve from the matrix; this search needs one";
    return refused;
  }
  StencilFamilyObjective f(problem, objective, solver, solver_options, alpha_stencil_family());
  AlphaSearchSummary s = detail::search_impl(f, options);
  s.evaluator = "factorize and solve";
  return s;
}

}  // namespace coons
