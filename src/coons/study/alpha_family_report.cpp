// The markdown, conclusions and histograms of the random-family α study (alpha_family.h).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "coons/io/plot.h"
#include "coons/study/alpha_family.h"

namespace coons {

namespace {

std::string g4(const std::optional<double>& x) { return x ? fmt::format("{:.4g}", *x) : "–"; }
std::string percent(double x) { return std::isfinite(100 * x) ? fmt::format("{:.3g} %", 100 * x) : "–"; }

std::vector<const AlphaFamilyCell*> cells_of(const AlphaFamilyResult& r, const std::string& objective) {
  std::vector<const AlphaFamilyCell*> out;
  for (const AlphaFamilyCell& c : r.cells)
    if (c.objective == objective) out.push_back(&c);
  return out;
}

}  // namespace

std::string alpha_family_conclusions(const AlphaFamilyResult& r) {
  std::string out;
  const int count = r.options.count;
  for (const std::string& objective : r.objectives) {
    const auto cells = cells_of(r, objective);
    std::vector<std::string> above, within, losses, medians, spreads, bounds, grid_ends, zeros;
    std::vector<double> median_gap;
    for (const AlphaFamilyCell* c : cells) {
      if (c->losses && c->loss_mean) {
        (c->losses->max > 0.01 ? above : within).push_back(fmt::format("{}", c->degree));
        losses.push_back(fmt::format("n = {}: α = {} loses {} on average, {} at the 90th percentile, {} at worst",
                                     c->degree, g4(c->best_alpha), percent(*c->loss_mean), percent(c->losses->q90),
                                     percent(c->losses->max)));
      }
      if (c->best_alpha && c->best_at_grid_end)
        grid_ends.push_back(fmt::format("{} (n = {})", g4(c->best_alpha), c->degree));
      if (c->alpha) {
        medians.push_back(fmt::format("{:.3g}", c->alpha->median));
        median_gap.push_back(c->alpha->median + 0.25);
      }
      // a spread of one or two μ* is none (1 from a single boundary of 200 read as "the same μ*")
      if (c->mu && c->mu->q10 > 0 && c->mu->size >= 3)
        spreads.push_back(
            fmt::format("{:.3g} (n = {}, {} boundaries)", c->mu->q90 / c->mu->q10, c->degree, c->mu->size));
      if (c->zero_optimum > 0) zeros.push_back(fmt::format("{} at n = {}", c->zero_optimum, c->degree));
      if (c->flat + c->at_bound + c->failed > 0)
        bounds.push_back(
            fmt::format("n = {}: {} flat, {} on a bound, {} failed", c->degree, c->flat, c->at_bound, c->failed));
    }
    out += fmt::format("- **{}** ({} boundaries). ", objective, count);
    if (!above.empty() && within.empty())
      out += fmt::format(
          "No single α is best at any degree studied: the best single α for the family loses "
          "more than 1 % against some boundary's own optimum at n = {}. ",
          fmt::join(above, ", "));
    else if (above.empty() && !within.empty())
      out += fmt::format("One α serves the whole family within 1 % of every boundary's own optimum at n = {}. ",
                         fmt::join(within, ", "));
    else if (!above.empty())
      out += fmt::format(
          "The best single α loses more than 1 % for some boundary at n = {}, and stays within "
          "1 % for every boundary at n = {}. ",
          fmt::join(above, ", "), fmt::join(within, ", "));
    if (!zeros.empty())
      out += fmt::format(
          "Boundaries whose own optimum is 0 up to rounding (the mask reproduces them; a relative loss means nothing "
          "for them, and the best single α is that of the others): {}. ",
          fmt::join(zeros, ", "));
    if (!losses.empty()) out += fmt::format("The best single α: {}. ", fmt::join(losses, "; "));
    if (!grid_ends.empty())
      out += fmt::format(
          "The best single α is at the end of its grid at {}: the family's mean loss still falls there, so it is "
          "where the grid stops, not an interior minimum. ",
          fmt::join(grid_ends, ", "));
    if (median_gap.size() >= 2) {
      // a gap to −1/4 within the searches' edge tolerance (1e-7 of the interval) is the bound
      // itself: medians of −0.25 found from inside by 1e-9 "moved towards −1/4"
      for (double& gap : median_gap)
        if (gap <= 1e-7 * 0.5) gap = 0;
      const bool on_bound = std::all_of(median_gap.begin(), median_gap.end(), [](double g) { return g == 0; });
      const bool falling = std::is_sorted(median_gap.rbegin(), median_gap.rend()) && median_gap.back() < median_gap[0];
      const auto [lo, hi] = std::minmax_element(median_gap.begin(), median_gap.end());
      const bool still = *hi - *lo <= 1e-9 * std::max(*hi, 1e-300);  // equal medians were "not monotone"
      out += on_bound
                 ? fmt::format("The median α* is −1/4, the bound, at every degree ({}). ", fmt::join(medians, ", "))
             : still ? fmt::format("The median α* does not move with n ({}). ", fmt::join(medians, ", "))
             : falling
                 ? fmt::format("The median α* moves towards −1/4 as n grows ({}). ", fmt::join(medians, ", "))
                 : fmt::format("The median α* per degree: {} (not monotone towards −1/4). ", fmt::join(medians, ", "));
    }
    if (!spreads.empty()) out += fmt::format("μ*'s 90th over 10th percentile: {}. ", fmt::join(spreads, ", "));
    out += bounds.empty() ? std::string("Every boundary's own search found an interior optimum.")
                          : fmt::format("Not interior: {}.", fmt::join(bounds, "; "));
    out += "\n";
  }
  return out;
}

std::string alpha_family_markdown(const AlphaFamilyResult& r, const std::vector<std::string>& figures) {
  const AlphaFamilyOptions& o = r.options;
  const std::string loss =
      "The loss of a boundary is (f(α) − f*)/f* at the family's best single α (the α minimising the mean loss). μ* "
      "and its quantiles count the boundaries with −1/4 < α* < 0 only (α* ≥ 0 has no μ).\n\n";
  std::string md =
      o.base_name.empty()
          ? fmt::format(
                "## The random-smooth family: is one α best?\n\n{} boundaries (seed {}): sides of degree {} "
                "with shared corners over the unit square, heights uniform in ±{}, in-plane displacements "
                "uniform in ±{}; each elevated exactly to the degree n. ",
                o.count, o.seed, o.generator.side_degree, o.generator.height, o.generator.wiggle)
          : fmt::format(
                "## The family {}: is one α best?\n\n{} perturbations (seed {}) of the boundary {}: its "
                "sides plus {} × its bounding-box diagonal times a random smooth displacement shared at the "
                "corners (sides of degree {}, heights uniform in ±{}, in-plane uniform in ±{}); each elevated "
                "exactly to the degree n. ",
                o.family_name(), o.count, o.seed, o.base_name, o.amplitude, o.generator.side_degree, o.generator.height,
                o.generator.wiggle);
  md += loss;
  const size_t n = r.objectives.size();
  auto q = [](const std::optional<Distribution>& d, double Distribution::*field) {
    return d ? fmt::format("{:.4g}", (*d).*field) : std::string("–");
  };
  auto lq = [](const std::optional<Distribution>& d, double Distribution::*field) {
    return d ? percent((*d).*field) : std::string("–");
  };
  auto figure = [&](size_t k, const std::string& what) {
    return k < figures.size() && !figures[k].empty() ? fmt::format("![{}]({})\n\n", what, figures[k]) : std::string();
  };
  for (size_t i = 0; i < n; ++i) {
    md += fmt::format("### {}\n\n", r.objectives[i]);
    md += "**The optima.** Where each boundary's own α* and μ* lie.\n\n";
    md +=
        "| n | interior | flat | on a bound | failed | flat or on a bound | α* 10 % | α* median | α* 90 % | μ* 10 % | "
        "μ* median | μ* 90 % |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const AlphaFamilyCell* c : cells_of(r, r.objectives[i]))
      md += fmt::format(
          "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", c->degree, c->interior, c->flat,
          c->at_bound, c->failed, o.count > 0 ? percent(double(c->flat + c->at_bound) / o.count) : "–",
          q(c->alpha, &Distribution::q10), q(c->alpha, &Distribution::median), q(c->alpha, &Distribution::q90),
          q(c->mu, &Distribution::q10), q(c->mu, &Distribution::median), q(c->mu, &Distribution::q90));
    md +=
        "\n**One α for all.** The best single α, how far it is from each boundary's own "
        "(the factor (α* + 1/4)/(α + 1/4)) and what each boundary loses with it (the relative excess "
        "(f(α) − f*)/f*).\n\n";
    md +=
        "| n | best α | its μ | factor 10 % | factor median | factor 90 % | excess median | excess mean | "
        "excess 90 % | excess max |\n";
    md += "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const AlphaFamilyCell* c : cells_of(r, r.objectives[i]))
      md += fmt::format("| {} | {}{} | {} | {} | {} | {} | {} | {} | {} | {} |\n", c->degree, g4(c->best_alpha),
                        c->best_at_grid_end ? " (grid end)" : "", g4(c->best_mu), q(c->alpha_ratio, &Distribution::q10),
                        q(c->alpha_ratio, &Distribution::median), q(c->alpha_ratio, &Distribution::q90),
                        lq(c->losses, &Distribution::median), c->loss_mean ? percent(*c->loss_mean) : "–",
                        lq(c->losses, &Distribution::q90), lq(c->losses, &Distribution::max));
    md += "\n" + figure(i, "α* of " + r.objectives[i]) + figure(n + i, "μ* of " + r.objectives[i]) +
          figure(2 * n + i, "excess at the best single α, " + r.objectives[i]);
  }
  md += "### Conclusions (computed from the tables)\n\n" + alpha_family_conclusions(r);
  return md;
}

namespace {

// One histogram per degree of log10 of `value(cell, b)` (skipped where it returns nothing), as step
// lines over common log bins, with `mark(cell)` (when given) marked at the tallest bin's height.
std::string plot_log_histograms(const std::string& png, const std::vector<const AlphaFamilyCell*>& cells,
                                const std::function<std::optional<double>(const AlphaFamilyCell&, size_t)>& value,
                                const std::function<std::optional<double>(const AlphaFamilyCell&)>& mark,
                                PlotOptions options) {
  constexpr int kBins = 24;
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const AlphaFamilyCell* c : cells)
    for (size_t b = 0; b < c->alpha_star.size(); ++b)
      if (const auto v = value(*c, b); v && *v > 0 && std::isfinite(*v)) {
        lo = std::min(lo, std::log10(*v));
        hi = std::max(hi, std::log10(*v));
      }
  if (!(lo < hi)) return "no spread of values to draw";
  std::vector<PlotSeries> series;
  for (const AlphaFamilyCell* c : cells) {
    std::vector<int> counts(kBins, 0);
    for (size_t b = 0; b < c->alpha_star.size(); ++b)
      if (const auto v = value(*c, b); v && *v > 0 && std::isfinite(*v))
        ++counts[std::min(kBins - 1, int((std::log10(*v) - lo) / (hi - lo) * kBins))];
    PlotSeries s;
    s.title = fmt::format("n = {}", c->degree);
    for (int k = 0; k < kBins; ++k)
      for (int edge : {k, k + 1}) {
        s.x.push_back(std::pow(10.0, lo + (hi - lo) * edge / kBins));
        s.y.push_back(counts[k]);
      }
    if (mark)
      if (const auto m = mark(*c); m && *m > 0) {
        s.marker_x.push_back(*m);
        s.marker_y.push_back(*std::max_element(counts.begin(), counts.end()));
      }
    series.push_back(std::move(s));
  }
  options.log_x = true;
  options.y_scale = AxisScale::kLinear;
  options.ylabel = "boundaries per bin";
  return plot_curves(png, series, options);
}

}  // namespace

std::vector<std::string> plot_alpha_family(const AlphaFamilyResult& r, const std::function<std::string(size_t)>& png) {
  std::vector<std::string> errors;
  const size_t n = r.objectives.size();
  const int count = r.options.count;
  for (size_t i = 0; i < n; ++i) {
    PlotOptions o;
    o.title = fmt::format("α* over {} {} boundaries, {}", count, r.options.family_name(), r.objectives[i]);
    o.xlabel = "α* + 1/4";
    o.marker_title = "best single α";
    errors.push_back(plot_log_histograms(
        png(i), cells_of(r, r.objectives[i]),
        [](const AlphaFamilyCell& c, size_t b) -> std::optional<double> {
          return c.alpha_star[b] ? std::optional<double>(*c.alpha_star[b] + 0.25) : std::nullopt;
        },
        [](const AlphaFamilyCell& c) -> std::optional<double> {
          return c.best_alpha ? std::optional<double>(*c.best_alpha + 0.25) : std::nullopt;
        },
        o));
  }
  for (size_t i = 0; i < n; ++i) {
    PlotOptions o;
    o.title = fmt::format("μ* over {} {} boundaries, {} (interior optima with α* < 0)", count, r.options.family_name(),
                          r.objectives[i]);
    o.xlabel = "μ* = −n²(1 + 4α*)/(4α*)";
    o.marker_title = "μ of the best single α";
    errors.push_back(plot_log_histograms(
        png(n + i), cells_of(r, r.objectives[i]), [](const AlphaFamilyCell& c, size_t b) { return c.mu_star[b]; },
        [](const AlphaFamilyCell& c) { return c.best_mu; }, o));
  }
  for (size_t i = 0; i < n; ++i) {
    PlotOptions o;
    o.title = fmt::format("relative excess (f(α) − f*)/f* at the best single α, {}", r.objectives[i]);
    o.xlabel = "relative excess over the boundary's own optimum";
    errors.push_back(plot_log_histograms(
        png(2 * n + i), cells_of(r, r.objectives[i]), [](const AlphaFamilyCell& c, size_t b) { return c.loss[b]; }, {},
        o));
  }
  return errors;
}

}  // namespace coons
