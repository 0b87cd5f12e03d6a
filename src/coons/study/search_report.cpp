#include "search_report.h"

#include <functional>

#include "coons/io/net_json.h"
#include "coons/mask/mask_families.h"
#include "coons/study/sweep.h"

namespace coons {

using nlohmann::json;

const char* to_string(SearchParameter p) {
  switch (p) {
    case SearchParameter::kMu:
      return "mu";
    case SearchParameter::kAlphaGamma:
      return "alpha-gamma";
    case SearchParameter::kWeight:
      return "weight";
    case SearchParameter::kAlpha:
      break;
  }
  return "alpha";
}

json search_solver_block(const solvers::SolverInfo& solver, bool picked_automatically, SearchStatus status, int solves,
                         double seconds, const std::string& message) {
  const bool failed = status == SearchStatus::kSolverFailed || status == SearchStatus::kFailedRegion ||
                      status == SearchStatus::kNotApplicable;
  json block = {{"name", solver.name},
                {"status", failed ? "failure" : "success"},
                {"iterations", solves},
                {"relative_residual", nullptr},
                {"seconds", {{"search", seconds}}}};
  if (failed && !message.empty()) block["message"] = message;
  if (picked_automatically) block["picked_by"] = "auto";
  return block;
}

void add_search_fields(json& out, const AlphaSearchSummary& s, const std::function<double(double)>& shown,
                       const std::string& evaluator_when_unnamed) {
  out["flat"] = s.flat;
  out["at_bound"] = s.at_bound;
  out["evaluations"] = s.evaluations;
  out["solves"] = s.solves;
  out["status"] = to_string(s.status);
  if (!s.message.empty()) out["message"] = s.message;
  out["local_minima"] = s.local_minima;
  json scan = json::array();
  for (auto [p, f] : s.scan) scan.push_back({shown(p), number_or_null(f)});
  out["scan"] = scan;
  out["evaluator"] = s.evaluator.empty() ? evaluator_when_unnamed : s.evaluator;
  // the evaluations that failed, and where: no optimum is claimed on them
  out["failed_evaluations"] = s.failed_evaluations;
  json intervals = json::array();
  for (auto [lo, hi] : s.failed_intervals) intervals.push_back({shown(lo), shown(hi)});
  out["failed_intervals"] = intervals;
  if (s.failed_evaluations > 0) out["first_failure"] = solvers::to_string(s.first_failure);
}

json search_report(const Boundary& b, const std::string& objective, SearchParameter parameter, const MaskFamily& family,
                   const AlphaSearchOptions& options, const AlphaSearchSummary& s,
                   const std::optional<MuScale>& mu_scale) {
  const bool by_mu = parameter == SearchParameter::kMu;
  const MuScale scale = mu_scale.value_or(
      MuScale{b.m, b.n, mu_of_compressed(b.m, b.n, options.lower), mu_of_compressed(b.m, b.n, options.upper)});
  json out;
  out["boundary"] = b.name;
  out["degree"] = {b.m, b.n};
  out["objective"] = objective;
  out["parameter"] = to_string(parameter);
  std::optional<double> alpha, mu;
  if (s.parameter) {
    const MaskPoint p = family(*s.parameter);
    alpha = p.mask.diag;
    mu = by_mu ? std::optional<double>(scale.mu(*s.parameter)) : mu_of_alpha(b, alpha);
    out["beta"] = p.mask.edge_i == p.mask.edge_j ? json(p.mask.edge_i) : json(nullptr);
    if (p.mask.edge_i != p.mask.edge_j) out["beta_ij"] = {p.mask.edge_i, p.mask.edge_j};
  }
  out["alpha"] = alpha ? json(*alpha) : json(nullptr);
  out["mu"] = mu ? json(*mu) : json(nullptr);
  out["value"] = number_or_null(s.value);
  if (by_mu)
    out["bounds"] = {scale.lower, scale.upper};
  else
    out["bounds"] = {options.lower, options.upper};
  add_search_fields(out, s, [&](double p) { return by_mu ? scale.mu(p) : p; });
  return out;
}

json weight_search_report(const Boundary& b, const std::string& objective, const AlphaSearchOptions& options,
                          const AlphaSearchSummary& s) {
  json out;
  out["boundary"] = b.name;
  out["degree"] = {b.m, b.n};
  out["objective"] = objective;
  out["parameter"] = to_string(SearchParameter::kWeight);
  out["mask"] = "c1-family";
  out["weight"] = s.parameter ? json(*s.parameter) : json(nullptr);
  out["alpha"] = nullptr;  // the contract's fields of every search report: this one is not over α
  out["mu"] = nullptr;
  out["value"] = number_or_null(s.value);
  out["bounds"] = {options.lower, options.upper};
  add_search_fields(out, s, [](double p) { return p; });
  return out;
}

json alpha_gamma_report(const Boundary& b, const std::string& objective, const AlphaSearchOptions& options,
                        const AlphaGammaSummary& g) {
  json out = {{"boundary", b.name},
              {"degree", {b.m, b.n}},
              {"objective", objective},
              {"parameter", "alpha-gamma"},
              {"alpha", g.flat ? json(nullptr) : json(g.alpha)},
              {"gamma", g.flat ? json(nullptr) : json(g.gamma)},
              {"beta_ij", g.flat ? json(nullptr) : json({0.25 - g.alpha + g.gamma, 0.25 - g.alpha - g.gamma})},
              {"mu", nullptr},
              {"value", number_or_null(g.value)},
              {"value_at_gamma0", number_or_null(g.value_at_gamma0)},
              {"bounds", {options.lower, options.upper}},
              {"flat", g.flat},
              {"at_bound", g.at_bound},
              {"evaluations", g.evaluations},
              {"solves", g.solves},
              {"status", to_string(g.status)}};
  if (!g.message.empty()) out["message"] = g.message;
  return out;
}

}  // namespace coons
