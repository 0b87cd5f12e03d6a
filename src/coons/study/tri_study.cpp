#include "tri_study.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <tuple>

#include "coons/io/json_file.h"
#include "coons/io/net_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/study/target.h"
#include "coons/study/tri_search.h"
#include "coons/tri/tri_solve.h"

namespace coons {

using nlohmann::json;

TriStudyInput read_tri_study_input(const std::string& path, double corner_tolerance) {
  TriBoundaryReadOptions options;
  options.min_model_size = kMinModelSize;  // a study searches
  options.corner_tolerance = corner_tolerance;
  TriStudyInput in;
  in.file = path;
  in.boundary = read_tri_boundary_file(path, options);
  in.target = target_from_json(read_json_file(path), path);
  return in;
}

std::vector<std::string> tri_study_objectives(const TriStudyInput& input) {
  std::vector<std::string> out = {"thin_plate", "e3", "dirichlet", "twist"};
  if (input.target) out.emplace_back("target");
  return out;
}

namespace {

// The boundary of `b` elevated to degree `degree` (≥ b.n): elevating the frame elevates its sides,
// whose control points depend on the sides alone.
tri::TriBoundary elevated(const tri::TriBoundary& b, int degree) {
  if (degree == b.n) return b;
  return tri::boundary_of(tri::elevate_degree(tri::frame_net(b), degree - b.n), b.name);
}

TriStudyCell study_cell(const tri::TriBoundary& b, const TriObjective& objective, const solvers::SolverInfo& solver) {
  const tri::TriNet frame = tri::frame_net(b);
  AlphaSearchOptions options;
  std::tie(options.lower, options.upper) = default_tri_bounds(b.n);
  TriStudyCell cell;
  cell.degree = b.n;
  cell.lower = options.lower;
  cell.upper = options.upper;
  cell.c = search_tri_c(frame, objective, solver, options);
  const auto value_at = [&](double c) {  // NaN (failed / null in the reports) where the solve failed
    const TriEvaluation e = evaluate_tri_objective(frame, objective, c, solver, false);
    return e.ok() ? e.value : std::numeric_limits<double>::quiet_NaN();
  };
  cell.quadratic = value_at(-1.0 / 6);
  cell.laplace = value_at(0.0);
  return cell;
}

std::string format_c(const AlphaSearchSummary& s) {
  if (s.status == SearchStatus::kSolverFailed) return "failed";
  if (s.status == SearchStatus::kFailedRegion) return "failed region";
  if (s.flat) return "flat";
  if (!s.parameter) return "–";
  std::string out = fmt::format("{:.4f}", *s.parameter);
  if (s.at_bound) out += " (bound)";
  if (s.local_minima > 1) out += " (multi)";
  return out;
}

}  // namespace

std::vector<TriStudyEntry> run_tri_study(const std::vector<TriStudyInput>& inputs, const std::vector<int>& degrees,
                                         const solvers::SolverInfo* solver,
                                         const std::function<void(const std::string&)>& progress) {
  const solvers::SolverInfo& backend = solver ? *solver : tri::default_tri_solver();
  std::vector<TriStudyEntry> out;
  for (const TriStudyInput& in : inputs) {
    TriStudyEntry entry{in.file, in.boundary, backend.name, solver == nullptr, {}};
    std::vector<int> own = {in.boundary.n};
    for (int d : degrees)
      if (d > in.boundary.n) own.push_back(d);
    for (const std::string& name : tri_study_objectives(in)) {
      std::string why;
      std::optional<TriObjective> objective = parse_tri_objective(name, &why);
      if (!objective) continue;  // every name of tri_study_objectives parses (tested)
      objective->target = in.target;
      TriStudyRow row{name, {}};
      for (int d : own) row.cells.push_back(study_cell(elevated(in.boundary, d), *objective, backend));
      entry.rows.push_back(std::move(row));
    }
    out.push_back(std::move(entry));
    if (progress) progress(fmt::format("triangle {} done", in.boundary.name));
  }
  return out;
}

json tri_study_results_json(const std::vector<TriStudyEntry>& entries) {
  json out = json::array();
  for (const TriStudyEntry& e : entries) {
    json objectives = json::object();
    for (const TriStudyRow& row : e.rows) {
      json cells = json::array();
      for (const TriStudyCell& c : row.cells)
        cells.push_back({{"degree", c.degree},
                         {"c", c.c.parameter ? number_or_null(*c.c.parameter) : json(nullptr)},
                         {"value", number_or_null(c.c.value)},
                         {"flat", c.c.flat},
                         {"at_bound", c.c.at_bound},
                         {"local_minima", c.c.local_minima},
                         {"status", to_string(c.c.status)},
                         {"bounds", {c.lower, c.upper}},
                         {"at_quadratic", number_or_null(c.quadratic)},
                         {"at_laplace", number_or_null(c.laplace)}});
      objectives[row.objective] = cells;
    }
    json solver = {{"name", e.solver}};
    if (e.solver_picked_automatically) solver["picked_by"] = "auto";
    out.push_back({{"kind", "triangle"},
                   {"boundary", e.boundary.name},
                   {"degree", e.boundary.n},
                   {"file", e.file},
                   {"solver", solver},
                   {"objectives", objectives}});
  }
  return out;
}

std::string tri_study_markdown(const std::vector<TriStudyEntry>& entries, const std::string& section_number) {
  if (entries.empty()) return "";
  std::string md;
  auto line = [&](const std::string& s) { md += s + "\n"; };
  line(fmt::format("## {}. Triangular boundaries: the best member c of the triangular family", section_number));
  line("");
  line("The mask b = a·(6 neighbours) + c·(3 far points), 6a + 3c = 1 (docs/math.md §9): c = −1/6 is the");
  line("quadratic-precision member, c = 0 the triangular Laplace mask. Per triangle, the optimal c of each objective");
  line("that exists for triangles (exact thin plate, E3, Dirichlet and twist energies; `target` is the mean squared");
  line("distance to the file's analytic surface) at its own degree and, sides elevated exactly, at each higher degree");
  line("of the study; the objective at c* against c = −1/6 and c = 0. `flat`: the objective does not depend on c;");
  line("`bound`: the optimum is on a search bound (given in results.json).");
  line("");
  for (const TriStudyEntry& e : entries) {
    line(fmt::format("### {} (triangle, degree {})", e.boundary.name, e.boundary.n));
    line("");
    line("| objective | degree | c* | value at c* | at c = −1/6 | at c = 0 |");
    line("|---|---|---|---|---|---|");
    for (const TriStudyRow& row : e.rows)
      for (const TriStudyCell& c : row.cells)
        line(fmt::format("| {} | {} | {} | {} | {} | {} |", row.objective, c.degree, format_c(c.c),
                         c.c.flat || !c.c.parameter ? "–" : fmt::format("{:.6g}", c.c.value),
                         std::isfinite(c.quadratic) ? fmt::format("{:.6g}", c.quadratic) : "failed",
                         std::isfinite(c.laplace) ? fmt::format("{:.6g}", c.laplace) : "failed"));
    line("");
  }
  return md;
}

}  // namespace coons
