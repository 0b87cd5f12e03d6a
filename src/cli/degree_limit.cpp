// `coons degree-limit BOUNDARY... --objective NAME...`: the measured degree law (α*, μ* at every
// degree, the limit of μ*(n) with its error and rate, the candidate fits, the continuum optimum by
// the Ritz method, the spreads of three parametrisations). One boundary and one objective: the
// JSON on standard output; --out DIR: report.md, results.json and figures/ for all of them.
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <set>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/write_files.h"
#include "coons/study/degree_limit_report.h"
#include "coons/study/degree_limit_study.h"
#include "coons/study/memory_estimate.h"
#include "registry.h"
#include "search_inputs.h"

namespace coons::cli {

namespace {

std::vector<int> default_degrees() {
  std::vector<int> d(62);
  std::iota(d.begin(), d.end(), 3);  // 3 … 64
  return d;
}

struct DegreeLimitRequest {
  std::vector<std::string> inputs;
  std::vector<std::string> objectives = {"thin_plate"};
  std::vector<int> degrees = default_degrees();
  std::vector<int> continuum_degrees = {24, 32, 40};
  std::string out_dir;
  std::string solver = "auto";
  double corner_tolerance = 1e-9;
  GlobalOptions global;
};

int run_degree_limit_command(const DegreeLimitRequest& r, const std::string& command_line) {
  check_corner_tolerance(r.corner_tolerance);
  Phases phases("degree-limit");
  phases.start("read");
  const std::vector<std::string> files = expand_inputs(r.inputs);
  if (files.empty()) throw InputError("command line", "BOUNDARY", "no boundary files given or found");
  DegreeLimitStudyOptions options;
  options.degrees = r.degrees;
  options.continuum_degrees = r.continuum_degrees;
  options.solver = solver_from_name(r.solver);
  std::string why;
  if (!options.is_valid(&why))
    throw InputError("command line", why.rfind("continuum", 0) == 0 ? "--continuum-degrees" : "--degrees", why);
  std::vector<Objective> objectives;
  for (const std::string& given : r.objectives) {
    const std::string name = objective_text(given);
    auto o = parse_objective(name, &why);
    if (!o) throw InputError("command line", "--objective", why);
    if (o->target_weight > 0) throw InputError("command line", "--objective", "'" + name + "' needs a target");
    objectives.push_back(*o);
  }
  if (r.out_dir.empty() && (files.size() != 1 || objectives.size() != 1))
    throw InputError("command line", "--out",
                     "several boundaries or objectives need a report folder (--out DIR); "
                     "one boundary and one objective print their JSON");
  BoundaryReadOptions read_options;
  read_options.min_model_size = kMinModelSize;  // the searches
  read_options.corner_tolerance = r.corner_tolerance;
  std::vector<StudyInput> inputs;
  int largest = 0;
  for (int d : options.degrees) largest = std::max(largest, d);
  for (int d : options.continuum_degrees) largest = std::max(largest, d);
  for (const auto& f : files) {
    inputs.push_back(read_study_input(f, read_options));
    warn_misspelt(f, inputs.back().misspelt);
    const Boundary& b = inputs.back().boundary;
    require_search_backend(options.solver, b, false, f);
    if (!options.degrees.empty() &&
        unreachable_degrees(inputs.back(), options.degrees).size() == options.degrees.size())
      throw InputError(f, "--degrees",
                       fmt::format("every degree asked for ({}) is {}", fmt::join(options.degrees, " "),
                                   unreachable_reason(inputs.back())));
    const int n = std::max({largest, b.m, b.n});
    check_memory(r.global, net_solve_bytes(n, n, options.solver) + net_metrics_bytes(n, n),
                 fmt::format("the degree law of {} at degree {}", b.name, n), f, "degree");
  }

  phases.start("solve");
  std::vector<DegreeLimitEntry> entries;
  for (const StudyInput& in : inputs)
    for (const Objective& o : objectives) {
      entries.push_back(run_degree_limit(in, o, options));
      phases.note(fmt::format("{} {} done", in.boundary.name, o.name));
    }

  phases.start("write");
  if (r.out_dir.empty()) {
    print_json(degree_limit_json(entries.front()));
    return kExitOk;
  }
  OutputSet out(r.out_dir, "--out");
  const std::vector<StudyFigure> figures =
      plot_degree_limit_figures(entries, [&](const std::string& file) { return out.stage(file); });
  for (const StudyFigure& f : figures)
    if (!f.error.empty()) out.discard(f.file);
  // a figure with nothing to draw (too few degrees, no continuum optimum) takes away an earlier
  // run's file of its name, as a failed plot does
  std::set<std::string> stale;  // (several entries share an objective)
  for (const DegreeLimitEntry& e : entries)
    for (const std::string& file : degree_limit_figure_files(e.objective))
      if (std::none_of(figures.begin(), figures.end(), [&](const StudyFigure& f) { return f.file == file; }))
        stale.insert(file);
  for (const std::string& file : stale) out.remove_stale(file);
  const std::string md = degree_limit_report_markdown(entries, options, current_provenance(command_line), figures);
  nlohmann::json results = nlohmann::json::array();
  for (const DegreeLimitEntry& e : entries) results.push_back(degree_limit_json(e));
  out.write("results.json", [&](std::ostream& o) { o << dump(results, 1) << '\n'; });
  out.write("report.md", [&](std::ostream& o) { o << md; });
  out.publish([&] { print_text(md + '\n' + fmt::format("report: {}\n", out.path_of("report.md") + "")); });
  return kExitOk;
}

}  // namespace

void register_degree_limit(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<DegreeLimitRequest>();
  auto* cmd = app.add_subcommand("degree-limit",
                                 "the measured degree law: alpha* and mu* at each degree, the limit of mu*(n) "
                                 "with its error and rate, the candidate fits, the continuum optimum (Ritz)");
  cmd->add_option("BOUNDARY", r->inputs, "boundary files or folders of them")->required();
  cmd->add_option("--objective", r->objectives, "objectives (thin_plate, e3, sums; no target)")->capture_default_str();
  cmd->add_option("--degrees", r->degrees, "degrees to search at (increasing; default 3 ... 64)")->check(int_item());
  cmd->add_option("--continuum-degrees", r->continuum_degrees, "degrees N of the Ritz spaces (increasing, <= 80)")
      ->check(int_item())
      ->capture_default_str();
  cmd->add_option("--out", r->out_dir, "report folder: report.md, results.json, figures/ (default: JSON on stdout)");
  cmd->add_option("--corner-tolerance", r->corner_tolerance,
                  "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  add_solver_option(*cmd, r->solver);
  add_memory_option(*cmd, r->global);
  set_example(*cmd, "coons degree-limit data/boundaries/conoid.json --objective thin_plate --degrees 4 6 8 12 16");
  registry.add(cmd, [r, &registry] { return run_degree_limit_command(*r, registry.command_line); });
}

}  // namespace coons::cli
