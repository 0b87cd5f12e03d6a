#include "study_conclusions.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace coons {

std::vector<std::string> study_conclusions(const StudyResult& r, double same_alpha_tolerance,
                                           double constant_mu_tolerance) {
  std::vector<std::string> out;
  // 1. One α for every shape? Per objective, over the shapes with an optimum (interior or bound).
  for (const std::string& objective : r.objectives) {
    std::string lo_shape, hi_shape;  // "name" or "name, on the bound"
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    int count = 0;
    for (const ShapeEntry& shape : r.shapes)
      for (const ShapeOptimum& o : shape.optima) {
        if (o.objective != objective || o.alpha.flat || !o.alpha.parameter || o.alpha.status != SearchStatus::kSuccess)
          continue;
        ++count;
        if (*o.alpha.parameter < lo) {
          lo = *o.alpha.parameter;
          lo_shape = shape.boundary.name + (o.alpha.at_bound ? ", on the bound" : "");
        }
        if (*o.alpha.parameter > hi) {
          hi = *o.alpha.parameter;
          hi_shape = shape.boundary.name + (o.alpha.at_bound ? ", on the bound" : "");
        }
      }
    if (count < 2)
      out.push_back(fmt::format("{}: fewer than two shapes have an optimum; nothing to compare", objective));
    else if (hi - lo > same_alpha_tolerance)
      out.push_back(
          fmt::format("{}: no single α is best — the optima at the shapes' own degrees range from {:.4f} "
                      "({}) to {:.4f} ({}) over {} shapes",
                      objective, lo, lo_shape, hi, hi_shape, count));
    else
      out.push_back(fmt::format("{}: the optima of {} shapes agree within {:.4f} (α* from {:.4f} ({}) to {:.4f} ({}))",
                                objective, count, hi - lo, lo, lo_shape, hi, hi_shape));
  }
  // 2. Flat shapes.
  std::vector<std::string> flat;
  for (const ShapeEntry& shape : r.shapes)
    if (!shape.optima.empty() &&
        std::all_of(shape.optima.begin(), shape.optima.end(), [](const ShapeOptimum& o) { return o.alpha.flat; }))
      flat.push_back(shape.boundary.name);
  if (!flat.empty()) {
    std::string names;
    for (const auto& n : flat) names += (names.empty() ? "" : ", ") + n;
    out.push_back(fmt::format("{} of {} shapes are flat for every objective (no α is better than another): {}",
                              flat.size(), r.shapes.size(), names));
  }
  // 3. The best fit to each target.
  for (const ReferenceTable& t : r.references) {
    if (t.best.status != SearchStatus::kSuccess && t.best.status != SearchStatus::kFlat) {
      out.push_back(fmt::format("{}: the search for the α closest to the target did not succeed ({})", t.boundary,
                                to_string(t.best.status)));
      continue;
    }
    if (!t.best.parameter || t.best.flat || !(t.best.value > 0)) {
      out.push_back(fmt::format("{}: no α fits the target better than another", t.boundary));
      continue;
    }
    out.push_back(
        fmt::format("{}: the α closest to the target is {:.4f} (rms {:.3g}, {:.3g}× closer than the Coons net)",
                    t.boundary, *t.best.parameter, t.best.value, t.coons_rms / t.best.value));
  }
  // 4. Does μ* stay put across the degrees? Only where at least two degrees have an interior μ*.
  for (const DegreeLawEntry& law : r.laws) {
    std::vector<std::pair<int, double>> mus;
    for (const DegreeCell& c : law.cells)
      if (c.mu.parameter && !c.mu.flat && !c.mu.at_bound && c.mu.status == SearchStatus::kSuccess)
        mus.emplace_back(c.degree, *c.mu.parameter);
    if (mus.size() < 2) continue;
    double lo = HUGE_VAL, hi = 0;
    for (auto [d, mu] : mus) {
      lo = std::min(lo, mu);
      hi = std::max(hi, mu);
    }
    if (lo > 0 && hi / lo - 1 <= constant_mu_tolerance)
      out.push_back(fmt::format("{}, {}: μ* stays put across the degrees (max/min {:.3f})", law.boundary, law.objective,
                                hi / lo));
    else
      out.push_back(fmt::format("{}, {}: μ* drifts with the degree, {:.4g} (n = {}) to {:.4g} (n = {})", law.boundary,
                                law.objective, mus.front().second, mus.front().first, mus.back().second,
                                mus.back().first));
  }
  return out;
}

std::string study_conclusions_markdown(const StudyResult& r) {
  std::string md = "## 5. Conclusions, computed from the tables\n\n";
  md += "Each sentence is generated from the numbers above; a claim they do not support is replaced by the\n";
  md += "measured values (one α is best when the optima lie within 0.05; μ* stays put when max/min ≤ 1.05).\n\n";
  for (const std::string& s : study_conclusions(r)) md += "- " + s + ".\n";
  return md;
}

}  // namespace coons
