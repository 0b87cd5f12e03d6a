#include "degree_limit_report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "coons/io/plot.h"
#include "coons/io/write_files.h"

namespace coons {

namespace {

std::string num(double x) { return fmt::format("{:.4g}", x); }

std::vector<std::pair<int, double>> interior_mus(const DegreeLimitEntry& e) {
  std::vector<std::pair<int, double>> out;
  for (const DegreeLimitCell& c : e.cells)
    if (c.mu) out.emplace_back(c.degree, *c.mu);
  return out;
}

bool all_flat(const DegreeLimitEntry& e) {
  return !e.cells.empty() && std::all_of(e.cells.begin(), e.cells.end(),
                                         [](const DegreeLimitCell& c) { return c.kind == DegreeOptimum::kFlat; });
}

// "n = 4 … 32": the degrees a spread was taken over.
std::string range_of(const Spread& s) { return fmt::format("n = {} … {}", s.from, s.to); }

// A spread over less than a factor kConstantRange in n says nothing about how μ* depends on the
// degree: over n = 30 … 32 the dome's e3 has max/min 1.003, over 4 … 32 1.57.
constexpr int kConstantRange = 4;
bool wide(const Spread& s) { return s.points >= 2 && s.to >= kConstantRange * s.from; }

bool is_constant(const DegreeLimitEntry& e, const ClaimThresholds& t) {
  return e.mu_spread.ratio && *e.mu_spread.ratio - 1 <= t.constant && wide(e.mu_spread);
}

bool has_reliable_limit(const DegreeLimitEntry& e, const ClaimThresholds& t) {
  return limit_claimed(e.limit, t.limit_error);
}

bool meets_continuum(const DegreeLimitEntry& e, const ClaimThresholds& t) {
  const ContinuumSummary cs = continuum_summary(e);
  if (!cs.mu || !has_reliable_limit(e, t)) return false;
  const double allowed = std::max(t.continuum_gap * *cs.mu, 2 * *e.limit.limit_error + cs.change.value_or(0));
  return std::abs(*e.limit.limit - *cs.mu) <= allowed;
}

// The fit of least residual among those with more points than parameters: a form that
// interpolates its points has residual 0 up to rounding, and with two points at n ≥ 8 both
// two-parameter forms did, one "fitting best" at 0 against 1.8e-16 (their μ∞ 5.25 and 7.26).
const LimitFit* best_fit(const DegreeLimitEntry& e) {
  const LimitFit* best = nullptr;
  for (const LimitFit& f : e.limit.fits)
    if (f.points > int(f.parameters.size()) && (!best || f.residual < best->residual)) best = &f;
  return best;
}

std::string within_text(const std::optional<int>& n, int last) {
  return n ? fmt::format("from n = {}", *n) : fmt::format("not yet at n = {}", last);
}

// "5 %" for 0.05: the label of a tolerance, from its value (DegreeLimitOptions::tolerances).
std::string tolerance_label(double tolerance) { return fmt::format("{:g} %", 100 * tolerance); }

// An entry fitted with fewer tolerances than the report shows (is_valid allows any number) has no
// value there, which is not "not yet".
std::optional<int> within_from(const DegreeLimitEntry& e, size_t k) {
  return k < e.limit.within_from.size() ? e.limit.within_from[k] : std::nullopt;
}

// "; within 5 % from n = 10, within 1 % not yet at n = 32" over the tolerances the entry has,
// each labelled by its value.
std::string within_clauses(const DegreeLimitEntry& e, int last) {
  std::string out;
  for (size_t k = 0; k < e.limit.within_from.size() && k < e.limit.tolerances.size(); ++k)
    out += fmt::format("{} within {} {}", k == 0 ? ";" : ",", tolerance_label(e.limit.tolerances[k]),
                       within_text(e.limit.within_from[k], last));
  return out;
}

}  // namespace

std::vector<std::string> degree_limit_conclusions(const DegreeLimitEntry& e, const ClaimThresholds& t) {
  std::vector<std::string> out;
  if (e.skipped_reason) {
    std::vector<std::string> parts;
    if (!e.skipped_degrees.empty()) parts.push_back(fmt::format("{} (search)", fmt::join(e.skipped_degrees, " ")));
    if (!e.skipped_continuum_degrees.empty())
      parts.push_back(fmt::format("{} (continuum)", fmt::join(e.skipped_continuum_degrees, " ")));
    out.push_back(fmt::format("Degrees not measured: {}, {}.", fmt::join(parts, "; "), *e.skipped_reason));
  }
  const auto mus = interior_mus(e);
  if (mus.empty()) {
    int coons = 0, other = 0;
    for (const DegreeLimitCell& c : e.cells)
      (c.kind == DegreeOptimum::kAtBound && c.alpha.parameter && *c.alpha.parameter <= -0.25 ? coons : other) += 1;
    if (all_flat(e))
      out.push_back("flat at every degree: the objective does not depend on α, no optimum and no μ.");
    else if (other == 0)
      out.push_back("α* = −1/4 (the Coons net, μ = 0) at every degree: the optimum is on the bound, no interior μ*.");
    else
      out.push_back(
          fmt::format("no interior optimum with α* < 0 at any of the {} degrees (on a bound, α* ≥ 0, flat "
                      "or failed): no μ*.",
                      e.cells.size()));
    return out;
  }
  // 1. constant or drifting
  if (is_constant(e, t))
    out.push_back(fmt::format("μ* does not depend on the degree: max/min = {:.3f} over {}.", *e.mu_spread.ratio,
                              range_of(e.mu_spread)));
  else if (e.mu_spread.ratio && *e.mu_spread.ratio - 1 <= t.constant)
    out.push_back(
        fmt::format("μ* varies by max/min = {:.3f} over {}, too narrow a range of degrees (less than a "
                    "factor {}) to say whether it depends on the degree.",
                    *e.mu_spread.ratio, range_of(e.mu_spread), kConstantRange));
  else
    out.push_back(fmt::format("μ* drifts with the degree: μ*({}) = {}, μ*({}) = {}{}.", mus.front().first,
                              num(mus.front().second), mus.back().first, num(mus.back().second),
                              e.mu_spread.ratio
                                  ? fmt::format(" (max/min {:.3g} over {})", *e.mu_spread.ratio, range_of(e.mu_spread))
                                  : std::string()));
  // 2. the limit
  const int last = mus.back().first;
  if (has_reliable_limit(e, t))
    out.push_back(fmt::format("μ*(n) converges: μ∞ = {} ± {} (rate n^−{:.2f}){}.", num(*e.limit.limit),
                              fmt::format("{:.2g}", *e.limit.limit_error), *e.limit.rate, within_clauses(e, last)));
  else if (e.limit.limit && e.limit.limit_error)
    out.push_back(fmt::format("no limit claimed: the extrapolation gives μ∞ = {} ± {:.2g}, an error above {:.0f} %.",
                              num(*e.limit.limit), *e.limit.limit_error, 100 * t.limit_error));
  else if (e.limit.limit)
    out.push_back(fmt::format("no limit claimed: the extrapolation gives μ∞ = {}, but {}.", num(*e.limit.limit),
                              e.limit.message));
  else
    out.push_back("no limit claimed: " + (e.limit.message.empty() ? std::string("no extrapolation") : e.limit.message) +
                  ".");
  if (const LimitFit* f = best_fit(e))
    out.push_back(fmt::format("Of the candidate forms, {} fits best (rms relative residual {:.2g} over n ≥ 8){}.",
                              f->form, f->residual,
                              f->at_bound ? fmt::format(", with p = {} at an end of the range searched, so a p "
                                                        "beyond it may fit better",
                                                        num(f->parameters.back().second))
                                          : std::string()));
  else if (!e.limit.fits.empty())
    out.push_back(
        fmt::format("No candidate form is preferred: each has as many parameters as the {} point(s) at "
                    "n ≥ 8 it fits, so it passes through them.",
                    e.limit.fits.front().points));
  // 3. the continuum optimum
  const ContinuumSummary cs = continuum_summary(e);
  if (cs.mu && meets_continuum(e, t))
    out.push_back(fmt::format("μ*(n) tends to the continuum optimum μ_c = {} (Ritz, N = {}): |μ∞ − μ_c| = {:.2g}.",
                              num(*cs.mu), cs.degree, std::abs(*e.limit.limit - *cs.mu)));
  else if (cs.mu && e.limit.limit && !has_reliable_limit(e, t))  // the reason is the limit, not the gap
    out.push_back(
        fmt::format("μ∞ = {} is not established (error ± {}), so no agreement with the continuum optimum "
                    "μ_c = {} (Ritz, N = {}) is claimed; they differ by {:.1f} %.",
                    num(*e.limit.limit), e.limit.limit_error ? num(*e.limit.limit_error) : "unknown", num(*cs.mu),
                    cs.degree, 100 * std::abs(*e.limit.limit - *cs.mu) / *cs.mu));
  else if (cs.mu && e.limit.limit)
    out.push_back(
        fmt::format("μ∞ = {} and the continuum optimum μ_c = {} (Ritz, N = {}) differ by {:.1f} %: not "
                    "claimed to agree.",
                    num(*e.limit.limit), num(*cs.mu), cs.degree, 100 * std::abs(*e.limit.limit - *cs.mu) / *cs.mu));
  else if (cs.mu)
    out.push_back(fmt::format("The continuum optimum is μ_c = {} (Ritz, N = {}); μ*({}) = {}.", num(*cs.mu), cs.degree,
                              last, num(mus.back().second)));
  else if (!e.continuum.empty())
    out.push_back(
        fmt::format("The continuum problem has no interior optimum in μ ({}).", to_string(e.continuum.back().status)));
  // 4. which parametrisation varies least over n = 4 … 32
  if (e.mu_spread.ratio) {
    std::string best = "μ*";
    double r = *e.mu_spread.ratio;
    if (e.exact_mu_spread.ratio && *e.exact_mu_spread.ratio < r) {
      best = "μ_exact (the exact-energy mask parameter)";
      r = *e.exact_mu_spread.ratio;
    }
    if (e.galerkin_spread.ratio && *e.galerkin_spread.ratio < r) {
      best = "ν* (the exact-energy family)";
      r = *e.galerkin_spread.ratio;
    }
    if (best == "μ*")
      out.push_back(fmt::format("No other parametrisation varies less than μ* (max/min {:.3g}).", r));
    else
      out.push_back(fmt::format("Over {}, {} varies least: max/min {:.3g}, against {:.3g} for μ*.",
                                range_of(e.mu_spread), best, r, *e.mu_spread.ratio));
  }
  return out;
}

std::string degree_limit_headline(const std::vector<DegreeLimitEntry>& entries, const std::string& objective,
                                  const ClaimThresholds& t) {
  std::vector<const DegreeLimitEntry*> with;
  for (const DegreeLimitEntry& e : entries)
    if (e.objective == objective && e.mu_spread.ratio) with.push_back(&e);
  if (with.empty()) return fmt::format("{}: no shape has interior optima at two degrees in n = 4 … 32", objective);
  double lo = HUGE_VAL, hi = 0, p_lo = HUGE_VAL, p_hi = 0;
  Spread range;  // the union of the entries' ranges
  range.from = with.front()->mu_spread.from;
  bool constant = true, limits = true, continuum = true;
  for (const DegreeLimitEntry* e : with) {
    lo = std::min(lo, *e->mu_spread.ratio);
    hi = std::max(hi, *e->mu_spread.ratio);
    range.from = std::min(range.from, e->mu_spread.from);
    range.to = std::max(range.to, e->mu_spread.to);
    constant = constant && is_constant(*e, t);
    limits = limits && has_reliable_limit(*e, t);
    continuum = continuum && meets_continuum(*e, t);
    if (e->limit.rate) {
      p_lo = std::min(p_lo, *e->limit.rate);
      p_hi = std::max(p_hi, *e->limit.rate);
    }
  }
  if (constant) return fmt::format("{}: μ* does not depend on the degree (max/min ≤ {:.3f})", objective, hi);
  if (hi - 1 <= t.constant)  // small spreads, but not all over a wide enough range of degrees
    return fmt::format("{}: μ* varies by max/min ≤ {:.3f} over {}, too narrow a range of degrees to say more",
                       objective, hi, range_of(range));
  std::string s = fmt::format("{}: μ* drifts with the degree (max/min {:.3g} to {:.3g} over {})", objective, lo, hi,
                              range_of(range));
  if (limits) {
    s += fmt::format(" and converges, as n^−p with p = {:.2f} … {:.2f}", p_lo, p_hi);
    if (continuum) s += ", to the optimum of the continuous problem";
    return s;
  }
  // Not every shape: say for how many the limit (and the agreement with μ_c) is established.
  int with_limit = 0, agreeing = 0;
  for (const DegreeLimitEntry* e : with) {
    with_limit += has_reliable_limit(*e, t) ? 1 : 0;
    agreeing += meets_continuum(*e, t) ? 1 : 0;
  }
  s += fmt::format("; a limit known to 5 % for {} of {} shapes, {} of them at the continuum optimum", with_limit,
                   with.size(), agreeing);
  return s;
}

std::vector<StudyFigure> plot_degree_limit_figures(const std::vector<DegreeLimitEntry>& entries,
                                                   const std::function<std::string(const std::string&)>& path_of) {
  std::vector<StudyFigure> figures;
  std::vector<std::string> objectives;
  for (const DegreeLimitEntry& e : entries)
    if (std::find(objectives.begin(), objectives.end(), e.objective) == objectives.end())
      objectives.push_back(e.objective);
  for (const std::string& objective : objectives) {
    std::vector<PlotSeries> mu_series, gap_series;
    for (const DegreeLimitEntry& e : entries) {
      if (e.objective != objective) continue;
      const auto mus = interior_mus(e);
      if (mus.size() < 2) continue;
      PlotSeries s{e.boundary + ": μ*(n)", {}, {}, false};
      for (auto [n, mu] : mus) {
        s.x.push_back(n);
        s.y.push_back(mu);
      }
      mu_series.push_back(s);
      const ContinuumSummary cs = continuum_summary(e);
      if (!cs.mu) continue;
      mu_series.push_back(PlotSeries{fmt::format("{}: continuum μ_c = {:.4g}", e.boundary, *cs.mu),
                                     {double(mus.front().first), double(mus.back().first)},
                                     {*cs.mu, *cs.mu},
                                     false});
      PlotSeries g{e.boundary + ": |μ*(n) − μ_c|", {}, {}, false};
      for (auto [n, mu] : mus)
        if (std::abs(mu - *cs.mu) > 0) {
          g.x.push_back(n);
          g.y.push_back(std::abs(mu - *cs.mu));
        }
      if (g.x.size() >= 2) gap_series.push_back(g);
    }
    PlotOptions o;
    o.log_x = o.log_y = true;
    o.xlabel = "degree n";
    if (!mu_series.empty()) {
      o.title = "μ* against the degree (" + objective + "), continuum optimum as a line";
      o.ylabel = "μ*";
      StudyFigure f{degree_limit_figure_files(objective)[0], ""};
      f.error = plot_curves(path_of(f.file), mu_series, o);
      figures.push_back(f);
    }
    if (!gap_series.empty()) {
      // the slope of a first-order law, for the eye: 20/n over the degrees drawn
      double first = HUGE_VAL, last = 0;
      for (const PlotSeries& g : gap_series) {
        first = std::min(first, g.x.front());
        last = std::max(last, g.x.back());
      }
      gap_series.push_back(PlotSeries{"reference slope: 20/n", {first, last}, {20 / first, 20 / last}, false});
      o.title = "distance of μ*(n) from the continuum optimum (" + objective + ")";
      o.ylabel = "|μ*(n) − μ_c|";
      StudyFigure f{degree_limit_figure_files(objective)[1], ""};
      f.error = plot_curves(path_of(f.file), gap_series, o);
      figures.push_back(f);
    }
  }
  return figures;
}

std::array<std::string, 2> degree_limit_figure_files(const std::string& objective) {
  return {"figures/mu_vs_degree_" + safe_file_stem(objective) + ".png",
          "figures/mu_gap_vs_degree_" + safe_file_stem(objective) + ".png"};
}

std::string degree_limit_report_markdown(const std::vector<DegreeLimitEntry>& entries,
                                         const DegreeLimitStudyOptions& options, const Provenance& p,
                                         const std::vector<StudyFigure>& figures) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  std::vector<std::string> objectives;
  for (const DegreeLimitEntry& e : entries)
    if (std::find(objectives.begin(), objectives.end(), e.objective) == objectives.end())
      objectives.push_back(e.objective);
  line("# The degree law, measured");
  line("");
  line(provenance_line(p));
  line("");
  line("## 1. Headline");
  line("");
  for (const std::string& o : objectives) line("- " + degree_limit_headline(entries, o) + ".");
  line("");
  line("Each claim below is printed only when the numbers support it (μ* constant: max/min ≤ 1.05 over degrees");
  line("within n = 4 … 32 that span at least a factor 4;");
  line("a limit: extrapolation error ≤ 5 %; agreement with the continuum: |μ∞ − μ_c| ≤ max(5 % of μ_c, twice the");
  line("error plus the Ritz change between its last two degrees)); otherwise the measured value is printed instead.");
  line("μ* = −n²(1 + 4α*)/(4α*) (docs/math.md §4) from α* of `search_alpha` at each degree (the boundary refitted");
  line("from its analytic sides, or elevated exactly); μ∞ comes from the last three degrees (the curve");
  line("μ∞ + a·n^−p through them), its error is how far that moved from the triple before or from the");
  line("free-rate fit; μ_c is the optimum of the continuous problem, computed by the Ritz method in integrated");
  line("Legendre polynomials of degree N, independent of the masks.");
  line("");
  line("## 2. Conclusions, shape by shape");
  line("");
  for (const DegreeLimitEntry& e : entries) {
    std::string s;
    for (const std::string& c : degree_limit_conclusions(e)) s += " " + c;
    line(fmt::format("- **{}, {}.**{}", e.boundary, e.objective, s));
  }
  line("");
  line("## 3. The law in numbers");
  line("");
  std::vector<int> shown;
  for (int d : options.degrees)
    if (d == options.degrees.front() || d == options.degrees.back() || d == 4 || d == 8 || d == 16 || d == 32)
      shown.push_back(d);
  std::string header = "| shape | objective |", rule = "|---|---|";
  for (int d : shown) {
    header += fmt::format(" μ* (n={}) |", d);
    rule += "---|";
  }
  header += " μ∞ ± error | rate p |";
  rule += "---|---|";
  for (double tolerance : options.limit.tolerances) {
    header += fmt::format(" within {} from |", tolerance_label(tolerance));
    rule += "---|";
  }
  line(header + " μ_c (Ritz) | status |");
  line(rule + "---|---|");
  for (const DegreeLimitEntry& e : entries) {
    std::string row = fmt::format("| {} | {} |", e.boundary, e.objective);
    for (int d : shown) {
      const DegreeLimitCell* cell = nullptr;
      for (const DegreeLimitCell& c : e.cells)
        if (c.degree == d) cell = &c;
      row += " " + (!cell ? std::string("–") : cell->mu ? num(*cell->mu) : std::string(to_string(cell->kind))) + " |";
    }
    const ContinuumSummary cs = continuum_summary(e);
    const std::string none = "–";
    row += fmt::format(" {} | {} |",
                       e.limit.limit
                           ? num(*e.limit.limit) +
                                 (e.limit.limit_error ? fmt::format(" ± {:.2g}", *e.limit.limit_error) : std::string())
                           : none,
                       e.limit.rate ? fmt::format("{:.2f}", *e.limit.rate) : none);
    for (size_t k = 0; k < options.limit.tolerances.size(); ++k)
      row += " " + (within_from(e, k) ? std::to_string(*within_from(e, k)) : none) + " |";
    row += fmt::format(" {} | {} |", cs.mu ? fmt::format("{} (N = {})", num(*cs.mu), cs.degree) : none,
                       e.limit.status == DegreeLimitStatus::kSuccess && !has_reliable_limit(e, {})
                           ? std::string("success, not claimed")
                           : std::string(to_string(e.limit.status)));
    line(row);
  }
  line("");
  line("The candidate forms, fitted by relative least squares over the degrees n ≥ " +
       std::to_string(options.limit.fit_from_degree) + " (rms relative residual):");
  line("");
  line("| shape | objective | form | parameters | residual |");
  line("|---|---|---|---|---|");
  for (const DegreeLimitEntry& e : entries)
    for (const LimitFit& f : e.limit.fits) {
      std::string params;
      for (const auto& [name, value] : f.parameters)
        params += fmt::format("{}{} = {}", params.empty() ? "" : ", ", name, num(value));
      if (f.at_bound) params += " (p at an end of the range searched)";
      line(fmt::format("| {} | {} | {} | {} | {:.2g} |", e.boundary, e.objective, f.form, params, f.residual));
    }
  line("");
  for (const StudyFigure& f : figures)
    if (f.error.empty() && f.file.find("figures/mu_") == 0) line(fmt::format("![{}]({})", f.file, f.file));
  line("");
  line("## 4. A degree-independent parameter?");
  line("");
  line("max/min of each parametrisation's optimum over n = " + std::to_string(options.spread_from) + " … " +
       std::to_string(options.spread_to) + " (1 would be degree-independent): μ* of the mask family through");
  line("α(n) = −n²/(4(n² + μ)); μ_exact, the μ for which the α*-net is most nearly stationary for the exact");
  line("∫∫‖p_uv‖² + μ∫∫‖∇p‖² (docs/math.md §4); ν*, the optimal μ of the exact-energy (Ritz) family at degree n.");
  line("");
  line("| shape | objective | μ* | μ_exact | ν* |");
  line("|---|---|---|---|---|");
  auto ratio = [](const Spread& s) {
    return s.ratio ? fmt::format("{:.3g} ({} degrees)", *s.ratio, s.points) : std::string("–");
  };
  for (const DegreeLimitEntry& e : entries)
    if (e.mu_spread.ratio || e.galerkin_spread.ratio)
      line(fmt::format("| {} | {} | {} | {} | {} |", e.boundary, e.objective, ratio(e.mu_spread),
                       ratio(e.exact_mu_spread), ratio(e.galerkin_spread)));
  line("");
  for (const StudyFigure& f : figures)
    if (!f.error.empty()) line(fmt::format("(figure {} not made: {})", f.file, f.error));
  return md;
}

}  // namespace coons
