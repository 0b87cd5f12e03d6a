// solve, export, search-alpha and sweep on triangular boundaries (tri_commands.h).
#include "tri_commands.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/matrix_market.h"
#include "coons/io/net_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/tri_mesh_export.h"
#include "coons/io/write_files.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/search_report.h"
#include "coons/study/sweep.h"
#include "coons/study/target.h"
#include "coons/study/tri_report.h"
#include "coons/study/tri_search.h"
#include "coons/tri/tri_sampling.h"
#include "report_output.h"

namespace coons::cli {

namespace {

tri::TriBoundary read_tri_input(const std::string& path, double corner_tolerance, double min_model_size = 0) {
  check_corner_tolerance(corner_tolerance);
  TriBoundaryReadOptions options;
  options.corner_tolerance = corner_tolerance;
  options.min_model_size = min_model_size;
  return read_tri_boundary_file(path, options);
}

//! --solver for triangles: auto is an LU-type backend (default_tri_solver).
const solvers::SolverInfo& tri_backend(const std::string& name, bool& picked_automatically) {
  const solvers::SolverInfo* info = solver_from_name(name);
  picked_automatically = info == nullptr;
  return info ? *info : tri::default_tri_solver();
}

//! An InputError naming --solver when a backend given by name cannot solve the masks of a c range
//! (a search's or a sweep's): one that is only for definite systems fails at every c != 0, so a
//! search tried all its scan points before it said so (exit 3), where view refused it at once.
void require_tri_range_backend(const solvers::SolverInfo& solver, bool picked_automatically, double lower,
                               double upper) {
  if (picked_automatically) return;
  const double c = lower != 0.0 ? lower : upper;  // (lower < upper: one of them is not 0)
  if (const tri::TriBackendCheck check = tri::check_tri_backend(solver, tri::TriMask{c}); !check.applicable)
    throw InputError("command line", "--solver",
                     tri::check_tri_backend(solver, tri::TriMask{0.0}).applicable  // refused for c != 0 only
                         ? fmt::format("{} (the c range [{}, {}] holds such c)", check.reason, lower, upper)
                         : check.reason);
}

// A triangle of degree n is bounded by the (n+1)×(n+1) grid's memory (about half of it).
void check_tri_memory(const GlobalOptions& g, int n, const solvers::SolverInfo* solver, const std::string& file,
                      double extra = 0) {
  check_memory(g, net_solve_bytes(n, n, solver) + net_metrics_bytes(n, n) + extra,
               fmt::format("a triangular net of degree {}", n), file, "degree");
}

// The request of solve/export for a triangle: only --method alpha, no --mu, --omega or
// --allow-indefinite (they have no meaning here); c defaults to −1/6.
struct TriRequest {
  tri::TriSolveOptions options;
  bool picked_automatically = false;
};

TriRequest resolve_tri(const NetRequest& r) {
  if (given(r.method_option) && r.method != Method::kAlpha)
    throw InputError("command line", "--method",
                     "a triangular boundary has only --method alpha (the mask family over c, --alpha c)");
  const std::pair<const CLI::Option*, const char*> not_triangular[] = {
      {r.mu_option, "--mu"},     {r.omega_option, "--omega"},   {r.indefinite_option, "--allow-indefinite"},
      {r.mask_option, "--mask"}, {r.weight_option, "--weight"}, {r.threads_option, "--threads"}};
  for (const auto& [option, name] : not_triangular)
    if (given(option)) throw InputError("command line", name, "does not apply to a triangular boundary");
  TriRequest out;
  out.options.mask.c = given(r.alpha_option) ? r.alpha : -1.0 / 6;
  require_alpha_value(out.options.mask.c);
  out.options.solver = &tri_backend(r.solver, out.picked_automatically);
  refuse_stopping_rules(r, out.options.solver);
  out.options.solver_options.tolerance = r.tolerance;
  out.options.solver_options.max_iterations = r.max_iterations;
  out.options.solver_options.time_limit_seconds = r.time_limit;
  require_valid_solver_options(out.options.solver_options);
  // A backend named that solves the c = 0 member only (Cholesky-type, CG: the system is symmetric
  // there alone) is refused a c it does not accept as bad input, as the rectangle's --alpha outside
  // the definite range is (docs/formats.md, Errors); one that never applies reports not_applicable.
  if (!out.picked_automatically)
    if (const tri::TriBackendCheck check = tri::check_tri_backend(*out.options.solver, out.options.mask);
        !check.applicable && tri::check_tri_backend(*out.options.solver, tri::TriMask{0.0}).applicable)
      throw InputError("command line", "--alpha",
                       fmt::format("c = {} is not accepted by {}: {} (use umfpack, eigen-lu, bicgstab or gmres)",
                                   out.options.mask.c, out.options.solver->name, check.reason));
  return out;
}

// c*ₙ makes the system singular (the bubble i·j·k is a null vector): with a consistent right-hand
// side an iterative backend then returns one of many nets and calls it a success, so every
// backend is refused the same way, as for a singular rectangle. 1e-12: within it the condition
// number exceeds 1e12.
void refuse_singular_member(const tri::TriBoundary& b, double c, const std::string& path) {
  const std::optional<double> star = tri::bubble_singular_c(b.n);
  if (star && std::abs(c - *star) <= 1e-12 * std::abs(*star))
    throw InputError(
        path, "--alpha",
        fmt::format("the mask system is singular: c = {} is the member c*_{} = -1/6 - 1/(2(n-3)) = {:.17g}, "
                    "at which the bubble i*j*k is a null vector",
                    c, b.n, *star));
}

}  // namespace

int run_tri_solve(const std::string& path, const NetRequest& net, const GlobalOptions& global) {
  Phases phases("solve");
  phases.start("read");
  const tri::TriBoundary b = read_tri_input(path, net.corner_tolerance);
  const TriRequest r = resolve_tri(net);
  check_tri_memory(global, b.n, r.options.solver, path);
  refuse_singular_member(b, r.options.mask.c, path);
  phases.start("solve");
  const tri::TriSolveResult result = tri::solve_tri_net(b, r.options);
  phases.start("metrics");
  const nlohmann::json report = tri_solve_report(b, r.options.mask, result, r.picked_automatically);
  print_net_report(report, nullptr, phases, true);  // one point per line, as the rectangle's net; timing last
  if (!result.summary.ok()) {
    print_solver_failure(path, result.summary);
    return kExitSolverFailed;
  }
  return kExitOk;
}

int run_tri_export(const TriExportArgs& e) {
  Phases phases("export");
  phases.start("read");
  const bool all = !e.obj && !e.mtx && !e.ply && !e.vtu;
  // the curvatures of PLY and VTU (asked for, or the defaults) leave the doubles below
  // kMinModelSize (Gaussian ~ 1/size²)
  const tri::TriBoundary b =
      read_tri_input(e.boundary, e.net->corner_tolerance, all || e.ply || e.vtu ? kMinModelSize : 0.0);
  const TriRequest r = resolve_tri(*e.net);
  const bool obj = all || e.obj, ply = all || e.ply, vtu = all || e.vtu;
  // a net of degree 2 or less has no interior: its system of no unknowns ("0 0 0", which no
  // reader takes) is not written by default, and asked for, bad input
  const bool unknowns = tri::interior_size(b.n) > 0;
  if (e.mtx && !unknowns)
    throw InputError(e.boundary, "--mtx",
                     fmt::format("a triangle of degree {} has no interior point: there is no system to write", b.n));
  const bool mtx = (all && unknowns) || e.mtx;
  check_export_options(e.samples, mtx, true, e.prefix);  // a triangle has --method alpha only
  const bool surface = obj || ply || vtu;
  const double sample_bytes = surface ? samples_bytes(e.samples) / 2 : 0.0;  // a triangle holds half the grid
  // samples that alone exceed the budget are --samples' fault, not the degree's
  check_memory(*e.global, sample_bytes, fmt::format("{} x {} surface samples", e.samples, e.samples), "command line",
               "--samples");
  check_tri_memory(*e.global, b.n, r.options.solver, e.boundary, sample_bytes);
  refuse_singular_member(b, r.options.mask.c, e.boundary);
  const std::string prefix = e.prefix.empty() ? safe_file_stem(b.name) : e.prefix;

  OutputSet out(e.out_dir, "--out");
  std::vector<std::string> names;
  if (obj) names.insert(names.end(), {prefix + ".surface.obj", prefix + ".net.obj"});
  if (ply) names.push_back(prefix + ".surface.ply");
  if (vtu) names.push_back(prefix + ".surface.vtu");
  if (mtx) names.insert(names.end(), {prefix + ".A.mtx", prefix + ".B.mtx"});
  for (const auto& name : names) require_new_output(out.path_of(name), e.global->force, "--out");

  nlohmann::json report = {{"boundary", b.name}, {"type", "triangle"},        {"degree", b.n},
                           {"method", "alpha"},  {"alpha", r.options.mask.c}, {"a", r.options.mask.a()}};
  phases.start("solve");
  const tri::TriSolveResult result = tri::solve_tri_net(b, r.options);
  report["solver"] = summary_to_json(result.summary);
  if (r.picked_automatically) report["solver"]["picked_by"] = "auto";
  if (!result.summary.ok()) {
    nlohmann::json failed = tri_solve_report(b, r.options.mask, result, r.picked_automatically);
    failed["timing"] = phases.timing();
    print_json(failed);
    print_solver_failure(e.boundary, result.summary);
    return kExitSolverFailed;
  }
  phases.start("write");
  std::vector<std::string> written;
  auto write = [&](const std::string& name, const std::function<void(std::ostream&)>& writer) {
    written.push_back(out.path_of(name));
    out.write(name, writer);
  };
  if (surface) {
    const tri::TriSurfaceSamples samples = tri::sample_tri_surface(result.net, e.samples);
    if (obj) {
      write(prefix + ".surface.obj", [&](std::ostream& o) { write_tri_surface_obj(o, samples, b.n); });
      write(prefix + ".net.obj", [&](std::ostream& o) { write_tri_net_obj(o, result.net); });
    }
    if (ply) write(prefix + ".surface.ply", [&](std::ostream& o) { write_tri_surface_ply(o, samples, b.n); });
    if (vtu) write(prefix + ".surface.vtu", [&](std::ostream& o) { write_tri_surface_vtu(o, samples); });
  }
  if (mtx) {
    phases.start("assemble");
    const tri::TriMaskSystem system = tri::assemble_tri_mask_system(tri::frame_net(b), r.options.mask);
    phases.start("write");
    write(prefix + ".A.mtx", [&](std::ostream& o) { write_matrix_market(o, system.A); });
    write(prefix + ".B.mtx", [&](std::ostream& o) { write_dense_matrix_market(o, system.B); });
    report["matrix_market"] = {
        {"matrix", "coordinate real general, I - mask on the interior (not symmetric for c != 0)"},
        {"rhs", "array real general, #interior by 3 (x, y, z), interior in the net's row order"}};
  }
  report["written"] = written;
  report["timing"] = phases.timing();
  out.publish([&] { print_json(report); });
  return kExitOk;
}

int run_tri_search(const TriSearchArgs& a) {
  Phases phases("search-alpha");
  phases.start("read");
  const tri::TriBoundary b = read_tri_input(a.boundary, a.corner_tolerance, kMinModelSize);
  if (!a.rejected.empty()) throw InputError("command line", a.rejected, "does not apply to a triangular boundary");
  const std::string text = objective_text(a.objective);
  std::string why;
  std::optional<TriObjective> objective = parse_tri_objective(text, &why);
  if (!objective) throw InputError("command line", "--objective", why);
  if (objective->uses_target()) {  // (the samples' memory only where they are taken)
    check_target_samples(*a.global, a.samples);
    objective->target = target_from_json(read_json_file(a.boundary), a.boundary, a.samples);
    if (!objective->target)
      throw InputError("command line", "--objective", "the objective uses 'target' but the file has no \"target\"");
  } else if (a.samples_given) {
    throw samples_without_target(a.objective);
  }
  AlphaSearchOptions options;
  const auto [lower, upper] = default_tri_bounds(b.n);
  options.lower = a.lower.value_or(lower);
  options.upper = a.upper.value_or(upper);
  options.scan_points = a.scan_points;
  require_valid_search_options(options);
  bool picked = false;
  const solvers::SolverInfo& solver = tri_backend(a.solver, picked);
  require_tri_range_backend(solver, picked, options.lower, options.upper);
  check_tri_memory(*a.global, b.n, &solver, a.boundary);
  phases.start("solve");
  const AlphaSearchSummary s = search_tri_c(tri::frame_net(b), *objective, solver, options);
  nlohmann::json report = tri_search_report(b, text, options, s);
  report["solver"] = search_solver_block(solver, picked, s.status, s.solves, s.seconds, s.message);
  report["timing"] = phases.timing();
  print_json(report);
  if (s.status != SearchStatus::kSolverFailed && s.status != SearchStatus::kFailedRegion) return kExitOk;
  std::cerr << fmt::format("error: {}: solver: {} search failed ({})\n", a.boundary, solver.name,
                           s.message.empty() ? "no successful evaluation" : s.message);
  return kExitSolverFailed;
}

int run_tri_sweep(const TriSweepArgs& a) {
  Phases phases("sweep");
  phases.start("read");
  const tri::TriBoundary b = read_tri_input(a.boundary, a.corner_tolerance);
  if (!a.rejected.empty()) throw InputError("command line", a.rejected, "does not apply to a triangular boundary");
  if (a.count < 2 || a.count > 100000) throw InputError("command line", "--count", "must be between 2 and 100000");
  const auto [lower, upper] = default_tri_bounds(b.n);
  const double from = a.from.value_or(lower), to = a.to.value_or(upper);
  if (!(std::isfinite(from) && std::isfinite(to) && from < to))
    throw InputError("command line", "--from/--to", "need finite values with from < to");
  // |c| ≤ 1e60, as solve and search-alpha require: beyond it the weights overflow in the solvers'
  // products, and regular systems read "singular" (c = 1e200) or c itself overflowed (±1.7e308)
  if (std::max(std::abs(from), std::abs(to)) > kMaxAlpha)
    throw InputError("command line", "--from/--to",
                     fmt::format("values must lie in [-{0:g}, {0:g}] (beyond, the mask's weights overflow in the "
                                 "solvers' products)",
                                 kMaxAlpha));
  TriObjective target_only;  // no terms: the evaluations only solve; the target gives rms_target
  target_only.target = target_from_json(read_json_file(a.boundary), a.boundary, a.samples);
  if (!target_only.target && a.samples_given) throw samples_without_sweep_target();
  if (target_only.target) check_target_samples(*a.global, a.samples);  // (only where they are taken)
  bool picked = false;
  const solvers::SolverInfo& solver = tri_backend(a.solver, picked);
  require_tri_range_backend(solver, picked, from, to);
  check_tri_memory(*a.global, b.n, &solver, a.boundary);

  phases.start("solve");
  const tri::TriNet frame = tri::frame_net(b);
  std::vector<std::string> lines;
  std::optional<solvers::SolveSummary> failed;  // the first failure
  int failed_values = 0;
  nlohmann::json intervals = nlohmann::json::array();
  bool previous_failed = false;
  solvers::SolveSummary first;
  const std::vector<double> values = linspace(from, to, a.count);
  for (size_t k = 0; k < values.size(); ++k) {
    phases.note(fmt::format("{}/{}", k + 1, values.size()));
    const TriEvaluation e = evaluate_tri_objective(frame, target_only, values[k], solver, false);
    lines.push_back(dump(tri_sweep_line(b, e, target_only)));
    if (k == 0) first = e.summary;
    if (!e.ok()) {
      if (failed_values++ == 0) failed = e.summary;
      if (previous_failed)
        intervals.back()[1] = values[k];
      else
        intervals.push_back({values[k], values[k]});
    }
    previous_failed = !e.ok();
  }
  phases.start("write");
  OutputSet out(a.out_dir, "--out");
  const std::string stem = safe_file_stem(b.name) + ".sweep-c";
  const std::string jsonl = out.path_of(stem + ".jsonl");
  out.write(stem + ".jsonl", [&](std::ostream& o) {
    for (const auto& line : lines) o << line << '\n';
  });
  nlohmann::json summary = {{"boundary", b.name},      {"type", "triangle"}, {"degree", b.n}, {"parameter", "c"},
                            {"values", values.size()}, {"from", from},       {"to", to},      {"jsonl", jsonl}};
  nlohmann::json block = summary_to_json(failed ? *failed : first);
  if (picked) block["picked_by"] = "auto";
  summary["solver"] = block;
  if (failed) {
    summary["failed_values"] = failed_values;
    summary["failed_intervals"] = intervals;
  }
  summary["timing"] = phases.timing();
  out.publish([&] { print_json(summary); });
  if (failed) {
    print_solver_failure(a.boundary, *failed);
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace coons::cli
