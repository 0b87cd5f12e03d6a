#include "family_search.h"

#include <string>
#include <utility>

#include "coons/alpha/search_impl.h"
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

namespace {

// The one run of both searches: refused (kNotApplicable, nothing evaluated) on invalid options, a
// problem the family's stencil does not fit (`representative` has every member's support and a
// definite symbol, so one check covers the family) or a backend without the matrix.
AlphaSearchSummary search_family(const StencilProblem& problem, const Objective& objective,
                                 const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                 const std::string& options_error, const Stencil& representative, StencilFamily family,
                                 const solvers::SolverOptions& solver_options) {
  AlphaSearchSummary refused;
  refused.status = SearchStatus::kNotApplicable;
  refused.evaluator = "factorize and solve";
  if (!options_error.empty()) {  // (is_valid always names its reason)
    refused.message = "options: " + options_error;
    return refused;
  }
  const std::vector<ProblemIssue> issues = check_stencil_problem(problem, representative);
  if (!issues.empty()) {
    refused.message = issues.front().field + ": " + issues.front().reason;
    return refused;
  }
  if (!solvers::accepts_matrix(solver)) {
    refused.message = "solver: " + solver.name + " does not solve from the matrix; this search needs one";
    return refused;
  }
  StencilFamilyObjective f(problem, objective, solver, solver_options, std::move(family));
  AlphaSearchSummary s = detail::search_impl(f, options);
  s.evaluator = "factorize and solve";
  return s;
}

}  // namespace

AlphaSearchSummary search_weight(const StencilProblem& problem, const Objective& objective,
                                 const solvers::SolverInfo& solver, const WeightSearchOptions& options,
                                 const solvers::SolverOptions& solver_options) {
  std::string why;
  if (options.is_valid(&why)) why.clear();
  return search_family(problem, objective, solver, options.search, why, c1_family_stencil(0.5), c1_weight_family(),
                       solver_options);
}

AlphaSearchSummary search_alpha_on_problem(const StencilProblem& problem, const Objective& objective,
                                           const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                           const solvers::SolverOptions& solver_options) {
  std::string why;
  if (options.is_valid(&why)) why.clear();
  return search_family(problem, objective, solver, options, why, alpha_stencil(alpha_mask(-0.1)),
                       alpha_stencil_family(), solver_options);
}

}  // namespace coons
