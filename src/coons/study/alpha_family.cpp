#include "coons/study/alpha_family.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "coons/io/net_json.h"
#include "coons/io/plot.h"

namespace coons {

using nlohmann::json;

bool AlphaFamilyOptions::is_valid(std::string* why, std::string* field) const {
  auto fail = [&](const char* name, const std::string& reason) {
    if (why) *why = reason;
    if (field) *field = name;
    return false;
  };
  if (std::string reason; !generator.is_valid(&reason)) return fail("generator", reason);
  if (base && std::max(base->m, base->n) > kMaxFamilyDegree)
    return fail("base", fmt::format("the base has degree {}, above the largest degree a family study takes ({})",
                                    std::max(base->m, base->n), kMaxFamilyDegree));
  if (degrees.empty()) return fail("degrees", "no degrees");
  const int lowest = base ? std::max({generator.side_degree, base->m, base->n}) : generator.side_degree;
  for (size_t k = 0; k < degrees.size(); ++k) {
    if (degrees[k] < lowest || degrees[k] > kMaxFamilyDegree)
      return fail("degrees", fmt::format("degree {} is outside [{}, {}] (the sides have degree {})", degrees[k], lowest,
                                         kMaxFamilyDegree, lowest));
    if (k > 0 && degrees[k] <= degrees[k - 1]) return fail("degrees", "degrees must be increasing, each once");
  }
  if (count < 1 || count > 100000) return fail("count", fmt::format("the count must be in [1, 100000], not {}", count));
  if (grid_points < 5 || grid_points > 10000) return fail("grid_points", "grid_points must be in [5, 10000]");
  if (!(std::isfinite(amplitude) && amplitude >= 0 && amplitude <= 1))
    return fail("amplitude", fmt::format("the amplitude must be in [0, 1], not {}", amplitude));
  return true;
}

std::string AlphaFamilyOptions::family_name() const {
  return base_name.empty() ? "random-smooth" : "perturbed:" + base_name;
}

Boundary family_boundary(const AlphaFamilyOptions& o, int index) {
  if (o.base_name.empty()) return random_smooth_boundary(o.seed, index, o.generator);
  if (!o.base) throw std::logic_error("family_boundary: the perturbed family needs its base");
  return perturbed_boundary(*o.base, o.amplitude, o.seed, index, o.generator);
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

double family_grid_alpha(double s, int grid_points) {
  // u = log((α + 1/4)/(1/4 − α)) from −u_end to u_end: the poles of f_b(α), just beyond α = −1/4
  // and α = 1/4, lie π off the real u axis (docs/formats.md), so the nodes serve both ends alike
  const double u_end = std::log((0.5 - kFamilyGridEnd) / kFamilyGridEnd);
  const double u = -u_end + 2 * u_end * s / (grid_points - 1);
  return std::clamp(-0.25 + 0.5 / (1 + std::exp(-u)), -0.25, 0.25);
}

std::vector<double> family_alpha_grid(int grid_points) {
  std::vector<double> grid(grid_points);
  for (int k = 0; k < grid_points; ++k) grid[k] = family_grid_alpha(k, grid_points);
  return grid;
}

double interpolate_on_grid(const std::vector<double>& values, double s) {
  const int size = int(values.size());
  if (size == 0) return HUGE_VAL;
  if (size == 1) return values[0];
  s = std::clamp(s, 0.0, double(size - 1));
  const int k = std::min(int(std::floor(s)), size - 2);  // s in [k, k + 1]
  const int points = std::min(kGridInterpolationPoints, size);
  const int first = std::clamp(k - (points / 2 - 1), 0, size - points);
  const int last = first + points - 1;
  bool finite = true;
  for (int j = first; j <= last; ++j) finite = finite && std::isfinite(values[j]);
  if (!finite) {
    if (!std::isfinite(values[k]) || !std::isfinite(values[k + 1])) return HUGE_VAL;
    return values[k] + (s - k) * (values[k + 1] - values[k]);
  }
  double sum = 0;
  for (int j = first; j <= last; ++j) {
    double w = 1;
    for (int i = first; i <= last; ++i)
      if (i != j) w *= (s - i) / double(j - i);
    sum += w * values[j];
  }
  return sum;
}

std::optional<BestSingleAlpha> best_single_alpha_on_grid(const std::vector<std::vector<double>>& values,
                                                         const std::vector<double>& optimum) {
  const auto count = int(values.size());
  if (count == 0 || optimum.size() != values.size()) return std::nullopt;
  // one grid for every curve, of at least two nodes (the refinement divides by grid_points − 1);
  // curves read back from a shard can be anything, and nothing here may read past one of them
  const auto grid_points = int(values[0].size());
  if (grid_points < 2) return std::nullopt;
  for (const std::vector<double>& curve : values)
    if (curve.size() != values[0].size()) return std::nullopt;
  std::vector<double> best(optimum);
  for (int b = 0; b < count; ++b)
    for (double v : values[b])
      if (std::isfinite(v)) best[b] = std::min(best[b], v);
  auto loss = [&](int b, double value) {
    if (!std::isfinite(value)) return HUGE_VAL;
    return best[b] > 0 ? (value - best[b]) / best[b] : value - best[b];
  };
  auto mean_at = [&](double s) {
    double sum = 0;
    for (int b = 0; b < count; ++b) sum += loss(b, interpolate_on_grid(values[b], s)) / count;
    return sum;
  };
  std::vector<double> mean(grid_points, 0);
  for (int k = 0; k < grid_points; ++k)
    for (int b = 0; b < count; ++b) mean[k] += loss(b, values[b][k]) / count;
  const auto at = int(std::min_element(mean.begin(), mean.end()) - mean.begin());
  if (!std::isfinite(mean[at])) return std::nullopt;
  double a = std::max(at - 1, 0), d = std::min(at + 1, grid_points - 1);
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
  const double s = std::min(f1, f2) <= mean[at] ? (f1 <= f2 ? x1 : x2) : double(at);
  const double alpha = family_grid_alpha(s, grid_points);
  // the golden sections end within 0.618^40 (≈ 4e−9) of a node: closer than 1e−6 to an end is on it
  const bool at_end = s <= 1e-6 || s >= grid_points - 1 - 1e-6;
  return BestSingleAlpha{alpha, s, at_end};
}

std::optional<double> best_single_alpha(int count, const std::vector<double>& optimum,
                                        const std::function<double(int, double)>& f, int grid_points) {
  if (count <= 0) return std::nullopt;
  const std::vector<double> grid = family_alpha_grid(grid_points);
  std::vector<std::vector<double>> values(count, std::vector<double>(grid_points));
  for (int b = 0; b < count; ++b)
    for (int k = 0; k < grid_points; ++k) values[b][k] = f(b, grid[k]);
  const auto best = best_single_alpha_on_grid(values, optimum);
  return best ? std::optional<double>(best->alpha) : std::nullopt;
}

namespace {

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

json family_description_json(const AlphaFamilyOptions& o) {
  json out = {
      {"family", o.family_name()},
      {"seed", o.seed},
      {"count", o.count},
      {"generator",
       {{"side_degree", o.generator.side_degree}, {"height", o.generator.height}, {"wiggle", o.generator.wiggle}}},
      {"degrees", o.degrees}};
  if (!o.base_name.empty()) out["amplitude"] = o.amplitude;
  return out;
}

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
                     {"zero_optimum", c.zero_optimum},
                     {"alpha_star", optional_list(c.alpha_star)},
                     {"mu_star", optional_list(c.mu_star)},
                     {"alpha_quantiles", distribution_json(c.alpha)},
                     {"mu_quantiles", distribution_json(c.mu)},
                     {"best_alpha", optional_number(c.best_alpha)},
                     {"best_mu", optional_number(c.best_mu)},
                     {"best_alpha_at_grid_end", c.best_at_grid_end},
                     {"loss", optional_list(c.loss)},
                     {"loss_quantiles", distribution_json(c.losses)},
                     {"loss_mean", optional_number(c.loss_mean)},
                     {"alpha_ratio_quantiles", distribution_json(c.alpha_ratio)}});
  json out = family_description_json(o);
  out["objectives"] = r.objectives;
  out["cells"] = cells;
  return out;
}

}  // namespace coons
