// `coons study BOUNDARY...`: the α study (coons/study/study.h) with its report: report.md,
// results.json and figures/, written together (nothing is left on any failure). Triangular
// boundary files among the inputs get the triangle rows of tri_study.h.
#include "coons/study/study.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>

#include "coons/config.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/write_files.h"
#include "coons/study/alpha_family.h"
#include "coons/study/bspline_study.h"
#include "coons/study/family_tasks.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/report_markdown.h"
#include "coons/study/study_conclusions.h"
#include "coons/study/study_failures.h"
#include "coons/study/task_key.h"
#include "coons/tri/tri_solve.h"
#include "registry.h"
#include "search_inputs.h"
#include "study_shard.h"
#include "view_command.h"

namespace coons::cli {

namespace {

struct StudyRequest {
  std::vector<std::string> inputs;
  std::vector<int> degrees = {3, 4, 6, 8, 12, 16};
  std::string out_dir = "out/study";
  std::string solver = "auto";
  double corner_tolerance = 1e-9;
  std::string family;      // "random-smooth" or "perturbed:NAME": the family study instead of files
  double amplitude = 0.1;  // of the perturbed family
  int count = 200;
  std::uint64_t seed = 1;
  std::string shard;  // --shard I/N: one part of the family study's tasks (study_shard.h)
  std::string merge;  // --merge DIR: the report from the shards in DIR
  bool html = false;  // --html: a `coons view` page per shape (study_pages.cpp)
  GlobalOptions global;
  // the options as given on the command line: an option that does nothing in the mode is refused
  struct Given {
    CLI::Option *degrees = nullptr, *amplitude = nullptr, *count = nullptr, *seed = nullptr, *html = nullptr,
                *corner_tolerance = nullptr, *solver = nullptr, *max_memory = nullptr;
  } given;
};

// An option that has no effect in the study's mode (files, --family, --merge) is an input error
// naming it, rather than silently ignored.
void refuse_inapplicable(const StudyRequest& r) {
  const StudyRequest::Given& g = r.given;
  auto refuse = [](const CLI::Option* option, const char* name, const std::string& why) {
    if (given(option)) throw InputError("command line", name, why);
  };
  if (!r.merge.empty()) {
    const std::string why = "does not apply to --merge (the shards carry the study's options)";
    refuse(g.degrees, "--degrees", why);
    refuse(g.html, "--html", why);
    refuse(g.count, "--count", why);
    refuse(g.seed, "--seed", why);
    refuse(g.amplitude, "--amplitude", why);
    refuse(g.corner_tolerance, "--corner-tolerance", why);
    refuse(g.solver, "--solver", why);
    refuse(g.max_memory, "--max-memory", "does not apply to --merge (it solves nothing)");
    return;
  }
  const bool perturbed = r.family.rfind("perturbed:", 0) == 0;
  if (r.family.empty()) {
    const std::string why = "applies to --family only, not to a study of boundary files";
    refuse(g.count, "--count", why);
    refuse(g.seed, "--seed", why);
    refuse(g.amplitude, "--amplitude", "applies to --family perturbed:NAME only");
    return;
  }
  refuse(g.html, "--html", "applies to a study of boundary files only, not to --family");
  if (!perturbed) {
    refuse(g.amplitude, "--amplitude", "applies to --family perturbed:NAME only, not to " + r.family);
    refuse(g.corner_tolerance, "--corner-tolerance",
           "applies to boundary files (and --family perturbed:FILE) only, not to " + r.family);
  }
}

// perturbed:NAME: NAME is a boundary file, or a bundled shape's name (data/boundaries/NAME.json from
// the current folder, the repository's root).
std::string perturbed_base_file(const std::string& name) {
  if (name.empty()) throw InputError("command line", "--family", "perturbed: needs a shape (perturbed:dome) or a file");
  if (std::filesystem::is_regular_file(name)) return name;
  std::string bundled = "data/boundaries/" + name + ".json";
  if (std::filesystem::is_regular_file(bundled)) return bundled;
  throw InputError("command line", "--family",
                   fmt::format("'{}' is neither a boundary file nor a bundled shape ({} not found)", name, bundled));
}

std::string read_file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot be read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `coons study --family random-smooth|perturbed:NAME`: α* over a seeded family (coons/study/alpha_family.h).
int run_family_command(const StudyRequest& r) {
  Phases phases("study");
  if (!r.inputs.empty())
    throw InputError("command line", "--family", "give either boundary files or --family, not both");
  AlphaFamilyOptions options;
  if (r.family.rfind("perturbed:", 0) == 0) {
    options.base_name = r.family.substr(10);
    const std::string file = perturbed_base_file(options.base_name);
    const BoundaryFile base = read_input(file, r.corner_tolerance, true, kMinModelSize);
    if (base.bspline)  // the family perturbs and elevates Bézier sides; a B-spline's are not
      throw InputError(file, "knots_u",
                       "a B-spline boundary cannot be the base of --family perturbed: (its sides are not Bézier "
                       "curves to perturb and elevate); give a Bézier boundary");
    options.base = base.boundary;
    options.base_content = fnv1a_hex(read_file_text(file));
    options.amplitude = r.amplitude;
  } else if (r.family != "random-smooth") {
    throw InputError("command line", "--family",
                     fmt::format("unknown family '{}' (known: random-smooth, perturbed:NAME)", r.family));
  }
  if (given(r.given.degrees)) options.degrees = r.degrees;
  options.count = r.count;
  options.seed = r.seed;
  options.solver = solver_from_name(r.solver);
  std::string why, field;
  if (!options.is_valid(&why, &field)) {  // the option that set the member at fault
    const std::string option = field == "degrees"     ? "--degrees"
                               : field == "count"     ? "--count"
                               : field == "amplitude" ? "--amplitude"
                                                      : "--family";
    if (field == "degrees" && !given(r.given.degrees)) why += " (the default degrees: give --degrees)";
    throw InputError("command line", option, why);
  }
  for (int d : options.degrees) {  // the family's boundaries at degree d are d × d
    Boundary at_degree;
    at_degree.m = at_degree.n = d;
    require_search_backend(options.solver, at_degree, false);
  }
  check_memory(r.global,
               net_solve_bytes(options.degrees.back(), options.degrees.back(), options.solver) +
                   net_metrics_bytes(options.degrees.back(), options.degrees.back()),
               fmt::format("the family study at degree {}", options.degrees.back()), "command line", "--degrees");
  if (!r.shard.empty()) {
    const auto shard = parse_shard(r.shard, &why);
    if (!shard) throw InputError("command line", "--shard", why);
    return run_family_shard(options, shard->first, shard->second, r.out_dir);
  }
  phases.start("solve");
  const AlphaFamilyResult result = run_alpha_family(options, [&](const std::string& s) { phases.note(s); });
  phases.start("write");
  write_family_report(result, r.out_dir);
  return failures_exit_status(family_failures(result));
}

int run_study_command(const StudyRequest& r, const std::string& command_line) {
  if (!r.merge.empty()) {
    if (!r.inputs.empty() || !r.family.empty() || !r.shard.empty())
      throw InputError("command line", "--merge",
                       "takes the study from the shards: give no boundaries, --family or --shard");
    refuse_inapplicable(r);
    return run_study_merge(r.merge, r.out_dir);
  }
  refuse_inapplicable(r);
  if (!r.family.empty()) return run_family_command(r);
  check_corner_tolerance(r.corner_tolerance);
  Phases phases("study");
  phases.start("read");
  const std::vector<std::string> files = expand_inputs(r.inputs);
  if (files.empty()) throw InputError("command line", "BOUNDARY", "no boundary files given or found (or --family)");
  StudyOptions options;
  options.degrees = r.degrees;
  options.solver = solver_from_name(r.solver);
  std::string why;
  if (!options.is_valid(&why)) throw InputError("command line", "--degrees", why);
  const std::string three_js = r.html ? read_three_js(COONS_THREE_JS_PATH) : "";
  BoundaryReadOptions read_options;
  read_options.min_model_size = kMinModelSize;  // the searches
  read_options.corner_tolerance = r.corner_tolerance;
  std::vector<StudyInput> inputs;
  std::vector<TriStudyInput> triangles;
  std::vector<BSplineStudyInput> bsplines;
  for (const auto& f : files) {
    if (is_triangle_file(f)) {
      triangles.push_back(read_tri_study_input(f, r.corner_tolerance));
      // a backend the triangular systems cannot take is refused here, as `coons view` does, rather
      // than turning every triangle row into "failed"
      if (options.solver)
        if (const tri::TriBackendCheck check = tri::check_tri_backend(*options.solver, tri::TriMask{-1.0 / 6.0});
            !check.applicable)
          throw InputError("command line", "--solver",
                           fmt::format("{} ({} is a triangular boundary)", check.reason, f));
      int largest = triangles.back().boundary.n;
      for (int d : options.degrees) largest = std::max(largest, d);
      if (largest > tri::kMaxTriDegree)
        throw InputError("command line", "--degrees",
                         fmt::format("{} is above {}, the largest degree of a triangular boundary ({} is one); study "
                                     "the triangles in a run of their own with smaller --degrees",
                                     largest, tri::kMaxTriDegree, f));
      check_memory(r.global, net_solve_bytes(largest, largest, options.solver) + net_metrics_bytes(largest, largest),
                   fmt::format("the study of {} at degree {}", triangles.back().boundary.name, largest), f, "degree");
      continue;
    }
    const BoundaryFile file = read_boundary_file(f, read_options);
    if (file.bspline) {  // a row at its own knots (bspline_study.h), not the degree study
      warn_misspelt(f, file.misspelt);
      check_memory(r.global,
                   64.0 * file.bspline->compatible.bottom.count() * file.bspline->compatible.left.count() * 100,
                   fmt::format("the B-spline row of {}", file.boundary.name), f, "knots_u");
      bsplines.push_back({f, file.boundary.name, *file.bspline});
      continue;
    }
    inputs.push_back(read_study_input(f, file));
    warn_misspelt(f, inputs.back().misspelt);
    const Boundary& b = inputs.back().boundary;
    require_search_backend(options.solver, b, false, f);
    int largest = std::max(b.m, b.n);
    for (int d : options.degrees) largest = std::max(largest, d);
    check_memory(r.global, net_solve_bytes(largest, largest, options.solver) + net_metrics_bytes(largest, largest),
                 fmt::format("the study of {} at degree {}", b.name, largest), f, "degree");
  }

  if (!r.shard.empty()) {
    const auto shard = parse_shard(r.shard, &why);
    if (!shard) throw InputError("command line", "--shard", why);
    if (r.html) throw InputError("command line", "--shard", "--html is not sharded yet (give it to an unsharded run)");
    return run_files_shard(files, options, r.corner_tolerance, shard->first, shard->second, r.out_dir);
  }
  phases.start("solve");
  StudyResult result = run_study(inputs, options, [&](const std::string& s) { phases.note(s); });
  result.triangles =
      run_tri_study(triangles, options.degrees, options.solver, [&](const std::string& s) { phases.note(s); });
  const std::vector<BSplineStudyRow> bspline_rows =
      run_bspline_study(bsplines, default_study_objectives(), bspline_row_solver(options.solver));

  phases.start("write");
  // B-spline rows and pages after the per-shape report (pages are not carried by shards)
  write_study_report(result, r.out_dir, command_line, [&](OutputSet& out) {
    std::string tail = write_bspline_rows(bspline_rows, out);
    if (r.html) tail += write_study_pages(result, inputs, bsplines, out, three_js, options.solver);
    return tail;
  });
  return study_exit_status(result, bspline_rows);
}

}  // namespace

std::string bspline_row_solver(const solvers::SolverInfo* solver) {
  return solver != nullptr && solvers::accepts_matrix(*solver) ? solver->name : std::string();
}

std::string write_bspline_rows(const std::vector<BSplineStudyRow>& rows, OutputSet& out) {
  if (rows.empty()) {
    out.remove_stale("bspline.json");  // an earlier run's rows, which this report does not have
    return "";
  }
  out.write("bspline.json", [&](std::ostream& o) { o << dump(bspline_study_json(rows), 1) << '\n'; });
  return "\n" + bspline_study_markdown(rows);
}

// A failed solve anywhere in the study: the report stands (it says "failed" where it happened), the
// exit status says so, with one line naming the first failure.
int study_exit_status(const StudyResult& result, const std::vector<BSplineStudyRow>& bspline_rows) {
  std::vector<StudyFailure> failures = study_failures(result);
  for (StudyFailure& f : bspline_study_failures(bspline_rows)) failures.push_back(std::move(f));
  return failures_exit_status(failures);
}

int failures_exit_status(const std::vector<StudyFailure>& failures) {
  if (failures.empty()) return kExitOk;
  const StudyFailure& first = failures.front();
  std::cerr << fmt::format("error: {}: solver: {}{} (the report is written; it says where)\n",
                           first.file.empty() ? "study" : first.file, first.what,
                           failures.size() > 1 ? fmt::format(", and {} more failures", failures.size() - 1) : "");
  return kExitSolverFailed;
}

void register_study(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<StudyRequest>();
  auto* cmd = app.add_subcommand("study",
                                 "the alpha study: optima per shape and degree, the c/n^2 law, a reference "
                                 "table for every boundary with a target, the best c of every triangular boundary; a "
                                 "self-contained report with PNG figures");
  cmd->add_option("BOUNDARY", r->inputs, "boundary files or folders of them (or --family)");
  r->given.degrees = cmd->add_option("--degrees", r->degrees,
                                     "degrees to study each shape at (increasing; with --family: 3 5 8 12 20)")
                         ->check(int_item())
                         ->capture_default_str();
  cmd->add_option("--family", r->family,
                  "random-smooth, or perturbed:NAME (a bundled shape or a boundary file plus random smooth "
                  "perturbations): instead of files, the distribution of alpha* over a seeded family and the best "
                  "single alpha");
  r->given.amplitude =
      cmd->add_option("--amplitude", r->amplitude,
                      "with --family perturbed:NAME: the perturbation's size, a fraction of the shape's bounding-box "
                      "diagonal, in [0, 1]")
          ->capture_default_str();
  r->given.count = cmd->add_option("--count", r->count, "with --family: how many boundaries")->capture_default_str();
  // CLI11 turned -1, 2^64 and 1e23 alike into 2^64 - 1: three seeds, one family
  const CLI::Validator seed_range(
      [](std::string& text) {
        const bool digits = !text.empty() && text.size() <= 20 &&
                            std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
        if (digits && (text.size() < 20 || text <= "18446744073709551615")) return std::string();
        return std::string("'") + text + "' is not an integer in [0, 18446744073709551615]";
      },
      "", "SEED");
  r->given.seed =
      cmd->add_option("--seed", r->seed, "with --family: the family's seed")->check(seed_range)->capture_default_str();
  cmd->add_option(
      "--shard", r->shard,
      "I/N: run the I-th of N disjoint parts of the task list (family tasks, or one per boundary file) into "
      "OUT/shard-I-of-N.jsonl (a rerun skips the tasks already there)");
  cmd->add_option("--merge", r->merge, "DIR: the report (to --out) from the shard files in DIR");
  cmd->add_option("--out", r->out_dir, "output folder: report.md, figures, results.json")->capture_default_str();
  r->given.html =
      cmd->add_flag("--html", r->html, "also a coons view page per shape in pages/, linked from the report");
  r->given.corner_tolerance =
      cmd->add_option("--corner-tolerance", r->corner_tolerance,
                      "corners must agree to this fraction of the bounding-box diagonal (boundary files and "
                      "--family perturbed:FILE)")
          ->capture_default_str();
  add_solver_option(*cmd, r->solver);
  r->given.solver = cmd->get_option("--solver");
  add_memory_option(*cmd, r->global);
  r->given.max_memory = cmd->get_option("--max-memory");
  set_example(*cmd, "coons study data/boundaries data/triangles --degrees 3 4 6 8 --out out/study");
  registry.add(cmd, [r, &registry] { return run_study_command(*r, registry.command_line); });
}

}  // namespace coons::cli
