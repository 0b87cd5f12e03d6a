#include "coons/study/alpha_family.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "coons/alpha/alpha_search.h"
#include "coons/io/net_json.h"
#include "coons/io/plot.h"
#include "coons/mask/mask_families.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/backend_choice.h"
#include "coons/study/degree_limit_study.h"
#include "coons/study/study.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif

namespace coons {

using nlohmann::json;

bool AlphaFamilyOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (!generator.is_valid(why)) return false;
  if (degrees.empty()) return fail("no degrees");
  for (size_t k = 0; k < degrees.size(); ++k) {
    if (degrees[k] < generator.side_degree || degrees[k] > 200)
      return fail(fmt::format("degree {} is outside [{}, 200] (the sides have degree {})", degrees[k],
                              generator.side_degree, generator.side_degree));
    if (k > 0 && degrees[k] <= degrees[k - 1]) return fail("degrees must be increasing, each once");
  }
  if (count < 1 || count > 100000) return fail(fmt::format("the count must be in [1, 100000], not {}", count));
  if (grid_points < 5 || grid_points > 10000) return fail("grid_points must be in [5, 10000]");
  return true;
}

std::optional<double> quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  const double at = std::clamp(q, 0.0, 1.0) * double(values.size() - 1);
  const auto lo = size_t(std::floor(at));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (at - double(lo)) * (values[hi] - values[lo]);
}

std::optional<Distribution> distribution_of(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  Distribution d;
  d.size = int(values.size());
  d.min = *quantile(values, 0);
  d.q10 = *quantile(values, 0.1);
  d.q25 = *quantile(values, 0.25);
  d.median = *quantile(values, 0.5);
  d.q75 = *quantile(values, 0.75);
  d.q90 = *quantile(values, 0.9);
  d.max = *quantile(values, 1);
  return d;
}

std::optional<double> best_single_alpha(int count, const std::vector<double>& optimum,
                                        const std::function<double(int, double)>& f, int grid_points) {
  if (count <= 0) return std::nullopt;
  const double lo = std::log(1e-6), hi = std::log(0.5);
  std::vector<double> grid(grid_points);
  for (int k = 0; k < grid_points; ++k) grid[k] = lo + (hi - lo) * k / (grid_points - 1);
  std::vector<std::vector<double>> values(count, std::vector<double>(grid_points));
  std::vector<double> best(optimum);
  for (int b = 0; b < count; ++b)
    for (int k = 0; k < grid_points; ++k) {
      values[b][k] = f(b, std::exp(grid[k]) - 0.25);
      if (std::isfinite(values[b][k])) best[b] = std::min(best[b], values[b][k]);
    }
  auto loss = [&](int b, double value) {
    if (!std::isfinite(value)) return HUGE_VAL;
    return best[b] > 0 ? (value - best[b]) / best[b] : value - best[b];
  };
  std::vector<double> mean(grid_points, 0);
  for (int k = 0; k < grid_points; ++k) {
    for (int b = 0; b < count; ++b) mean[k] += loss(b, values[b][k]) / count;
  }
  const auto at = int(std::min_element(mean.begin(), mean.end()) - mean.begin());
  if (!std::isfinite(mean[at])) return std::nullopt;
  auto mean_at = [&](double t) {
    double s = 0;
    for (int b = 0; b < count; ++b) s += loss(b, f(b, std::exp(t) - 0.25)) / count;
    return s;
  };
  double a = grid[std::max(at - 1, 0)], d = grid[std::min(at + 1, grid_points - 1)];
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = d - r * (d - a), x2 = a + r * (d - a), f1 = mean_at(x1), f2 = mean_at(x2);
  for (int it = 0; it < 40; ++it) {
    if (f1 <= f2) {
      d = x2;
      x2 = x1;
      f2 = f1;
      x1 = d - r * (d - a);
      f1 = mean_at(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + r * (d - a);
      f2 = mean_at(x2);
    }
  }
  const double t = f1 <= f2 ? x1 : x2;
  return std::min(f1, f2) <= mean[at] ? std::exp(t) - 0.25 : std::exp(grid[at]) - 0.25;
}

namespace {

// f_b(α) of one boundary: the sine basis where it applies, else a factorisation and a solve.
std::function<double(double)> alpha_curve(const Boundary& b, const Objective& objective,
                                          const solvers::SolverInfo& solver) {
#if COONS_HAVE_FFTW
  if (b.m >= 2 && b.n >= 2 && SpectralAlphaObjective::supports(objective)) {
    auto f = std::make_shared<SpectralAlphaSearchObjective>(b, objective);
    return [f](double alpha) {
      const auto e = f->evaluate(alpha, false);
      return e.ok() ? e.value : HUGE_VAL;
    };
  }
#endif
  auto f = std::make_shared<MaskObjective>(
      b, objective, [](double a) { return alpha_family(a); }, solver);
  return [f](double alpha) {
    const auto e = f->evaluate(alpha, false);
    return e.ok() ? e.value : HUGE_VAL;
  };
}

std::vector<double> present(const std::vector<std::optional<double>>& v) {
  std::vector<double> out;
  for (const auto& x : v)
    if (x) out.push_back(*x);
  return out;
}

AlphaFamilyCell run_cell(const std::vector<Boundary>& family, int degree, const Objective& objective,
                         const AlphaFamilyOptions& options) {
  AlphaFamilyCell cell;
  cell.degree = degree;
  cell.objective = objective.name;
  const int count = int(family.size());
  cell.alpha_star.resize(count);
  cell.mu_star.resize(count);
  cell.loss.resize(count);
  std::vector<int> used;  // boundaries with an optimum
  std::vector<double> optimum;
  std::vector<std::function<double(double)>> curves;
  for (int k = 0; k < count; ++k) {
    const Boundary b = elevate_boundary(family[k], degree, degree);
    const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
    const AlphaSearchSummary s = search_alpha(b, objective, solver);
    if (s.flat) {
      ++cell.flat;
      continue;
    }
    if (!s.parameter || s.status != SearchStatus::kSuccess) {
      ++cell.failed;
      continue;
    }
    cell.alpha_star[k] = s.parameter;
    cell.mu_star[k] = s.at_bound ? std::nullopt : mu_of_alpha(degree, *s.parameter);
    ++(s.at_bound ? cell.at_bound : cell.interior);
    used.push_back(k);
    optimum.push_back(s.value);
    curves.push_back(alpha_curve(b, objective, solver));
  }
  cell.alpha = distribution_of(present(cell.alpha_star));
  cell.mu = distribution_of(present(cell.mu_star));
  cell.best_alpha = best_single_alpha(
      int(used.size()), optimum, [&](int b, double alpha) { return curves[b](alpha); }, options.grid_points);
  if (cell.best_alpha) {
    cell.best_mu = mu_of_alpha(degree, *cell.best_alpha);
    for (size_t u = 0; u < used.size(); ++u) {
      const double value = curves[u](*cell.best_alpha);
      const double own = std::min(optimum[u], value);
      if (std::isfinite(value) && own > 0) cell.loss[used[u]] = (value - own) / own;
    }
  }
  const std::vector<double> losses = present(cell.loss);
  cell.losses = distribution_of(losses);
  if (!losses.empty()) {
    double sum = 0;
    for (double x : losses) sum += x;
    cell.loss_mean = sum / double(losses.size());
  }
  return cell;
}

}  // namespace

AlphaFamilyResult run_alpha_family(const AlphaFamilyOptions& options,
                                   const std::function<void(const std::string&)>& progress) {
  AlphaFamilyResult r;
  r.options = options;
  const std::vector<Objective> objectives =
      options.objectives.empty() ? default_study_objectives() : options.objectives;
  for (const Objective& o : objectives) r.objectives.push_back(o.name);
  const std::vector<Boundary> family = random_smooth_family(options.seed, options.count, options.generator);
  for (const Objective& o : objectives)
    for (int d : options.degrees) {
      if (progress) progress(fmt::format("degree {}, {}", d, o.name));
      r.cells.push_back(run_cell(family, d, o, options));
    }
  return r;
}

namespace {

json optional_number(const std::optional<double>& x) { return x ? number_or_null(*x) : json(nullptr); }

json distribution_json(const std::optional<Distribution>& d) {
  if (!d) return nullptr;
  return {{"size", d->size},
          {"min", number_or_null(d->min)},
          {"q10", number_or_null(d->q10)},
          {"q25", number_or_null(d->q25)},
          {"median", number_or_null(d->median)},
          {"q75", number_or_null(d->q75)},
          {"q90", number_or_null(d->q90)},
          {"max", number_or_null(d->max)}};
}

json optional_list(const std::vector<std::optional<double>>& v) {
  json out = json::array();
  for (const auto& x : v) out.push_back(optional_number(x));
  return out;
}

}  // namespace

json alpha_family_json(const AlphaFamilyResult& r) {
  const AlphaFamilyOptions& o = r.options;
  json cells = json::array();
  for (const AlphaFamilyCell& c : r.cells)
    cells.push_back({{"degree", c.degree},
                     {"objective", c.objective},
                     {"interior", c.interior},
                     {"flat", c.flat},
                     {"at_bound", c.at_bound},
                     {"failed", c.failed},
                     {"alpha_star", optional_list(c.alpha_star)},
                     {"mu_star", optional_list(c.mu_star)},
                     {"alpha_quantiles", distribution_json(c.alpha)},
                     {"mu_quantiles", distribution_json(c.mu)},
                     {"best_alpha", optional_number(c.best_alpha)},
                     {"best_mu", optional_number(c.best_mu)},
                     {"loss", optional_list(c.loss)},
                     {"loss_quantiles", distribution_json(c.losses)},
                     {"loss_mean", optional_number(c.loss_mean)}});
  return {{"family", "random-smooth"},
          {"seed", o.seed},
          {"count", o.count},
          {"generator",
           {{"side_degree", o.generator.side_degree}, {"height", o.generator.height}, {"wiggle", o.generator.wiggle}}},
          {"degrees", o.degrees},
          {"objectives", r.objectives},
          {"cells", cells}};
}

}  // namespace coons
