#include "alpha_commands.h"

#include <algorithm>
#include <map>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <ceres/version.h>
#include <fmt/format.h>
#include <fmt/ostream.h>
#include <unistd.h>

#include "coons/alpha/alpha_search.h"
#include "coons/config.h"
#include "coons/curves/boundary_fit.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/net_json.h"
#include "coons/io/plot.h"
#include "coons/io/write_files.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask_families.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/metrics/bernstein.h"
#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"
#include "coons/net/degree_elevation.h"
#include "solvers/registry.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ---- targets ---------------------------------------------------------------------------------

std::vector<double> numbers_after_colon(const std::string& spec, size_t count, const std::string& field) {
  std::vector<double> out;
  std::stringstream in(spec.substr(spec.find(':') + 1));
  for (std::string item; std::getline(in, item, ',');) {
    try {
      size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(out.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("command line", field, "'" + item + "' is not a finite number");
    }
  }
  if (out.size() != count)
    throw InputError("command line", field, fmt::format("'{}' needs {} numbers after the colon", spec, count));
  return out;
}

Eigen::RowVector3d vec3(const json& j, const std::string& source, const std::string& field) {
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    throw InputError(source, field, "must be [x, y, z]");
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

double positive(const json& j, const std::string& source, const std::string& field) {
  if (!j.is_number() || !(j.get<double>() > 0)) throw InputError(source, field, "must be a positive number");
  return j.get<double>();
}

// The target of a boundary file: {"sphere": {"center", "radius"}} | {"cylinder": {"point",
// "axis", "radius"}} | {"plane": {"point", "normal"}}.
std::optional<Target> target_from_boundary_file(const std::string& path) {
  std::ifstream in(path);
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception&) {
    return std::nullopt;  // already reported by read_boundary_file
  }
  if (!doc.is_object() || !doc.contains("target")) return std::nullopt;
  const json& t = doc["target"];
  Target out;
  if (t.contains("sphere")) {
    out.kind = Target::Kind::kSphere;
    out.point = vec3(t["sphere"].value("center", json()), path, "target.sphere.center");
    out.radius = positive(t["sphere"].value("radius", json()), path, "target.sphere.radius");
  } else if (t.contains("cylinder")) {
    out.kind = Target::Kind::kCylinder;
    out.point = vec3(t["cylinder"].value("point", json()), path, "target.cylinder.point");
    out.direction = vec3(t["cylinder"].value("axis", json()), path, "target.cylinder.axis");
    out.radius = positive(t["cylinder"].value("radius", json()), path, "target.cylinder.radius");
  } else if (t.contains("plane")) {
    out.kind = Target::Kind::kPlane;
    out.point = vec3(t["plane"].value("point", json()), path, "target.plane.point");
    out.direction = vec3(t["plane"].value("normal", json()), path, "target.plane.normal");
  } else {
    throw InputError(path, "target", "must hold sphere, cylinder or plane");
  }
  if (out.direction.norm() == 0) throw InputError(path, "target", "axis/normal must not be zero");
  return out;
}

// --target: a closed-form net of the same boundary, a net file, or an analytic surface; when
// absent, the boundary file's own "target".
std::optional<Target> resolve_target(const std::string& spec, const std::string& boundary_path, const Boundary& b,
                                     int samples) {
  std::optional<Target> t;
  if (spec.empty()) {
    t = target_from_boundary_file(boundary_path);
  } else if (spec == "hermite-coons" || spec == "coons") {
    if (spec == "hermite-coons" && (b.m < 3 || b.n < 3))
      throw InputError(boundary_path, "degree", "--target hermite-coons needs degree >= 3 in both directions");
    t = Target{};
    t->net = spec == "coons" ? discrete_coons_net(b) : hermite_coons_net(b);
  } else if (spec.rfind("sphere:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 4, "--target");
    t = Target{Target::Kind::kSphere, {}, {v[0], v[1], v[2]}, {0, 0, 1}, v[3], samples};
  } else if (spec.rfind("cylinder:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 7, "--target");
    t = Target{Target::Kind::kCylinder, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], samples};
  } else if (spec.rfind("plane:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 6, "--target");
    t = Target{Target::Kind::kPlane, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, 1, samples};
  } else {
    const BoundaryFile f = read_boundary_file(spec);
    if (!f.net) throw InputError(spec, "net", "a target file must hold a \"net\"");
    t = Target{};
    t->net = *f.net;
  }
  if (t) {
    t->samples = samples;
    if (t->kind != Target::Kind::kNet && t->direction.norm() == 0)
      throw InputError("command line", "--target", "axis/normal must not be zero");
    if ((t->kind == Target::Kind::kSphere || t->kind == Target::Kind::kCylinder) && !(t->radius > 0))
      throw InputError("command line", "--target", "radius must be positive");
  }
  return t;
}

// ---- shared pieces of the search ---------------------------------------------------------------

std::string search_solver(const NetRequest& net, const Boundary& b, bool indefinite) {
  const auto stencil = mask_stencil(alpha_mask(-0.1), std::max(b.m - 1, 1), std::max(b.n - 1, 1));
  if (net.solver == "auto") {
    const std::string pick = solvers::choose_auto_solver(stencil);
    if (!indefinite) return pick;
    const solvers::SolverInfo* info = solvers::find_solver(pick);
    return info && !info->definite_only ? pick : "eigen-lu";
  }
  const solvers::SolverInfo* info = solvers::find_solver(net.solver);
  if (!info) throw InputError("command line", "--solver", "unknown solver '" + net.solver + "'");
  if (indefinite && info->definite_only)
    throw InputError("command line", "--solver", net.solver + " needs a positive definite system; bounds outside [-0.25, 0.25] need another solver");
  return net.solver;
}

std::optional<double> mu_of_alpha(const Boundary& b, std::optional<double> alpha) {
  if (!alpha || b.m != b.n || *alpha < -0.25 || *alpha >= 0) return std::nullopt;
  return mu_from_alpha(b.n, *alpha);
}

struct SearchSetup {
  Objective objective;
  MaskFamily family;
  AlphaSearchOptions options;
  std::string solver;
};

SearchSetup setup_search(const std::string& path, const Boundary& b, const NetRequest& net, const SearchRequest& r) {
  SearchSetup s;
  std::string why;
  auto objective = parse_objective(r.objective, &why);
  if (!objective) throw InputError("command line", "--objective", why);
  s.objective = *objective;
  if (r.samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  if (s.objective.target_weight > 0) {
    s.objective.target = resolve_target(r.target, path, b, r.samples);
    if (!s.objective.target)
      throw InputError("command line", "--target",
                       "the objective uses 'target' but neither --target nor the boundary file gives one");
  }
  bool indefinite = false;
  if (r.parameter == "alpha") {
    s.family = [](double a) { return alpha_family(a); };
    s.options.lower = r.lower.value_or(-0.25);
    s.options.upper = r.upper.value_or(0.25);
    indefinite = s.options.lower < -0.25 || s.options.upper > 0.25;
    if (indefinite && !r.allow_indefinite)
      throw InputError("command line", r.lower && *r.lower < -0.25 ? "--lower" : "--upper",
                       "bounds outside [-0.25, 0.25] make the system indefinite; add --allow-indefinite to search there");
  } else if (r.parameter == "mu") {
    // searched on the compressed scale s = μ/(μ + mn), so the scan spans μ's orders of magnitude
    const int m = b.m, n = b.n;
    s.family = [m, n](double t) { return mu_family_compressed(m, n, t); };
    const double lower = r.lower.value_or(0.0), upper = r.upper.value_or(1000.0 * m * n);
    if (!(lower >= 0 && std::isfinite(upper) && upper > lower))
      throw InputError("command line", "--lower/--upper", "mu bounds need 0 <= lower < upper < infinity");
    s.options.lower = compressed_of_mu(m, n, lower);
    s.options.upper = compressed_of_mu(m, n, upper);
  } else if (r.parameter == "alpha-gamma") {
    s.family = [](double a) { return alpha_family(a); };
    s.options.lower = r.lower.value_or(-0.25);
    s.options.upper = r.upper.value_or(0.25);
    if (s.options.lower < -0.25 || s.options.upper > 0.25)
      throw InputError("command line", "--lower/--upper", "the (alpha, gamma) search stays in [-0.25, 0.25]");
  } else {
    throw InputError("command line", "--parameter", "unknown parameter '" + r.parameter + "' (alpha, mu, alpha-gamma)");
  }
  s.options.scan_points = r.scan_points;
  if (!s.options.is_valid(&why)) throw InputError("command line", "--lower/--upper/--scan", why);
  s.solver = search_solver(net, b, indefinite);
  return s;
}

json search_report(const Boundary& b, const SearchRequest& r, const SearchSetup& setup, const AlphaSearchSummary& s,
                   const std::string& solver) {
  json out;
  out["boundary"] = b.name;
  out["degree"] = {b.m, b.n};
  out["objective"] = r.objective;
  out["parameter"] = r.parameter;
  std::optional<double> alpha, mu;
  if (s.parameter) {
    const MaskPoint p = setup.family(*s.parameter);
    alpha = p.mask.diag;
    if (r.parameter == "mu") mu = mu_of_compressed(b.m, b.n, *s.parameter);
    else mu = mu_of_alpha(b, alpha);
    out["beta"] = p.mask.edge_i == p.mask.edge_j ? json(p.mask.edge_i) : json(nullptr);
    if (p.mask.edge_i != p.mask.edge_j) out["beta_ij"] = {p.mask.edge_i, p.mask.edge_j};
  }
  out["alpha"] = alpha ? json(*alpha) : json(nullptr);
  out["mu"] = mu ? json(*mu) : json(nullptr);
  out["value"] = number_or_null(s.value);
  if (r.parameter == "mu")
    out["bounds"] = {mu_of_compressed(b.m, b.n, setup.options.lower), mu_of_compressed(b.m, b.n, setup.options.upper)};
  else
    out["bounds"] = {setup.options.lower, setup.options.upper};
  out["flat"] = s.flat;
  out["at_bound"] = s.at_bound;
  out["evaluations"] = s.evaluations;
  out["solves"] = s.solves;
  out["status"] = to_string(s.status);
  if (!s.message.empty()) out["message"] = s.message;
  out["local_minima"] = s.local_minima;
  json scan = json::array();
  for (auto [p, f] : s.scan) scan.push_back({r.parameter == "mu" ? mu_of_compressed(b.m, b.n, p) : p, number_or_null(f)});
  out["scan"] = scan;
  out["solver"] = solver;
  out["seconds"] = s.seconds;
  return out;
}

// ---- sweep -------------------------------------------------------------------------------------

struct SweepRow {
  double parameter;
  Mask9 mask;
  solvers::SolveSummary summary;
  NetMetrics metrics;
  std::optional<double> rms_target;
};

// Solves every mask of the sweep through the solver's sweep API: the right-hand side is
// e_i·B_Ei + e_j·B_Ej + d·B_K, so its three basis terms are computed (and transformed) once.
std::vector<SweepRow> run_sweep(const Boundary& b, const std::vector<double>& params, const MaskFamily& family,
                                const std::string& solver_name, const std::optional<Target>& target, bool progress,
                                std::vector<ControlNet>* nets = nullptr) {
  const ControlNet frame = frame_net(b);
  const int rows = std::max(b.m - 1, 0), cols = std::max(b.n - 1, 0);
  const solvers::SolverInfo* info = solvers::find_solver(solver_name);
  const std::vector<Eigen::MatrixX3d> basis = {mask_rhs(frame, Mask9{1, 0, 0}), mask_rhs(frame, Mask9{0, 1, 0}),
                                               mask_rhs(frame, Mask9{0, 0, 1})};
  std::vector<SweepRow> rows_out(params.size());
  std::vector<Eigen::SparseMatrix<double>> matrices;
  std::vector<solvers::LinearSolver::SweepMember> members;
  for (size_t k = 0; k < params.size(); ++k) {
    rows_out[k].parameter = params[k];
    rows_out[k].mask = family(params[k]).mask;
    solvers::LinearOperator op;
    op.stencil = mask_stencil(rows_out[k].mask, rows, cols);
    members.push_back({op, {rows_out[k].mask.edge_i, rows_out[k].mask.edge_j, rows_out[k].mask.diag}});
  }
  if (info->needs_matrix) {
    matrices.reserve(params.size());
    for (auto& m : members) {
      matrices.push_back(solvers::stencil_matrix(*m.op.stencil));
      m.op.matrix = &matrices.back();
    }
  }
  auto finish_row = [&](size_t k, const ControlNet& net) {
    rows_out[k].metrics = net_metrics(net, rows_out[k].mask);
    if (target) rows_out[k].rms_target = rms_distance(net, *target);
    if (nets) nets->push_back(net);
    if (progress) fmt::print(stderr, "\rsweep {}: {}/{}", b.name, k + 1, params.size());
  };
  if (rows * cols == 0) {
    for (size_t k = 0; k < params.size(); ++k) finish_row(k, frame);
  } else {
    auto solver = solvers::make_solver(solver_name);
    solver->sweep(basis, members, [&](size_t k, const Eigen::MatrixX3d& X, const solvers::SolveSummary& s) {
      rows_out[k].summary = s;
      finish_row(k, s.ok() ? fill_interior(frame, X) : frame);
    });
  }
  if (progress) fmt::print(stderr, "\n");
  return rows_out;
}

json sweep_line(const Boundary& b, const std::string& parameter, const SweepRow& row) {
  json line = metrics_to_json(row.metrics);
  line[parameter] = row.parameter;
  if (parameter != "alpha") line["alpha"] = row.mask.diag;
  if (row.mask.edge_i == row.mask.edge_j) line["beta"] = row.mask.edge_i;
  else line["beta_ij"] = {row.mask.edge_i, row.mask.edge_j};
  if (parameter == "alpha") {
    const auto mu = mu_of_alpha(b, row.parameter);
    line["mu"] = mu ? json(*mu) : json(nullptr);
  }
  line["status"] = solvers::to_string(row.summary.status);
  if (!row.summary.ok()) {
    line = json{{parameter, row.parameter}, {"status", solvers::to_string(row.summary.status)}, {"message", row.summary.message}};
  }
  if (row.rms_target && row.summary.ok()) line["rms_target"] = *row.rms_target;
  return line;
}

// Energy curves, each divided by its largest value, with each curve's minimum marked.
std::string plot_sweep(const std::string& png, const Boundary& b, const std::string& parameter,
                       const std::vector<SweepRow>& rows) {
  struct Curve {
    const char* name;
    double NetMetrics::*field;
  };
  const Curve curves[] = {{"thin plate", &NetMetrics::thin_plate_energy}, {"E3", &NetMetrics::e3_energy},
                          {"twist", &NetMetrics::twist_energy}, {"Dirichlet", &NetMetrics::dirichlet_energy}};
  std::vector<PlotSeries> series;
  PlotSeries minima{"minima", {}, {}, true};
  auto add = [&](const std::string& name, const std::vector<double>& values) {
    PlotSeries s{name, {}, {}, false};
    double top = 0;
    for (double v : values) top = std::max(top, std::abs(v));
    if (top == 0) return;
    size_t best = 0;
    for (size_t k = 0; k < rows.size(); ++k) {
      if (!rows[k].summary.ok()) continue;
      s.x.push_back(rows[k].parameter);
      s.y.push_back(values[k] / top);
      if (values[k] < values[best]) best = k;
    }
    minima.x.push_back(rows[best].parameter);
    minima.y.push_back(values[best] / top);
    series.push_back(std::move(s));
  };
  for (const Curve& c : curves) {
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r.metrics.*(c.field));
    add(c.name, v);
  }
  if (!rows.empty() && rows[0].rms_target) {
    std::vector<double> v;
    for (const auto& r : rows) v.push_back(r.rms_target.value_or(0));
    add("rms to target", v);
  }
  series.push_back(minima);
  PlotOptions o;
  o.title = fmt::format("{} ({}x{}): energies / their maximum", b.name, b.m, b.n);
  o.xlabel = parameter;
  o.ylabel = "normalised value";
  return plot_curves(png, series, o);
}

std::vector<double> linspace(double from, double to, int count) {
  std::vector<double> out(count);
  for (int k = 0; k < count; ++k) out[k] = count == 1 ? from : from + (to - from) * k / (count - 1);
  return out;
}

}  // namespace

void add_search_options(CLI::App& cmd, SearchRequest& r) {
  cmd.add_option("--objective", r.objective, "thin_plate, twist, dirichlet, e3, target, or a weighted sum "
                 "such as thin_plate+0.1*e3")->required();
  cmd.add_option("--parameter", r.parameter, "alpha (the Farin-Hansford family), mu (the anisotropic mask) or alpha-gamma (every symmetric 3x3 mask)")
      ->capture_default_str();
  cmd.add_option("--lower", r.lower, "lower bound (alpha: -0.25, mu: 0)");
  cmd.add_option("--upper", r.upper, "upper bound (alpha: 0.25, mu: 1000·m·n)");
  cmd.add_flag("--allow-indefinite", r.allow_indefinite, "accept alpha bounds outside [-0.25, 0.25]");
  cmd.add_option("--target", r.target, "hermite-coons | coons | NET.json | sphere:cx,cy,cz,r | "
                 "cylinder:px,py,pz,dx,dy,dz,r | plane:px,py,pz,nx,ny,nz (default: the boundary file's \"target\")");
  cmd.add_option("--scan", r.scan_points, "points of the coarse scan")->capture_default_str();
  cmd.add_option("--samples", r.samples, "target objective: samples per direction")->capture_default_str();
}

void add_sweep_options(CLI::App& cmd, SweepRequest& r) {
  cmd.add_option("--parameter", r.parameter, "alpha or mu")->capture_default_str();
  cmd.add_option("--from", r.from, "first value")->capture_default_str();
  cmd.add_option("--to", r.to, "last value")->capture_default_str();
  cmd.add_option("--count", r.count, "number of values")->capture_default_str();
  cmd.add_option("--out", r.out_dir, "output folder: NAME.sweep.jsonl and NAME.sweep.png")->capture_default_str();
  cmd.add_option("--target", r.target, "also report the rms distance to a target (as in search-alpha)");
  cmd.add_option("--samples", r.samples, "target: samples per direction")->capture_default_str();
}

void add_study_options(CLI::App& cmd, StudyRequest& r) {
  cmd.add_option("BOUNDARY", r.inputs, "boundary files or folders of them")->required();
  cmd.add_option("--degrees", r.degrees, "degrees to study each shape at")->capture_default_str();
  cmd.add_option("--out", r.out_dir, "output folder: report.md, figures, results.json")->capture_default_str();
}

int cmd_search_alpha(const std::string& path, const NetRequest& net, const SearchRequest& r) {
  const BoundaryFile input = read_input(path, net);
  const Boundary& b = input.boundary;
  const SearchSetup setup = setup_search(path, b, net, r);
  if (r.parameter == "alpha-gamma") {
    MaskObjective objective(b, setup.objective, setup.family, setup.solver);
    const AlphaGammaSummary g = search_alpha_gamma(objective, setup.options);
    json out = {{"boundary", b.name}, {"degree", {b.m, b.n}}, {"objective", r.objective}, {"parameter", r.parameter},
                {"alpha", g.flat ? json(nullptr) : json(g.alpha)}, {"gamma", g.flat ? json(nullptr) : json(g.gamma)},
                {"beta_ij", g.flat ? json(nullptr) : json({0.25 - g.alpha + g.gamma, 0.25 - g.alpha - g.gamma})},
                {"mu", nullptr}, {"value", number_or_null(g.value)}, {"value_at_gamma0", number_or_null(g.value_at_gamma0)},
                {"bounds", {setup.options.lower, setup.options.upper}}, {"flat", g.flat}, {"at_bound", false},
                {"evaluations", g.evaluations}, {"solves", g.solves}, {"status", to_string(g.status)}, {"solver", setup.solver}};
    if (!g.message.empty()) out["message"] = g.message;
    std::cout << out.dump(2) << '\n';
    return g.status == SearchStatus::kSolverFailed ? kExitSolverFailed : kExitOk;
  }
  // The α family is searched in the sine basis when it can be (search_alpha): no solve per evaluation.
  AlphaSearchSummary s;
  if (r.parameter == "alpha") {
    s = search_alpha(b, setup.objective, setup.solver, setup.options);
  } else if (r.parameter == "mu") {
    s = coons::search_mu(b, setup.objective, setup.solver, setup.options);
  } else {
    MaskObjective objective(b, setup.objective, setup.family, setup.solver);
    s = search_mask_parameter(objective, setup.options);
  }
  json report = search_report(b, r, setup, s, setup.solver);
  report["evaluator"] = s.evaluator.empty() ? "factorize and solve" : s.evaluator;
  std::cout << report.dump(2) << '\n';
  return s.status == SearchStatus::kSolverFailed ? kExitSolverFailed : kExitOk;
}

int cmd_refit(const std::string& path, const NetRequest& net, const RefitRequest& r) {
  const BoundaryFile input = read_input(path, net);
  const Boundary& b = input.boundary;
  if (r.degree.size() != 2 || r.degree[0] < 1 || r.degree[1] < 1 || r.degree[0] > 1000 || r.degree[1] > 1000)
    throw InputError("command line", "--degree", "needs two degrees M N in [1, 1000]");
  const int m = r.degree[0], n = r.degree[1];
  json out;
  if (const auto curves = read_boundary_curves(path)) {
    const FittedBoundary f = fit_boundary(*curves, m, n, b.name, path);
    out = boundary_to_json(f.boundary);
    out["method"] = "refit";
    out["max_deviation"] = f.max_deviation;
  } else if (m >= b.m && n >= b.n) {
    out = boundary_to_json(elevate_boundary(b, m, n));
    out["method"] = "elevated";
    out["max_deviation"] = 0.0;
  } else {
    throw InputError(path, "curves", fmt::format("degree ({}, {}) is below the boundary's ({}, {}); lowering it needs "
                                                 "the analytic sides (a \"curves\" object)", m, n, b.m, b.n));
  }
  // The new file keeps what belongs to the shape rather than to its degree: the analytic sides
  // (refit again) and the target (search-alpha --objective target).
  const json source = read_json_file(path);
  for (const char* key : {"curves", "target"})
    if (source.contains(key)) out[key] = source[key];
  if (r.out.empty()) {
    std::cout << out.dump(2) << '\n';
  } else {
    write_file_atomically(r.out, [&](std::ostream& o) { o << out.dump(2) << '\n'; });
    std::cout << json{{"boundary", b.name}, {"degree", {m, n}}, {"method", out["method"]}, {"max_deviation", out["max_deviation"]}, {"written", r.out}}.dump(2) << '\n';
  }
  return kExitOk;
}

void add_refit_options(CLI::App& cmd, RefitRequest& r) {
  cmd.add_option("--degree", r.degree, "the new degree M N")->required()->expected(2);
  cmd.add_option("--out", r.out, "write the boundary file here (default: standard output)");
}

int cmd_sweep(const std::string& path, const NetRequest& net, const SweepRequest& r) {
  const BoundaryFile input = read_input(path, net);
  const Boundary& b = input.boundary;
  if (r.count < 2 || r.count > 100000) throw InputError("command line", "--count", "must be between 2 and 100000");
  if (!(std::isfinite(r.from) && std::isfinite(r.to) && r.from < r.to))
    throw InputError("command line", "--from/--to", "need finite values with from < to");
  MaskFamily family;
  if (r.parameter == "alpha") {
    if (r.from < -0.25 || r.to > 0.25) throw InputError("command line", "--from/--to", "alpha must stay in [-0.25, 0.25]");
    family = [](double a) { return alpha_family(a); };
  } else if (r.parameter == "mu") {
    if (r.from < 0) throw InputError("command line", "--from", "mu must be >= 0");
    family = [m = b.m, n = b.n](double mu) { return mu_family(m, n, mu); };
  } else {
    throw InputError("command line", "--parameter", "unknown parameter '" + r.parameter + "' (alpha, mu)");
  }
  const std::optional<Target> target = r.target.empty() ? target_from_boundary_file(path)
                                                        : resolve_target(r.target, path, b, r.samples);
  const std::string solver = search_solver(net, b, false);
  const bool progress = isatty(STDERR_FILENO) != 0;
  const std::vector<SweepRow> rows = run_sweep(b, linspace(r.from, r.to, r.count), family, solver, target, progress);

  std::error_code ec;
  fs::create_directories(r.out_dir, ec);
  if (ec) throw InputError(r.out_dir, "--out", "cannot create the folder: " + ec.message());
  const std::string base = (fs::path(r.out_dir) / (b.name + ".sweep")).string();
  write_file_atomically(base + ".jsonl", [&](std::ostream& out) {
    for (const auto& row : rows) out << sweep_line(b, r.parameter, row).dump() << '\n';
  });
  const std::string plot_error = plot_sweep(base + ".png", b, r.parameter, rows);
  json summary = {{"boundary", b.name}, {"values", rows.size()}, {"jsonl", base + ".jsonl"}, {"solver", solver}};
  if (plot_error.empty()) summary["png"] = base + ".png";
  else summary["png_error"] = plot_error;
  std::cout << summary.dump(2) << '\n';
  for (const auto& row : rows)
    if (!row.summary.ok() && b.m > 1 && b.n > 1) return kExitSolverFailed;
  return kExitOk;
}

// ---- study -------------------------------------------------------------------------------------

namespace {

struct StudyCell {  // one shape at one degree
  int degree = 0;
  std::string objective;
  AlphaSearchSummary alpha, mu;
  std::optional<double> mu_equivalent;  // μ of α* (m = n)
};

std::string format_optimum(const AlphaSearchSummary& s, int digits = 4) {
  if (s.status == SearchStatus::kSolverFailed) return "failed";
  if (s.flat) return "flat";
  if (!s.parameter) return "–";
  std::string out = fmt::format("{:.{}f}", *s.parameter, digits);
  if (s.at_bound) out += " (bound)";
  if (s.local_minima > 1) out += " (multi)";
  return out;
}

// The μ optimum on [0, 1000·mn] (compressed scale), reported in μ units.
AlphaSearchSummary search_mu(const Boundary& b, const Objective& objective, const std::string& solver) {
  AlphaSearchOptions options;
  options.lower = 0;
  options.upper = compressed_of_mu(b.m, b.n, 1000.0 * b.m * b.n);
  AlphaSearchSummary s = coons::search_mu(b, objective, solver, options);
  if (s.parameter) s.parameter = mu_of_compressed(b.m, b.n, *s.parameter);
  return s;
}

std::string shell_output(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buffer[256];
    while (fgets(buffer, sizeof buffer, p)) out += buffer;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

}  // namespace

int cmd_study(const StudyRequest& r, const NetRequest& net) {
  const std::vector<std::string> files = expand_inputs(r.inputs);
  if (files.empty()) throw InputError("command line", "BOUNDARY", "no boundary files given or found");
  for (int d : r.degrees)
    if (d < 2 || d > 200) throw InputError("command line", "--degrees", fmt::format("{} is outside [2, 200]", d));
  std::vector<std::pair<std::string, BoundaryFile>> inputs;
  for (const auto& f : files) inputs.emplace_back(f, read_input(f, net));

  const fs::path out = r.out_dir, figures = out / "figures";
  std::error_code ec;
  fs::create_directories(figures, ec);
  if (ec) throw InputError(r.out_dir, "--out", "cannot create the folder: " + ec.message());
  const bool progress = isatty(STDERR_FILENO) != 0;
  const std::vector<std::string> objectives = {"thin_plate", "e3"};

  std::string md;
  json results = json::array();
  auto line = [&](const std::string& s) { md += s + "\n"; };
  const std::string date = shell_output("date -u +%Y-%m-%dT%H:%M:%SZ");
  const std::string git = shell_output("git describe --always --dirty 2>/dev/null");
  line("# The α study: which mask gives the best surface?");
  line("");
  line(fmt::format("Generated by `{}` on {} (coons {}{}, Eigen {}.{}.{}, Ceres {}). Every number below is computed by this run.",
                   r.command_line, date, COONS_VERSION, git.empty() ? "" : ", git " + git, EIGEN_WORLD_VERSION,
                   EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION, CERES_VERSION_STRING));
  line("");
  line("α is the weight of the four diagonal neighbours in b_ij = α·K + β·E (Farin & Hansford 1999); α = −1/4 is the");
  line("Coons net, α = 0 the Laplace net. μ is the degree-independent membrane weight of ∫‖p_uv‖² + μ∫‖∇p‖², with");
  line("α(n) = −n²/(4(n² + μ)) (docs/math.md §4). Optima come from `search_alpha` (coarse scan, then Ceres with the");
  line("analytic derivative; objectives over α are evaluated in the sine basis of the mask family, with no solve per");
  line("evaluation); `flat` means the objective does not depend on α, `bound` that the optimum is on a bound,");
  line("`multi` that the scan saw several local minima.");
  line("");

  // 1. Per shape at its own degree: Coons vs Laplace vs optimal, curves and pictures.
  line("## 1. Coons, Laplace and optimal nets at each shape's own degree");
  line("");
  line("| shape | degree | objective | α* | value at α* | at Coons (−1/4) | at Laplace (0) | μ* |");
  line("|---|---|---|---|---|---|---|---|");
  std::vector<std::string> figure_lines;
  for (const auto& [path, input] : inputs) {
    const Boundary& b = input.boundary;
    const std::string solver = search_solver(net, b, false);
    json shape = {{"boundary", b.name}, {"degree", {b.m, b.n}}, {"file", path}};
    std::optional<double> alpha_tp;
    for (const auto& name : objectives) {
      std::string why;
      const Objective objective = *parse_objective(name, &why);
      MaskObjective f(b, objective, [](double a) { return alpha_family(a); }, solver);
      const AlphaSearchSummary s = search_alpha(b, objective, solver);
      const double coons_value = f.evaluate(-0.25).value, laplace_value = f.evaluate(0.0).value;
      AlphaSearchSummary mu_s;
      if (b.m > 1 && b.n > 1) {
        mu_s = search_mu(b, objective, solver);
      }
      if (name == "thin_plate" && s.parameter && !s.flat) alpha_tp = s.parameter;
      line(fmt::format("| {} | {}×{} | {} | {} | {} | {:.6g} | {:.6g} | {} |", b.name, b.m, b.n, name, format_optimum(s),
                       s.flat ? "–" : fmt::format("{:.6g}", s.value), coons_value, laplace_value, format_optimum(mu_s, 3)));
      shape[name] = {{"alpha", s.parameter ? json(*s.parameter) : json(nullptr)}, {"value", number_or_null(s.value)},
                     {"flat", s.flat}, {"at_bound", s.at_bound}, {"coons", coons_value}, {"laplace", laplace_value},
                     {"mu", mu_s.parameter ? json(*mu_s.parameter) : json(nullptr)}, {"mu_flat", mu_s.flat},
                     {"mu_at_bound", mu_s.at_bound}, {"status", to_string(s.status)}};
    }
    // energy curves
    const std::vector<SweepRow> rows = run_sweep(b, linspace(-0.25, 0.25, 41), [](double a) { return alpha_family(a); },
                                                 solver, target_from_boundary_file(path), false);
    const std::string curves = (figures / (b.name + "_energies.png")).string();
    const std::string e1 = plot_sweep(curves, b, "alpha", rows);
    // pictures
    std::vector<std::pair<std::string, ControlNet>> nets = {{"Coons (α = −1/4)", discrete_coons_net(b)},
                                                            {"Laplace (α = 0)", solve_mask_net(b, alpha_mask(0), solver).net}};
    if (alpha_tp) nets.emplace_back(fmt::format("thin-plate optimum (α = {:.3f})", *alpha_tp), solve_mask_net(b, alpha_mask(*alpha_tp), solver).net);
    const std::string picture = (figures / (b.name + "_nets.png")).string();
    const std::string e2 = plot_nets(picture, nets, 25, b.name);
    figure_lines.push_back(fmt::format("### {}\n", b.name));
    figure_lines.push_back(e1.empty() ? fmt::format("![energies of {}](figures/{}_energies.png)\n", b.name, b.name) : "(energy plot failed: " + e1 + ")\n");
    figure_lines.push_back(e2.empty() ? fmt::format("![nets of {}](figures/{}_nets.png)\n", b.name, b.name) : "(picture failed: " + e2 + ")\n");
    results.push_back(shape);
    if (progress) fmt::print(stderr, "\rstudy: shape {} done", b.name);
  }
  line("");

  // 2. Degree dependence.
  line("## 2. How the optimum moves with the degree");
  line("");
  line("A boundary given by curves (analytic sides) is refitted at each degree (d, d); any other boundary is");
  line("degree-elevated exactly (its curves do not change) for d ≥ its own degree, and left out (–) below it. The law α* + 1/4 ≈ c/n² is fitted");
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
  std::vector<PlotSeries> law_series, mu_series;
  std::vector<std::string> fit_rows;  // shapes given by curves: deviation of the fit per degree
  for (const auto& [path, input] : inputs) {
    const Boundary& native = input.boundary;
    const std::optional<std::vector<Curve>> curves = read_boundary_curves(path);
    // A shape at degree d: refitted from its curves when it has them, else elevated exactly.
    std::map<int, Boundary> at_degree;
    std::string fit_row = fmt::format("| {} |", native.name);
    for (int d : r.degrees) {
      if (curves) {
        const FittedBoundary f = fit_boundary(*curves, d, d, native.name, path);
        at_degree.emplace(d, f.boundary);
        fit_row += fmt::format(" {:.2e} |", f.max_deviation);
      } else if (d >= native.m && d >= native.n) {
        at_degree.emplace(d, elevate_boundary(native, d, d));
      }
    }
    if (curves) fit_rows.push_back(fit_row);
    for (const auto& name : objectives) {
      std::string why;
      const Objective objective = *parse_objective(name, &why);
      std::string row = fmt::format("| {} | {} |", native.name, name);
      std::vector<std::pair<int, double>> interior;
      std::string mus;
      PlotSeries mu_line{native.name + " " + name, {}, {}, false};
      json by_degree = json::array();
      for (int d : r.degrees) {
        if (!at_degree.count(d)) {
          row += " – |";
          continue;
        }
        const Boundary& b = at_degree.at(d);
        const std::string solver = search_solver(net, b, false);
        const AlphaSearchSummary s = search_alpha(b, objective, solver);
        const AlphaSearchSummary mu_s = search_mu(b, objective, solver);
        row += " " + format_optimum(s) + " |";
        if (s.parameter && !s.flat && !s.at_bound) interior.emplace_back(d, *s.parameter);
        if (mu_s.parameter && !mu_s.flat && !mu_s.at_bound) {
          mus += fmt::format("{}{:.3g}", mus.empty() ? "" : ", ", *mu_s.parameter);
          mu_line.x.push_back(d);
          mu_line.y.push_back(*mu_s.parameter);
        } else {
          mus += std::string(mus.empty() ? "" : ", ") + format_optimum(mu_s, 1);
        }
        by_degree.push_back({{"degree", d}, {"alpha", s.parameter ? json(*s.parameter) : json(nullptr)},
                             {"flat", s.flat}, {"at_bound", s.at_bound},
                             {"mu", mu_s.parameter ? json(*mu_s.parameter) : json(nullptr)},
                             {"mu_flat", mu_s.flat}, {"mu_at_bound", mu_s.at_bound}});
      }
      // fit α* + 1/4 = c/n²
      double num = 0, den = 0;
      for (auto [d, a] : interior) {
        num += (a + 0.25) / (double(d) * d);
        den += 1.0 / (double(d) * d * d * d);
      }
      if (interior.size() >= 2 && den > 0) {
        const double c = num / den;
        double misfit = 0;
        PlotSeries measured{native.name + " " + name + " α*+1/4", {}, {}, true};
        PlotSeries law{native.name + " " + name + " c/n²", {}, {}, false};
        for (auto [d, a] : interior) {
          misfit = std::max(misfit, std::abs((a + 0.25) - c / (double(d) * d)) / std::max(std::abs(a + 0.25), 1e-300));
          measured.x.push_back(d);
          measured.y.push_back(a + 0.25);
        }
        for (int d = r.degrees.front(); d <= r.degrees.back(); ++d) {
          law.x.push_back(d);
          law.y.push_back(c / (double(d) * d));
        }
        if (name == "thin_plate") {
          law_series.push_back(measured);
          law_series.push_back(law);
        }
        row += fmt::format(" {:.4g} | {:.1f}% |", c, 100 * misfit);
        results.push_back({{"boundary", native.name}, {"objective", name}, {"by_degree", by_degree}, {"c", c}, {"misfit", misfit}});
      } else {
        row += " – | – |";
        results.push_back({{"boundary", native.name}, {"objective", name}, {"by_degree", by_degree}});
      }
      row += " " + (mus.empty() ? "–" : mus) + " |";
      line(row);
      if (name == "thin_plate" && mu_line.x.size() >= 2) mu_series.push_back(mu_line);
    }
    if (progress) fmt::print(stderr, "\rstudy: degrees of {} done        ", native.name);
  }
  if (progress) fmt::print(stderr, "\n");
  line("");
  if (!fit_rows.empty()) {
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
    for (const auto& fr : fit_rows) line(fr);
    line("");
  }
  PlotOptions law_options{"thin-plate optimum: α* + 1/4 against degree, with the fitted c/n²", "degree n", "α* + 1/4", true, true, 1100, 700};
  const std::string law_error = law_series.empty() ? "no shape has two interior optima" : plot_curves((figures / "alpha_vs_degree.png").string(), law_series, law_options);
  line(law_error.empty() ? "![α* against degree](figures/alpha_vs_degree.png)" : "(α* plot: " + law_error + ")");
  line("");
  PlotOptions mu_options{"thin-plate optimum μ* against degree (flat if the c/n² law holds)", "degree n", "μ*", false, false, 1100, 700};
  const std::string mu_error = mu_series.empty() ? "no shape has two interior μ optima" : plot_curves((figures / "mu_vs_degree.png").string(), mu_series, mu_options);
  line(mu_error.empty() ? "![μ* against degree](figures/mu_vs_degree.png)" : "(μ* plot: " + mu_error + ")");
  line("");

  // 3. The dome table of docs/math.md §7.
  for (const auto& [path, input] : inputs) {
    if (input.boundary.name != "dome") continue;
    const Boundary& b = input.boundary;
    const std::string solver = search_solver(net, b, false);
    line("## 3. The dome (docs/math.md §7): a Farin–Hansford table");
    line("");
    const std::optional<Target> sphere = target_from_boundary_file(path);
    line(std::string("| α | S(½,½).z | thin plate | Dirichlet |") + (sphere ? " rms distance to the sphere |" : ""));
    line(std::string("|---|---|---|---|") + (sphere ? "---|" : ""));
    for (double a : {-0.25, -0.2, -0.1, 0.0}) {
      const ControlNet n = solve_mask_net(b, alpha_mask(a), solver).net;
      line(fmt::format("| {} | {:.6f} | {:.3f} | {:.3f} |", a, evaluate(n, 0.5, 0.5)(2), thin_plate_energy(n), dirichlet_energy(n)) +
           (sphere ? fmt::format(" {:.4f} |", rms_distance(n, *sphere)) : ""));
    }
    if (sphere) {
      Objective o;
      o.name = "target";
      o.target_weight = 1;
      o.target = sphere;
      const AlphaSearchSummary s = search_alpha(b, o, solver);
      line("");
      line(fmt::format("The α that fits the sphere best: {} (rms {:.4g}, against {:.4g} for the Coons net: {:.0f}× closer).",
                       format_optimum(s), s.value, rms_distance(discrete_coons_net(b), *sphere),
                       rms_distance(discrete_coons_net(b), *sphere) / s.value));
    }
    line("");
  }

  line("## 4. Energy curves and nets, shape by shape");
  line("");
  for (const auto& l : figure_lines) line(l);

  write_file_atomically((out / "results.json").string(), [&](std::ostream& o) { o << results.dump(1) << '\n'; });
  write_file_atomically((out / "report.md").string(), [&](std::ostream& o) { o << md; });
  std::cout << md << '\n' << fmt::format("report: {}\n", (out / "report.md").string());
  return kExitOk;
}

}  // namespace coons::cli
