// `coons sweep BOUNDARY`: every metric on a grid of α (or μ): NAME.sweep-alpha.jsonl (or
// .sweep-mu.jsonl) and a PNG of the normalised energy curves, written together.
#include "coons/study/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/net_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/write_files.h"
#include "coons/study/backend_choice.h"
#include "coons/study/memory_estimate.h"
#include "net_request.h"
#include "registry.h"
#include "search_inputs.h"
#include "tri_commands.h"

namespace coons::cli {

namespace {

struct SweepRequest {
  std::string boundary;
  SweepParameter parameter = SweepParameter::kAlpha;
  double from = -0.25, to = 0.25;
  int count = 51;
  std::string out_dir = ".";
  std::string target;
  int samples = 41;
  std::string solver = "auto";
  int threads = 1;
  double corner_tolerance = 1e-9;
  GlobalOptions global;
  CLI::Option *from_option = nullptr, *to_option = nullptr, *threads_option = nullptr, *samples_option = nullptr;
};

TriSweepArgs tri_sweep_args(const SweepRequest& r) {
  TriSweepArgs a{r.boundary, r.solver,  r.out_dir,          std::nullopt, std::nullopt,
                 r.count,    r.samples, r.corner_tolerance, &r.global,    ""};
  a.samples_given = r.samples_option->count() > 0;
  if (r.from_option->count() > 0) a.from = r.from;
  if (r.to_option->count() > 0) a.to = r.to;
  if (r.parameter != SweepParameter::kAlpha) a.rejected = "--parameter";
  if (!r.target.empty()) a.rejected = "--target";
  if (r.threads_option->count() > 0) a.rejected = "--threads";  // (as solve and export refuse it)
  return a;
}

int run_sweep_command(const SweepRequest& r) {
  if (is_triangle_file(r.boundary)) return run_tri_sweep(tri_sweep_args(r));
  Phases phases("sweep");
  phases.start("read");
  const BoundaryFile file = read_input(r.boundary, r.corner_tolerance);
  require_one_ring(file, r.boundary, "coons sweep");
  const Boundary& b = file.boundary;
  if (r.count < 2 || r.count > 100000) throw InputError("command line", "--count", "must be between 2 and 100000");
  const double from = r.parameter == SweepParameter::kMu && r.from_option->count() == 0 ? 0.0 : r.from;
  const double to = r.parameter == SweepParameter::kMu && r.to_option->count() == 0 ? 100.0 : r.to;
  if (!(std::isfinite(from) && std::isfinite(to) && from < to))
    throw InputError("command line", "--from/--to", "need finite values with from < to");
  if (r.parameter == SweepParameter::kAlpha && (from < -0.25 || to > 0.25))
    throw InputError("command line", "--from/--to", "alpha must stay in [-0.25, 0.25]");
  if (r.parameter == SweepParameter::kMu && from < 0) throw InputError("command line", "--from", "mu must be >= 0");
  // (100000 values of [-0.25, -0.2499999999999999] were a few doubles, each written thousands of times)
  const std::vector<double> values = linspace(from, to, r.count);
  if (std::adjacent_find(values.begin(), values.end(), std::greater_equal<>()) != values.end())
    throw InputError("command line", "--from/--to",
                     fmt::format("the interval [{}, {}] is too narrow for {} distinct values (neighbours round to the "
                                 "same double)",
                                 from, to, r.count));
  const std::optional<Target> target = resolve_target(r.target, r.boundary, b, r.samples);
  if (!target && r.samples_option->count() > 0) throw samples_without_sweep_target();
  if (target) check_target_samples(r.global, r.samples);  // (only where they are taken)
  const solvers::SolverOptions options = threads_options(r.threads, r.threads_option, r.solver);
  const solvers::SolverInfo* requested = solver_from_name(r.solver);
  require_search_backend(requested, b, false);
  const solvers::SolverInfo& solver = search_backend(requested, b, false);
  const double interior = std::max(0.0, b.m - 1.0) * std::max(0.0, b.n - 1.0);
  check_memory(r.global,
               net_solve_bytes(b.m, b.n, &solver) + net_metrics_bytes(b.m, b.n) +
                   (solver.needs_matrix ? r.count * interior * 9 * 16 : 0.0),
               fmt::format("a sweep of {} nets of degree ({}, {})", r.count, b.m, b.n), r.boundary, "degree");

  phases.start("solve");
  const std::vector<SweepRow> rows = run_sweep(
      b, values, sweep_family(r.parameter, b), solver, target,
      [&](size_t done, size_t all) { phases.note(fmt::format("{}/{}", done, all)); }, nullptr, options);

  phases.start("write");
  OutputSet out(r.out_dir, "--out");
  const std::string stem = safe_file_stem(b.name) + ".sweep-" + to_string(r.parameter);
  const std::string jsonl = out.path_of(stem + ".jsonl"), png = out.path_of(stem + ".png");
  out.write(stem + ".jsonl", [&](std::ostream& o) {
    for (const auto& row : rows) o << dump(sweep_line(b, r.parameter, row)) << '\n';
  });
  const std::string plot_error = plot_sweep(out.stage(stem + ".png"), b, r.parameter, rows);
  nlohmann::json summary = {{"boundary", b.name},
                            {"degree", {b.m, b.n}},
                            {"parameter", to_string(r.parameter)},
                            {"values", rows.size()},
                            {"jsonl", jsonl}};
  if (plot_error.empty())
    summary["png"] = png;
  else
    summary["png_error"] = plot_error;
  // the solver block: the backend, and the first failure if any row failed
  const SweepRow* failed = nullptr;
  int failures = 0;
  nlohmann::json intervals = nlohmann::json::array();  // runs of failed values: [first, last]
  for (size_t k = 0; k < rows.size(); ++k) {
    if (rows[k].summary.ok() || b.m < 2 || b.n < 2) continue;
    failed = failed ? failed : &rows[k];
    ++failures;
    if (k > 0 && !rows[k - 1].summary.ok())
      intervals.back()[1] = rows[k].parameter;
    else
      intervals.push_back({rows[k].parameter, rows[k].parameter});
  }
  nlohmann::json block = summary_to_json(failed ? failed->summary : rows.front().summary);
  if (!requested) block["picked_by"] = "auto";
  summary["solver"] = block;
  if (failed) {
    summary["failed_values"] = failures;
    summary["failed_intervals"] = intervals;
  }
  summary["timing"] = phases.timing();
  if (!plot_error.empty()) out.discard(stem + ".png");
  out.publish([&] { print_json(summary); });
  if (failed) {
    print_solver_failure(r.boundary, failed->summary);
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace

void register_sweep(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<SweepRequest>();
  auto* cmd = app.add_subcommand("sweep",
                                 "every metric on a grid of alpha (or mu): NAME.sweep-alpha.jsonl "
                                 "(NAME.sweep-mu.jsonl) and a PNG plot");
  cmd->add_option("BOUNDARY", r->boundary, "boundary JSON file (docs/formats.md)")->required();
  const std::map<std::string, SweepParameter> parameters = {{"alpha", SweepParameter::kAlpha},
                                                            {"mu", SweepParameter::kMu}};
  cmd->add_option("--parameter", r->parameter, "alpha or mu")->transform(choice_of(parameters))->default_str("alpha");
  r->from_option = cmd->add_option("--from", r->from, "first value (mu: default 0)")
                       ->transform(fold_negative_zero())
                       ->capture_default_str();
  r->to_option = cmd->add_option("--to", r->to, "last value (mu: default 100)")
                     ->transform(fold_negative_zero())
                     ->capture_default_str();
  cmd->add_option("--count", r->count, "number of values")->capture_default_str();
  cmd->add_option("--out", r->out_dir, "output folder: NAME.sweep-PARAMETER.jsonl and .png")->capture_default_str();
  cmd->add_option("--target", r->target,
                  "also report the rms distance to a target (as in search-alpha; default: "
                  "the boundary file's \"target\")");
  r->samples_option = cmd->add_option("--samples", r->samples, "target: samples per direction")->capture_default_str();
  cmd->add_option("--corner-tolerance", r->corner_tolerance,
                  "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  add_solver_option(*cmd, r->solver);
  r->threads_option = add_threads_option(*cmd, r->threads);
  add_memory_option(*cmd, r->global);
  set_example(*cmd, "coons sweep data/boundaries/dome.json --from -0.25 --to 0 --count 26 --out out/sweep");
  registry.add(cmd, [r] { return run_sweep_command(*r); });
}

}  // namespace coons::cli
