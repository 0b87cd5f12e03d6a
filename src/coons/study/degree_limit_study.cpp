#include "degree_limit_study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "coons/io/boundary_curves.h"
#include "coons/io/net_json.h"
#include "coons/mask/mask9.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/backend_choice.h"
#include "coons/study/sweep.h"

namespace coons {

using nlohmann::json;

bool DegreeLimitStudyOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  auto increasing = [&](const std::vector<int>& v, int lo, int hi, const char* what) {
    for (size_t k = 0; k < v.size(); ++k) {
      if (v[k] < lo || v[k] > hi) return fail(fmt::format("{}: {} is outside [{}, {}]", what, v[k], lo, hi));
      if (k > 0 && v[k] <= v[k - 1]) return fail(fmt::format("{} must be increasing, each once", what));
    }
    return true;
  };
  if (degrees.empty()) return fail("no degrees");
  if (!increasing(degrees, 2, 200, "degrees") || !increasing(continuum_degrees, 2, 80, "continuum degrees"))
    return false;
  if (spread_from > spread_to) return fail("spread_from must not exceed spread_to");
  if (!limit.is_valid(why) || !continuum.is_valid(why)) return false;
  return true;
}

std::optional<double> mu_of_alpha(int n, double alpha) {
  if (!(alpha > -0.25 && alpha < -kAlphaZeroWithinRounding)) return std::nullopt;
  return -double(n) * n * (1 + 4 * alpha) / (4 * alpha);
}

const char* to_string(DegreeOptimum kind) {
  switch (kind) {
    case DegreeOptimum::kInterior:
      return "interior";
    case DegreeOptimum::kFlat:
      return "flat";
    case DegreeOptimum::kAtBound:
      return "at_bound";
    case DegreeOptimum::kFailed:
      return "failed";
  }
  return "unknown";
}

namespace {

bool exact_terms_only(const Objective& o) { return o.discrete.empty() && o.target_weight == 0 && !o.energy.empty(); }

Spread spread_of(const std::vector<std::pair<int, double>>& values, const DegreeLimitStudyOptions& options) {
  Spread s;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (auto [n, v] : values)
    if (n >= options.spread_from && n <= options.spread_to) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      s.from = s.points == 0 ? n : std::min(s.from, n);
      s.to = std::max(s.to, n);
      ++s.points;
    }
  if (s.points >= 2 && lo > 0) s.ratio = hi / lo;
  return s;
}

json optional_int(const std::optional<int>& x) { return x ? json(*x) : json(nullptr); }

}  // namespace

std::vector<int> unreachable_degrees(const StudyInput& input, const std::vector<int>& degrees) {
  std::vector<int> out;
  for (int d : degrees)
    if (!input.curves && (d < input.boundary.m || d < input.boundary.n)) out.push_back(d);
  return out;
}

std::string unreachable_reason(const StudyInput& input) {
  return fmt::format(
      "below the boundary's degree {}x{} in u or v, and it has no \"curves\" to refit from (degree elevation "
      "only raises)",
      input.boundary.m, input.boundary.n);
}

DegreeLimitEntry run_degree_limit(const StudyInput& input, const Objective& objective,
                                  const DegreeLimitStudyOptions& options) {
  DegreeLimitEntry e;
  e.boundary = input.boundary.name;
  e.objective = objective.name;
  // Every boundary first, so that a refit that fails is an input error before any search.
  std::map<int, std::pair<Boundary, std::optional<double>>> at;
  auto boundary_at = [&](int d) {
    if (input.curves) {
      const FittedBoundary f = fit_boundary_or_throw(*input.curves, d, d, input.boundary.name, input.file);
      at.emplace(d, std::make_pair(f.boundary, std::optional<double>(f.max_deviation)));
    } else if (d >= input.boundary.m && d >= input.boundary.n) {
      at.emplace(d, std::make_pair(elevate_boundary(input.boundary, d, d), std::optional<double>()));
    }
  };
  for (int d : options.degrees) boundary_at(d);
  for (int d : options.continuum_degrees)
    if (!at.count(d)) boundary_at(d);
  e.skipped_degrees = unreachable_degrees(input, options.degrees);
  e.skipped_continuum_degrees = unreachable_degrees(input, options.continuum_degrees);
  if (!e.skipped_degrees.empty() || !e.skipped_continuum_degrees.empty()) e.skipped_reason = unreachable_reason(input);

  std::vector<std::pair<int, double>> mus, exact_mus, galerkin_mus;
  for (int d : options.degrees) {
    if (!at.count(d)) continue;
    const auto& [b, deviation] = at.at(d);
    const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
    DegreeLimitCell cell;
    cell.degree = d;
    cell.max_deviation = deviation;
    cell.alpha = search_alpha(b, objective, solver);
    const AlphaSearchSummary& s = cell.alpha;
    if (s.flat) {
      cell.kind = DegreeOptimum::kFlat;
    } else if (!s.parameter || s.status != SearchStatus::kSuccess) {
      cell.kind = DegreeOptimum::kFailed;
    } else {
      // interior unless on a bound; μ* only for −1/4 < α* < 0 (an interior α* ≥ 0 has none)
      cell.kind = s.at_bound ? DegreeOptimum::kAtBound : DegreeOptimum::kInterior;
      cell.mu = s.at_bound ? std::nullopt : mu_of_alpha(d, *s.parameter);
    }
    if (cell.mu) mus.emplace_back(d, *cell.mu);
    if (cell.kind == DegreeOptimum::kInterior && d <= options.exact_mu_max_degree) {
      const MaskSolveResult net = solve_mask_net(b, alpha_mask(*s.parameter), solver);
      if (net.summary.status == solvers::SolveStatus::kSuccess) cell.exact_mu = exact_energy_mu(net.net);
      if (cell.exact_mu && *cell.exact_mu > 0) exact_mus.emplace_back(d, *cell.exact_mu);
    }
    if (exact_terms_only(objective) && d <= options.exact_mu_max_degree) {
      cell.galerkin = continuum_optimum(ContinuumProblem(b), objective.energy, options.continuum);
      if (cell.galerkin->mu) galerkin_mus.emplace_back(d, *cell.galerkin->mu);
    }
    e.cells.push_back(std::move(cell));
  }
  e.limit = fit_degree_limit(mus, options.limit);
  if (exact_terms_only(objective)) {
    for (int d : options.continuum_degrees)
      if (at.count(d))
        e.continuum.push_back(continuum_optimum(ContinuumProblem(at.at(d).first), objective.energy, options.continuum));
    if (e.continuum.empty() && !options.continuum_degrees.empty())
      e.continuum_unavailable = "every continuum degree asked for is " + *e.skipped_reason;
  } else {
    e.continuum_unavailable = "the objective is not a sum of exact energies E(a, b)";
  }
  e.mu_spread = spread_of(mus, options);
  e.exact_mu_spread = spread_of(exact_mus, options);
  e.galerkin_spread = spread_of(galerkin_mus, options);
  return e;
}

ContinuumSummary continuum_summary(const DegreeLimitEntry& entry) {
  ContinuumSummary s;
  std::optional<double> before;
  for (const ContinuumOptimum& c : entry.continuum) {
    if (!c.mu) continue;
    if (s.mu) before = s.mu;
    s.mu = c.mu;
    s.degree = c.degree;
  }
  if (s.mu && before) s.change = std::abs(*s.mu - *before);
  return s;
}

namespace {

// Why the limit is not claimed, or the fit's own note: a limit whose error estimate exceeds the
// claim's threshold has no message of the fit's.
json limit_message(const DegreeLimitResult& r) {
  if (!r.message.empty()) return r.message;
  if (r.status == DegreeLimitStatus::kSuccess && r.limit && r.limit_error && !limit_claimed(r))
    return fmt::format("the error estimate {:.3g} is above {:g} % of the limit {:.6g}", *r.limit_error,
                       100 * kLimitClaimError, *r.limit);
  return nullptr;
}

}  // namespace

json degree_limit_json(const DegreeLimitEntry& e) {
  json degrees = json::array(), alpha = json::array(), mu = json::array(), kind = json::array(),
       exact_mu = json::array(), galerkin = json::array(), deviation = json::array();
  for (const DegreeLimitCell& c : e.cells) {
    degrees.push_back(c.degree);
    alpha.push_back(c.kind == DegreeOptimum::kInterior || c.kind == DegreeOptimum::kAtBound
                        ? optional_number(c.alpha.parameter)
                        : json(nullptr));
    mu.push_back(optional_number(c.mu));
    kind.push_back(to_string(c.kind));
    exact_mu.push_back(optional_number(c.exact_mu));
    galerkin.push_back(c.galerkin ? optional_number(c.galerkin->mu) : json(nullptr));
    deviation.push_back(optional_number(c.max_deviation));
  }
  json fits = json::array();
  for (const LimitFit& f : e.limit.fits) {
    json parameters = json::object();
    for (const auto& [name, value] : f.parameters) parameters[name] = number_or_null(value);
    json fit = {
        {"form", f.form}, {"parameters", parameters}, {"residual", number_or_null(f.residual)}, {"points", f.points}};
    if (!f.parameters.empty() && f.parameters.back().first == "p") fit["p_at_bound"] = f.at_bound;
    fits.push_back(std::move(fit));
  }
  json rates = json::array();
  for (auto [n, p] : e.limit.rates) rates.push_back({{"degree", n}, {"rate", number_or_null(p)}});
  json continuum = json::array();
  for (const ContinuumOptimum& c : e.continuum)
    continuum.push_back({{"degree", c.degree},
                         {"mu", optional_number(c.mu)},
                         {"status", to_string(c.status)},
                         {"value", number_or_null(c.value)}});
  const ContinuumSummary cs = continuum_summary(e);
  auto spread = [](const Spread& s) {
    return json{{"max_over_min", optional_number(s.ratio)},
                {"points", s.points},
                {"from", s.points > 0 ? json(s.from) : json(nullptr)},
                {"to", s.points > 0 ? json(s.to) : json(nullptr)}};
  };
  json out = {{"boundary", e.boundary},
              {"objective", e.objective},
              {"degrees", degrees},
              {"optimum", kind},
              {"alpha_star", alpha},
              {"mu_star", mu},
              {"max_deviation", deviation},
              {"limit_status", to_string(e.limit.status)},
              {"limit_claimed", limit_claimed(e.limit)},
              {"limit_message", limit_message(e.limit)},
              {"mu_limit", optional_number(e.limit.limit)},
              {"mu_limit_error", optional_number(e.limit.limit_error)},
              {"rate", optional_number(e.limit.rate)},
              {"rates", rates},
              {"fits", fits},
              // names fixed by docs/formats.md for the default tolerances {0.05, 0.01}
              {"within_5_percent_from", e.limit.within_from.size() > 0 ? optional_int(e.limit.within_from[0]) : json()},
              {"within_1_percent_from", e.limit.within_from.size() > 1 ? optional_int(e.limit.within_from[1]) : json()},
              {"exact_mu", exact_mu},
              {"galerkin_mu", galerkin},
              {"continuum", continuum},
              {"mu_continuum", optional_number(cs.mu)},
              {"mu_continuum_change", optional_number(cs.change)},
              {"spread",
               {{"mu_star", spread(e.mu_spread)},
                {"exact_mu", spread(e.exact_mu_spread)},
                {"galerkin_mu", spread(e.galerkin_spread)}}}};
  if (e.continuum_unavailable) out["continuum_unavailable"] = *e.continuum_unavailable;
  if (e.skipped_reason) {
    out["skipped_degrees"] = e.skipped_degrees;
    out["skipped_continuum_degrees"] = e.skipped_continuum_degrees;
    out["skipped_reason"] = *e.skipped_reason;
  }
  return out;
}

}  // namespace coons
