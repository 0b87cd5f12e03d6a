#include "study.h"

#include <fmt/format.h>

#include <map>

#include "coons/alpha/family_search.h"
#include "coons/io/boundary_curves.h"
#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "coons/mask/mask_families.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/mask/stencil.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/backend_choice.h"
#include "coons/study/study_failures.h"
#include "coons/study/target.h"
#include "coons/study/two_ring_problem.h"

namespace coons {

using nlohmann::json;

StudyInput read_study_input(const std::string& path, const BoundaryReadOptions& options) {
  return read_study_input(path, read_boundary_file(path, options));
}

StudyInput read_study_input(const std::string& path, const BoundaryFile& file) {
  StudyInput in;
  in.file = path;
  if (file.bspline)
    throw InputError(path, "knots_u",
                     "a B-spline boundary is not elevated over Bézier degrees, so degree studies do not apply to it "
                     "(`coons study` gives it one row at its own knots)");
  in.boundary = file.boundary;
  in.misspelt = file.misspelt;
  TwoRingProblem two = two_ring_problem(file);
  if (two.problem) {
    const std::vector<ProblemIssue> issues = check_stencil_problem(*two.problem, c1_family_stencil(0.5));
    if (!issues.empty()) throw InputError(path, issues.front().field, issues.front().reason);
    in.two_rings = std::move(two.problem);
  } else {
    in.one_ring = two.field == "ribbons" ? "one data ring, no ribbons" : "one data ring, rings 1";
  }
  in.curves = read_boundary_curves(path);
  in.target = read_boundary_target(path);
  return in;
}

std::vector<Objective> default_study_objectives() {
  std::vector<Objective> out;
  for (const char* name : {"thin_plate", "e3"}) {
    std::string why;
    out.push_back(*parse_objective(name, &why));
  }
  return out;
}

bool StudyOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (degrees.empty()) return fail("no degrees");
  for (size_t k = 0; k < degrees.size(); ++k) {
    if (degrees[k] < 2 || degrees[k] > 200) return fail(fmt::format("{} is outside [2, 200]", degrees[k]));
    if (k > 0 && degrees[k] <= degrees[k - 1]) return fail("degrees must be given in increasing order, each once");
  }
  if (curve_points < 2) return fail("curve_points must be >= 2");
  for (const auto& o : objectives)
    if (o.target_weight > 0) return fail("objective '" + o.name + "' needs a target; the study has one per shape");
  for (double a : reference_alphas)
    if (!(a >= -0.25 && a <= 0.25)) return fail(fmt::format("reference alpha {} is outside [-0.25, 0.25]", a));
  return true;
}

AlphaSearchSummary study_search_mu(const Boundary& b, const Objective& objective, const solvers::SolverInfo& solver) {
  const MuScale scale{b.m, b.n, 0.0, 1000.0 * b.m * b.n};
  AlphaSearchOptions options;
  options.lower = scale.s_lower();
  options.upper = scale.s_upper();
  AlphaSearchSummary s = search_mu(b, objective, solver, options);
  if (s.parameter) s.parameter = scale.mu(*s.parameter);
  return s;
}

StudyResult run_study(const std::vector<StudyInput>& inputs, const StudyOptions& options,
                      const std::function<void(const std::string&)>& progress) {
  const std::vector<Objective> objectives =
      options.objectives.empty() ? default_study_objectives() : options.objectives;
  auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  StudyResult result;
  result.degrees = options.degrees;
  for (const auto& o : objectives) result.objectives.push_back(o.name);

  // Every shape at every degree first: a refit that fails is an input error before any work.
  std::vector<std::map<int, Boundary>> at_degree(inputs.size());
  for (size_t k = 0; k < inputs.size(); ++k) {
    const StudyInput& in = inputs[k];
    FitDeviationEntry deviations{in.boundary.name, {}};
    for (int d : options.degrees) {
      if (in.curves) {
        const FittedBoundary f = fit_boundary_or_throw(*in.curves, d, d, in.boundary.name, in.file);
        at_degree[k].emplace(d, f.boundary);
        deviations.max_deviation.emplace_back(d, f.max_deviation);
      } else if (d >= in.boundary.m && d >= in.boundary.n) {
        at_degree[k].emplace(d, elevate_boundary(in.boundary, d, d));
      }
    }
    if (in.curves) result.fit_deviations.push_back(std::move(deviations));
  }

  // 1. Each shape at its own degree.
  for (const StudyInput& in : inputs) {
    const Boundary& b = in.boundary;
    const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
    ShapeEntry shape{in.file, b, solver.name, options.solver == nullptr, {}, {}, in.one_ring, {}, {}};
    const solvers::SolverInfo& weight_solver = weight_search_backend(options.solver);
    if (in.two_rings) shape.weight_solver = weight_solver.name;
    if (!in.two_rings && shape.one_ring.empty()) shape.one_ring = "one data ring";
    std::optional<double> alpha_tp;
    for (const Objective& objective : objectives) {
      MaskObjective f(
          b, objective, [](double a) { return alpha_family(a); }, solver);
      ShapeOptimum o;
      o.objective = objective.name;
      o.alpha = search_alpha(b, objective, solver);
      // a value only where its solve succeeded (NaN: reported as failed / null, never as a number)
      const auto value_at = [&](double a) {
        const auto e = f.evaluate(a);
        return e.ok() ? e.value : std::numeric_limits<double>::quiet_NaN();
      };
      o.coons = value_at(-0.25);
      o.laplace = value_at(0.0);
      if (b.m > 1 && b.n > 1) o.mu = study_search_mu(b, objective, solver);
      if (in.two_rings) o.weight = search_weight(*in.two_rings, objective, weight_solver);
      if (objective.name == "thin_plate" && o.alpha.parameter && !o.alpha.flat) alpha_tp = o.alpha.parameter;
      shape.optima.push_back(std::move(o));
    }
    shape.curves = run_sweep(
        b, linspace(-0.25, 0.25, options.curve_points), [](double a) { return alpha_family(a); }, solver, in.target);
    // a picture only of a net whose solve succeeded (a failed one is the frame with a zero inside)
    shape.pictures = {{"Coons (α = −1/4)", discrete_coons_net(b)}};
    if (MaskSolveResult laplace = solve_mask_net(b, alpha_mask(0), solver); laplace.summary.ok())
      shape.pictures.emplace_back("Laplace (α = 0)", std::move(laplace.net));
    if (alpha_tp)
      if (MaskSolveResult best = solve_mask_net(b, alpha_mask(*alpha_tp), solver); best.summary.ok())
        shape.pictures.emplace_back(fmt::format("thin-plate optimum (α = {:.3f})", *alpha_tp), std::move(best.net));
    result.shapes.push_back(std::move(shape));
    say(fmt::format("shape {} done", b.name));
  }

  // 2. The optimum against the degree, and the degree law.
  for (size_t k = 0; k < inputs.size(); ++k) {
    const Boundary& native = inputs[k].boundary;
    for (const Objective& objective : objectives) {
      DegreeLawEntry law{native.name, objective.name, {}, {}, std::nullopt};
      for (int d : options.degrees) {
        if (!at_degree[k].count(d)) continue;
        const Boundary& b = at_degree[k].at(d);
        const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
        DegreeCell cell{d, search_alpha(b, objective, solver), study_search_mu(b, objective, solver)};
        if (cell.alpha.parameter && !cell.alpha.flat && !cell.alpha.at_bound)
          law.interior.emplace_back(d, *cell.alpha.parameter);
        law.cells.push_back(std::move(cell));
      }
      law.fit = fit_degree_law(law.interior);
      result.laws.push_back(std::move(law));
    }
    say(fmt::format("degrees of {} done", native.name));
  }

  // 3. A reference table for every shape with a target.
  for (const StudyInput& in : inputs) {
    if (!in.target) continue;
    const Boundary& b = in.boundary;
    const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
    ReferenceTable table{b.name, b.m, b.n, {}, {}, 0};
    for (double a : options.reference_alphas) {
      const MaskSolveResult solved = solve_mask_net(b, alpha_mask(a), solver);
      if (!solved.summary.ok()) {  // no numbers from a failed solve: the row says failed
        const double failed = std::numeric_limits<double>::quiet_NaN();
        table.rows.push_back({a, failed, failed, failed, failed});
        continue;
      }
      const ControlNet& net = solved.net;
      table.rows.push_back({a, evaluate(net, 0.5, 0.5)(2), thin_plate_energy(net), dirichlet_energy(net),
                            rms_distance(net, *in.target)});
    }
    Objective o;
    o.name = "target";
    o.target_weight = 1;
    o.target = in.target;
    table.best = search_alpha(b, o, solver);
    table.coons_rms = rms_distance(discrete_coons_net(b), *in.target);
    result.references.push_back(std::move(table));
    say(fmt::format("reference table of {} done", b.name));
  }
  return result;
}

json study_results_json(const StudyResult& r) {
  json results = json::array();
  for (const ShapeEntry& shape : r.shapes) {
    const Boundary& b = shape.boundary;
    json entry = {{"kind", "shape"}, {"boundary", b.name}, {"degree", {b.m, b.n}}, {"file", shape.file}};
    // the solver block of every report; its seconds are left out so that reruns compare equal. Its
    // status is that of every solve of the shape at its own degree (study_failures.h); iterations
    // counts the linear solves of the α* and μ* searches, as in search-alpha's report.
    int solves = 0;
    for (const ShapeOptimum& o : shape.optima) solves += o.alpha.solves + o.mu.solves;
    const std::vector<std::string> failures = shape_failures(shape);
    entry["solver"] = {{"name", shape.solver},
                       {"status", failures.empty() ? "success" : "failure"},
                       {"iterations", solves},
                       {"relative_residual", nullptr}};
    if (!failures.empty()) {
      std::string message;
      for (const std::string& f : failures) message += (message.empty() ? "" : "; ") + f;
      entry["solver"]["message"] = message;
    }
    if (shape.solver_picked_automatically) entry["solver"]["picked_by"] = "auto";
    for (const ShapeOptimum& o : shape.optima) {
      const AlphaSearchSummary& s = o.alpha;
      const AlphaSearchSummary& mu = o.mu;
      entry[o.objective] = {{"alpha", optional_number(s.parameter)},
                            {"value", number_or_null(s.value)},
                            {"flat", s.flat},
                            {"at_bound", s.at_bound},
                            {"local_minima", s.local_minima},
                            {"coons", number_or_null(o.coons)},
                            {"laplace", number_or_null(o.laplace)},
                            {"mu", optional_number(mu.parameter)},
                            {"mu_flat", mu.flat},
                            {"mu_at_bound", mu.at_bound},
                            {"mu_local_minima", mu.local_minima},
                            {"status", to_string(s.status)}};
      if (o.weight) {  // the C1 family beside α* (inputs with two data rings only)
        json& block = entry[o.objective];
        block["weight"] = optional_number(o.weight->parameter);
        block["weight_value"] = number_or_null(o.weight->value);
        block["weight_flat"] = o.weight->flat;
        block["weight_at_bound"] = o.weight->at_bound;
        block["weight_status"] = to_string(o.weight->status);
      }
    }
    if (!shape.weight_solver.empty()) entry["weight_solver"] = shape.weight_solver;
    results.push_back(std::move(entry));
  }
  for (const DegreeLawEntry& law : r.laws) {
    json by_degree = json::array();
    for (const DegreeCell& c : law.cells)
      by_degree.push_back({{"degree", c.degree},
                           {"alpha", optional_number(c.alpha.parameter)},
                           {"flat", c.alpha.flat},
                           {"at_bound", c.alpha.at_bound},
                           {"local_minima", c.alpha.local_minima},
                           {"status", to_string(c.alpha.status)},
                           {"mu", optional_number(c.mu.parameter)},
                           {"mu_flat", c.mu.flat},
                           {"mu_at_bound", c.mu.at_bound},
                           {"mu_status", to_string(c.mu.status)}});
    json entry = {
        {"kind", "degree_law"}, {"boundary", law.boundary}, {"objective", law.objective}, {"by_degree", by_degree}};
    if (law.fit) {
      entry["c"] = number_or_null(law.fit->c);
      entry["misfit"] = number_or_null(law.fit->misfit);
    }
    results.push_back(std::move(entry));
  }
  for (const FitDeviationEntry& f : r.fit_deviations) {
    json by_degree = json::array();
    for (auto [d, dev] : f.max_deviation) by_degree.push_back({{"degree", d}, {"max_deviation", number_or_null(dev)}});
    results.push_back({{"kind", "fit_deviation"}, {"boundary", f.boundary}, {"by_degree", by_degree}});
  }
  for (const ReferenceTable& t : r.references) {
    json rows = json::array();
    for (const ReferenceRow& row : t.rows)
      rows.push_back({{"alpha", row.alpha},
                      {"center_z", number_or_null(row.center_z)},
                      {"thin_plate", number_or_null(row.thin_plate)},
                      {"dirichlet", number_or_null(row.dirichlet)},
                      {"rms_target", number_or_null(row.rms_target)}});
    const AlphaSearchSummary& s = t.best;
    results.push_back({{"kind", "reference_table"},
                       {"boundary", t.boundary},
                       {"degree", {t.m, t.n}},
                       {"rows", rows},
                       {"best_fit",
                        {{"alpha", optional_number(s.parameter)},
                         {"rms_target", number_or_null(s.value)},
                         {"flat", s.flat},
                         {"at_bound", s.at_bound},
                         {"local_minima", s.local_minima},
                         {"status", to_string(s.status)}}},
                       {"coons_rms_target", number_or_null(t.coons_rms)},
                       {"coons_over_best", s.status == SearchStatus::kSuccess && s.parameter && s.value > 0
                                               ? number_or_null(t.coons_rms / s.value)
                                               : json(nullptr)}});
  }
  for (json& entry : tri_study_results_json(r.triangles)) results.push_back(std::move(entry));
  return results;
}

}  // namespace coons
