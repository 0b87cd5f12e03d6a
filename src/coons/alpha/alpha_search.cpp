#include "alpha_search.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

#include "coons/alpha/search_run.h"
#include "coons/config.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif
#include "solvers/registry.h"

namespace coons {

bool AlphaSearchOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower < upper))
    return fail("bounds must be finite with lower < upper");
  if (scan_points < 3) return fail("scan_points must be at least 3");
  if (!(flat_tolerance > 0)) return fail("flat_tolerance must be positive");
  if (!(parameter_tolerance > 0)) return fail("parameter_tolerance must be positive");
  if (max_iterations < 1) return fail("max_iterations must be at least 1");
  return true;
}

const char* to_string(SearchStatus s) {
  switch (s) {
    case SearchStatus::kSuccess:
      return "success";
    case SearchStatus::kFlat:
      return "flat";
    case SearchStatus::kSolverFailed:
      return "solver_failed";
    case SearchStatus::kNotConverged:
      return "not_converged";
    case SearchStatus::kFailedRegion:
      return "failed_region";
    case SearchStatus::kNotApplicable:
      return "not_applicable";
  }
  return "solver_failed";
}

std::string AlphaSearchSummary::brief_report() const {
  std::ostringstream out;
  out << to_string(status);
  if (parameter) out << ": optimum " << *parameter << ", value " << value;
  if (flat) out << " (flat objective)";
  if (at_bound) out << " (at a bound)";
  if (failed_evaluations > 0) out << ", " << failed_evaluations << " failed evaluation(s)";
  out << ", " << evaluations << " evaluations, " << solves << " solves, " << seconds << " s";
  if (!message.empty()) out << "; " << message;
  return out.str();
}

AlphaSearchSummary search_mask_parameter(MaskObjective& objective, const AlphaSearchOptions& options) {
  return detail::search_impl(objective, options);
}

namespace {
// The fallback of search_alpha and search_mu: a factorisation and solves per evaluation.
AlphaSearchSummary search_by_solving(const Boundary& boundary, const Objective& objective, MaskFamily family,
                                     const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                     const solvers::SolverOptions& solver_options) {
  MaskObjective f(boundary, objective, std::move(family), solver, solver_options);
  AlphaSearchSummary s = detail::search_impl(f, options);
  s.evaluator = "factorize and solve";
  return s;
}
}  // namespace

AlphaSearchSummary search_alpha(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                                const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options) {
#if COONS_HAVE_FFTW
  const solvers::SolverInfo* info = &solver;
  if (info && info->family == solvers::SolverFamily::kStructured && boundary.m >= 2 && boundary.n >= 2 &&
      SpectralAlphaObjective::supports(objective)) {
    SpectralAlphaSearchObjective f(boundary, objective);
    AlphaSearchSummary s = detail::search_impl(f, options);
    s.evaluator = "sine basis";
    return s;
  }
#endif
  return search_by_solving(
      boundary, objective, [](double a) { return alpha_family(a); }, solver, options, solver_options);
}

AlphaSearchSummary search_mu(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                             const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options) {
  if (boundary.m == boundary.n) {
    AlphaSearchOptions on_alpha = options;
    on_alpha.lower = (options.lower - 1) / 4;
    on_alpha.upper = (options.upper - 1) / 4;
    AlphaSearchSummary s = search_alpha(boundary, objective, solver, on_alpha, solver_options);
    if (s.parameter) s.parameter = 1 + 4 * *s.parameter;
    for (auto& point : s.scan) point.first = 1 + 4 * point.first;
    for (auto& run : s.failed_intervals) run = {1 + 4 * run.first, 1 + 4 * run.second};
    if (!s.message.empty()) s.message += " (parameters in this message are alpha = (s - 1)/4)";
    return s;
  }
  return search_by_solving(
      boundary, objective, [m = boundary.m, n = boundary.n](double t) { return mu_family_compressed(m, n, t); }, solver,
      options, solver_options);
}

#if COONS_HAVE_FFTW
AlphaSearchSummary search_mask_parameter(SpectralAlphaSearchObjective& objective, const AlphaSearchOptions& options) {
  return detail::search_impl(objective, options);
}
#endif

}  // namespace coons
