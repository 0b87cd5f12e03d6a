#include "coons/study/bspline_study.h"

#include <fmt/format.h>

#include <cmath>

#include "coons/io/net_json.h"
#include "coons/study/bspline_net.h"
#include "coons/study/bspline_search.h"
#include "coons/surfaces/bspline_energy.h"
#include "solvers/registry.h"

namespace coons {

namespace {

double thin_plate_at(const BSplineBoundary& b, double alpha, const std::string& solver) {
  auto backend = solvers::make_solver(solver);
  const BSplineNetOutcome r = make_bspline_net(b, NetMethod::kAlpha, alpha, backend.get());
  if (!r.summary || !r.summary->ok()) return NAN;
  return bspline_combined_energy(r.local, bspline_thin_plate_terms());
}

std::string number(double x) { return std::isfinite(x) ? fmt::format("{:.6g}", x) : std::string("—"); }

}  // namespace

std::vector<BSplineStudyRow> run_bspline_study(const std::vector<BSplineStudyInput>& inputs,
                                               const std::vector<Objective>& objectives, const std::string& solver) {
  std::vector<BSplineStudyRow> rows;
  for (const BSplineStudyInput& in : inputs) {
    const BSplineBoundary& b = in.sides.compatible;
    BSplineStudyRow row;
    row.file = in.file;
    row.name = in.name;
    row.degree_u = b.bottom.degree;
    row.degree_v = b.left.degree;
    row.count_u = b.bottom.count();
    row.count_v = b.left.count();
    row.notes = in.sides.notes;
    // [−1/4, U] is searched (bspline_search_options), where the system is definite.
    row.solver = solver.empty() ? auto_bspline_solver(0.0) : solver;
    const AlphaSearchOptions bounds = bspline_search_options(b);
    row.thin_plate_coons = thin_plate_at(b, -0.25, row.solver);
    row.thin_plate_laplace = thin_plate_at(b, 0.0, row.solver);
    for (const Objective& o : objectives) {
      std::string why;
      if (!bspline_objective_supported(o, &why)) continue;
      row.searches.emplace_back(o.name, search_bspline_alpha(b, o, row.solver, bounds));
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string bspline_study_markdown(const std::vector<BSplineStudyRow>& rows) {
  if (rows.empty()) return "";
  std::string md =
      "## B-spline boundaries\n\n"
      "A B-spline boundary is not studied over Bézier degrees (its net is not elevated); it gets one row at its own "
      "knots, after opposite sides were made compatible. Thin-plate energies of the Greville Coons net (α = −1/4) "
      "and of the non-uniform Laplace net (α = 0), and the best α of the non-uniform family (docs/math.md §10) for "
      "each objective, searched from α = −1/4 up to the end of the range where its system is positive definite (at "
      "most 1/4).\n\n"
      "| boundary | degrees (p, q) | points | compatibility | thin plate α = −1/4 | thin plate α = 0 | best α |\n"
      "| --- | --- | --- | --- | --- | --- | --- |\n";
  for (const BSplineStudyRow& r : rows) {
    std::string notes;
    for (const CompatibilityNote& n : r.notes)
      notes += fmt::format("{}{}: +{} knots, degree +{}", notes.empty() ? "" : "; ", n.side, n.knots_inserted,
                           n.degree_raised_by);
    std::string best;
    for (const auto& [objective, s] : r.searches) {
      std::string verdict = s.parameter ? fmt::format("{:.6g}", *s.parameter) : std::string(to_string(s.status));
      if (s.at_bound) verdict += " (at bound)";
      if (s.status != SearchStatus::kSuccess && s.parameter) verdict += fmt::format(" ({})", to_string(s.status));
      best += fmt::format("{}{}: {}", best.empty() ? "" : "; ", objective, verdict);
    }
    md += fmt::format("| {} | ({}, {}) | {} × {} | {} | {} | {} | {} |\n", r.name, r.degree_u, r.degree_v, r.count_u,
                      r.count_v, notes.empty() ? "none" : notes, number(r.thin_plate_coons),
                      number(r.thin_plate_laplace), best.empty() ? "—" : best);
  }
  return md;
}

nlohmann::json bspline_study_json(const std::vector<BSplineStudyRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BSplineStudyRow& r : rows) {
    nlohmann::json row = {{"file", r.file},
                          {"boundary", r.name},
                          {"degree_spline", {r.degree_u, r.degree_v}},
                          {"points", {r.count_u, r.count_v}},
                          {"solver", r.solver},
                          {"thin_plate_coons", number_or_null(r.thin_plate_coons)},
                          {"thin_plate_laplace", number_or_null(r.thin_plate_laplace)}};
    nlohmann::json notes = nlohmann::json::array();
    for (const CompatibilityNote& n : r.notes)
      notes.push_back(
          {{"side", n.side}, {"degree_raised_by", n.degree_raised_by}, {"knots_inserted", n.knots_inserted}});
    row["compatibility"] = notes;
    nlohmann::json searches = nlohmann::json::object();
    for (const auto& [objective, s] : r.searches)
      searches[objective] = {{"status", to_string(s.status)},
                             {"alpha", s.parameter ? nlohmann::json(*s.parameter) : nlohmann::json(nullptr)},
                             {"value", number_or_null(s.value)},
                             {"at_bound", s.at_bound},
                             {"flat", s.flat}};
    row["best_alpha"] = searches;
    out.push_back(row);
  }
  return out;
}

}  // namespace coons
