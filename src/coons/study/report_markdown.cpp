#include "report_markdown.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "coons/io/plot.h"
#include "coons/io/write_files.h"

namespace coons {

namespace {

// A value of the report, or "failed" where its solve failed (NaN).
std::string value_or_failed(double x, const char* spec = "{:.6g}") {
  return std::isfinite(x) ? fmt::format(fmt::runtime(spec), x) : std::string("failed");
}

std::string format_optimum(const AlphaSearchSummary& s, int digits = 4) {
  if (s.status == SearchStatus::kSolverFailed) return "failed";
  if (s.status == SearchStatus::kFailedRegion) return "failed region";
  if (s.flat) return "flat";
  if (!s.parameter) return "–";
  std::string out = fmt::format("{:.{}f}", *s.parameter, digits);
  if (s.at_bound) out += " (bound)";
  if (s.local_minima > 1) out += " (multi)";
  return out;
}

// The value column beside format_optimum: the objective at the optimum; with a failed region the
// lowest successful evaluation, which is no optimum, so labelled; nothing where no solve succeeded.
std::string value_at_optimum(const AlphaSearchSummary& s) {
  if (s.status == SearchStatus::kFailedRegion)
    return std::isfinite(s.value) ? fmt::format("{:.6g} (outside the failed region)", s.value) : "–";
  if (s.flat || !s.parameter || s.status == SearchStatus::kSolverFailed || !std::isfinite(s.value)) return "–";
  return fmt::format("{:.6g}", s.value);
}

const DegreeCell* cell_at(const DegreeLawEntry& law, int degree) {
  for (const auto& c : law.cells)
    if (c.degree == degree) return &c;
  return nullptr;
}

}  // namespace

std::vector<std::string> shape_file_stems(const StudyResult& result) {
  std::vector<std::string> stems;
  std::map<std::string, int> seen;
  for (const ShapeEntry& shape : result.shapes) {
    std::string stem = safe_file_stem(shape.boundary.name);
    if (seen.count(stem)) stem += fmt::format("-{}x{}", shape.boundary.m, shape.boundary.n);
    for (int k = 2; seen.count(stem); ++k) stem = fmt::format("{}-{}", safe_file_stem(shape.boundary.name), k);
    seen[stem] = 1;
    stems.push_back(stem);
  }
  return stems;
}

StudyFigures plot_study_figures(const StudyResult& r, const std::function<std::string(const std::string&)>& path_of) {
  StudyFigures figures;
  const std::vector<std::string> stems = shape_file_stems(r);
  for (size_t k = 0; k < r.shapes.size(); ++k) {
    const ShapeEntry& shape = r.shapes[k];
    StudyFigure energies{"figures/" + stems[k] + "_energies.png", ""};
    std::map<std::string, SweepOptimum> optima;  // α* of the table, not the sweep's lowest point
    for (const ShapeOptimum& o : shape.optima)
      if (o.alpha.parameter && !o.alpha.flat && o.alpha.status == SearchStatus::kSuccess)
        optima[o.objective] = {*o.alpha.parameter, o.alpha.value};
    energies.error = plot_sweep(path_of(energies.file), shape.boundary, SweepParameter::kAlpha, shape.curves, optima);
    StudyFigure nets{"figures/" + stems[k] + "_nets.png", ""};
    nets.error = plot_nets(path_of(nets.file), shape.pictures, 25, shape.boundary.name);
    figures.energies.push_back(energies);
    figures.nets.push_back(nets);
  }
  // α* + 1/4 against the degree with the fitted law, and μ* against the degree (thin plate).
  std::vector<PlotSeries> law_series, mu_series;
  for (const DegreeLawEntry& law : r.laws) {
    if (law.objective != "thin_plate") continue;
    if (law.fit) {
      // one colour per shape: the fitted c/n² line with the measured α* + 1/4 marked on it
      PlotSeries fitted{fmt::format("{}: c/n², c = {:.3g}", law.boundary, law.fit->c), {}, {}, false};
      for (int d = r.degrees.front(); d <= r.degrees.back(); ++d) {
        fitted.x.push_back(d);
        fitted.y.push_back(law.fit->c / (double(d) * d));
      }
      for (auto [d, a] : law.interior) {
        fitted.marker_x.push_back(d);
        fitted.marker_y.push_back(a + 0.25);
      }
      law_series.push_back(std::move(fitted));
    }
    PlotSeries mu_line{law.boundary + " " + law.objective, {}, {}, false};
    for (const DegreeCell& c : law.cells)
      if (c.mu.parameter && !c.mu.flat && !c.mu.at_bound) {
        mu_line.x.push_back(c.degree);
        mu_line.y.push_back(*c.mu.parameter);
      }
    if (mu_line.x.size() >= 2) mu_series.push_back(mu_line);
  }
  figures.alpha_vs_degree.file = "figures/alpha_vs_degree.png";
  PlotOptions law_options{"thin-plate optimum: α* + 1/4 against degree, with the fitted c/n²",
                          "degree n",
                          "α* + 1/4",
                          true,
                          true,
                          1100,
                          700};
  law_options.marker_title = "measured α* + 1/4";
  figures.alpha_vs_degree.error = law_series.empty()
                                      ? "no shape has two interior optima"
                                      : plot_curves(path_of(figures.alpha_vs_degree.file), law_series, law_options);
  figures.mu_vs_degree.file = "figures/mu_vs_degree.png";
  PlotOptions mu_options{
      "thin-plate optimum μ* against degree (flat if the c/n² law holds)", "degree n", "μ*", false, false, 1100, 700};
  figures.mu_vs_degree.error = mu_series.empty()
                                   ? "no shape has two interior μ optima"
                                   : plot_curves(path_of(figures.mu_vs_degree.file), mu_series, mu_options);
  return figures;
}

namespace {

// The title, the provenance and what α, μ and the optima's marks mean.
std::string study_introduction_markdown(const Provenance& p) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  line("# The α study: which mask gives the best surface?");
  line("");
  line(provenance_line(p));
  line("");
  line("α is the weight of the four diagonal neighbours in b_ij = α·K + β·E (Farin & Hansford 1999); α = −1/4 is the");
  line("Coons net, α = 0 the Laplace net. μ is the membrane weight of ∫‖p_uv‖² + μ∫‖∇p‖², with");
  line(
      "α(n) = −n²/(4(n² + μ)) (docs/math.md §4; μ* still drifts with n, as O(1/n)). Optima come from `search_alpha` "
      "(coarse scan, then Ceres with the");
  line("analytic derivative; objectives over α are evaluated in the sine basis of the mask family, with no solve per");
  line("evaluation); `flat` means the objective does not depend on α, `bound` that the optimum is on a bound,");
  line("`multi` that the scan saw several local minima.");
  line("");
  return md;
}

// §1: each shape's optima at its own degree (with the C1 family's column where a shape has two data rings).
std::string study_optima_markdown(const StudyResult& r) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  line("## 1. Coons, Laplace and optimal nets at each shape's own degree");
  line("");
  // the C1 family's column only when some input has two data rings (the report is otherwise unchanged)
  const bool c1_column = std::any_of(r.shapes.begin(), r.shapes.end(), [](const ShapeEntry& shape) {
    return std::any_of(shape.optima.begin(), shape.optima.end(), [](const ShapeOptimum& o) { return o.weight; });
  });
  if (c1_column) {
    line("w* is the weight of the 5×5 C1 family (w = 1: `c1-coons`, w = 0: `biharmonic`, docs/formats.md \"Masks\"),");
    line("found by `search_weight` on the shape's two data rings; a shape with one data ring has none (–, with the");
    line("reason).");
    line("");
    line(
        "| shape | degree | objective | α* | value at α* | at Coons (−1/4) | at Laplace (0) | μ* | w* (C1 family) | "
        "value at w* |");
    line("|---|---|---|---|---|---|---|---|---|---|");
  } else {
    line("| shape | degree | objective | α* | value at α* | at Coons (−1/4) | at Laplace (0) | μ* |");
    line("|---|---|---|---|---|---|---|---|");
  }
  for (const ShapeEntry& shape : r.shapes) {
    const Boundary& b = shape.boundary;
    for (const ShapeOptimum& o : shape.optima) {
      std::string row = fmt::format("| {} | {}×{} | {} | {} | {} | {} | {} | {} |", b.name, b.m, b.n, o.objective,
                                    format_optimum(o.alpha), value_at_optimum(o.alpha), value_or_failed(o.coons),
                                    value_or_failed(o.laplace), format_optimum(o.mu, 3));
      if (c1_column)
        row += o.weight ? fmt::format(" {} | {} |", format_optimum(*o.weight), value_at_optimum(*o.weight))
                        : fmt::format(" – ({}) | – |", shape.one_ring);
      line(row);
    }
  }
  line("");
  return md;
}

// §2: the optimum against the degree, the fit of the degree law, the refits' deviations and the two plots.
std::string study_degrees_markdown(const StudyResult& r, const StudyFigures& figures) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  line("## 2. How the optimum moves with the degree");
  line("");
  line("A boundary given by curves (analytic sides) is refitted at each degree (d, d); any other boundary is");
  line(
      "degree-elevated exactly (its curves do not change) for d ≥ its own degree, and left out (–) below it. The law "
      "α* + 1/4 ≈ c/n² is fitted");
  line("per shape by least squares over the degrees with an interior optimum; `c` and the largest relative misfit are");
  line("given. If the law holds, μ* is nearly constant across degrees.");
  line("");
  std::string header = "| shape | objective |";
  std::string rule = "|---|---|";
  for (int d : r.degrees) {
    header += fmt::format(" α* (n={}) |", d);
    rule += "---|";
  }
  header += " c | misfit | μ* by degree |";
  rule += "---|---|---|";
  line(header);
  line(rule);
  for (const DegreeLawEntry& law : r.laws) {
    std::string row = fmt::format("| {} | {} |", law.boundary, law.objective);
    std::string mus;
    for (int d : r.degrees) {
      const DegreeCell* c = cell_at(law, d);
      if (!c) {
        row += " – |";
        continue;
      }
      row += " " + format_optimum(c->alpha) + " |";
      if (c->mu.parameter && !c->mu.flat && !c->mu.at_bound)
        mus += fmt::format("{}{:.3g}", mus.empty() ? "" : ", ", *c->mu.parameter);
      else
        mus += std::string(mus.empty() ? "" : ", ") + format_optimum(c->mu, 1);
    }
    if (law.fit)
      row += fmt::format(" {:.4g} | {:.1f}% |", law.fit->c, 100 * law.fit->misfit);
    else
      row += " – | – |";
    row += " " + (mus.empty() ? "–" : mus) + " |";
    line(row);
  }
  line("");
  if (!r.fit_deviations.empty()) {
    line("Shapes given by curves (the boundary file's `curves`) are refitted at each degree; the largest");
    line("deviation of a fitted side from its curve:");
    line("");
    std::string h = "| shape |", rl = "|---|";
    for (int d : r.degrees) {
      h += fmt::format(" n = {} |", d);
      rl += "---|";
    }
    line(h);
    line(rl);
    for (const FitDeviationEntry& f : r.fit_deviations) {
      std::string fr = fmt::format("| {} |", f.boundary);
      for (auto [d, dev] : f.max_deviation) fr += fmt::format(" {:.2e} |", dev);
      line(fr);
    }
    line("");
  }
  const StudyFigure& law = figures.alpha_vs_degree;
  line(law.error.empty() ? fmt::format("![α* against degree]({})", law.file) : "(α* plot: " + law.error + ")");
  line("");
  const StudyFigure& mu = figures.mu_vs_degree;
  line(mu.error.empty() ? fmt::format("![μ* against degree]({})", mu.file) : "(μ* plot: " + mu.error + ")");
  line("");
  return md;
}

// §3: a reference table for every boundary with a target (nothing without one).
std::string study_references_markdown(const StudyResult& r) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  if (!r.references.empty()) {
    line("## 3. Reference tables: every boundary with a target");
    line("");
    line("The net at α = −1/4, −1/5, −1/10 and 0 (as in Farin & Hansford's table for the dome, docs/math.md §7) and");
    line("the α whose surface is closest to the boundary file's `target` (rms distance of the sampled surface).");
    line("");
  }
  for (const ReferenceTable& t : r.references) {
    line(fmt::format("### {} ({}×{})", t.boundary, t.m, t.n));
    line("");
    line("| α | S(½,½).z | thin plate | Dirichlet | rms distance to the target |");
    line("|---|---|---|---|---|");
    for (const ReferenceRow& row : t.rows)
      line(fmt::format("| {} | {} | {} | {} | {} |", row.alpha, value_or_failed(row.center_z, "{:.6f}"),
                       value_or_failed(row.thin_plate, "{:.3f}"), value_or_failed(row.dirichlet, "{:.3f}"),
                       value_or_failed(row.rms_target, "{:.4f}")));
    line("");
    if (t.best.status == SearchStatus::kSuccess && t.best.parameter && !t.best.flat && t.best.value > 0)
      line(fmt::format(
          "The α that fits the target best: {} (rms {:.4g}, against {:.4g} for the Coons net: {:.3g}× closer).",
          format_optimum(t.best), t.best.value, t.coons_rms, t.coons_rms / t.best.value));
    else
      line(fmt::format("The α that fits the target best: {} (no distance is compared).", format_optimum(t.best)));
    line("");
  }
  return md;
}

// §4: the energy curves and nets of each shape.
std::string study_pictures_markdown(const StudyResult& r, const StudyFigures& figures) {
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  line("## 4. Energy curves and nets, shape by shape");
  line("");
  for (size_t k = 0; k < r.shapes.size(); ++k) {
    const std::string& name = r.shapes[k].boundary.name;
    const StudyFigure& e = figures.energies[k];
    const StudyFigure& n = figures.nets[k];
    line(fmt::format("### {}\n", name));
    line(e.error.empty() ? fmt::format("![energies of {}]({})\n", name, e.file)
                         : "(energy plot failed: " + e.error + ")\n");
    line(n.error.empty() ? fmt::format("![nets of {}]({})\n", name, n.file) : "(picture failed: " + n.error + ")\n");
  }
  return md;
}

}  // namespace

std::string study_report_markdown(const StudyResult& r, const Provenance& p, const StudyFigures& figures) {
  return study_introduction_markdown(p) + study_optima_markdown(r) + study_degrees_markdown(r, figures) +
         study_references_markdown(r) + study_pictures_markdown(r, figures);
}

}  // namespace coons
