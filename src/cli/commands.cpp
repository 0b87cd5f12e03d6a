#include "commands.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "alpha_commands.h"
#include "common.h"
#include "surface_command.h"
#include <fmt/format.h>
#include <fmt/ostream.h>
#include <nlohmann/json.hpp>

#include "coons/config.h"
#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/matrix_market.h"
#include "coons/io/net_json.h"
#include "coons/io/obj_export.h"
#include "coons/io/write_files.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"
#include "solvers/registry.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ---- solve -----------------------------------------------------------------------------------

int cmd_solve(const std::string& path, const NetRequest& request) {
  const BoundaryFile input = read_input(path, request);
  const ResolvedRequest r = resolve(request, input.boundary, path);
  const NetOutcome outcome = make_net(input.boundary, r);
  std::cout << solve_report(input.boundary, r, outcome, request.mu).dump(2) << '\n';
  return outcome.summary && !outcome.summary->ok() ? kExitSolverFailed : kExitOk;
}

// ---- solvers ---------------------------------------------------------------------------------

int cmd_solvers(bool as_json, bool verbose) {
  if (as_json) {
    json names = json::array();
    for (const auto& s : solvers::available_solvers()) names.push_back(s.name);
    std::cout << names.dump() << '\n';
    return kExitOk;
  }
  for (const auto& s : solvers::available_solvers()) {
    if (verbose) fmt::print("{:<20} {:<11} {}\n", s.name, solvers::to_string(s.family), s.description);
    else fmt::print("{}\n", s.name);
  }
  return kExitOk;
}

// ---- export ----------------------------------------------------------------------------------

struct ExportRequest {
  std::string out_dir = ".";
  std::string prefix;
  int samples = 33;
  bool obj = false, mtx = false;
};

int cmd_export(const std::string& path, const NetRequest& request, ExportRequest e) {
  const BoundaryFile input = read_input(path, request);
  const ResolvedRequest r = resolve(request, input.boundary, path);
  if (e.samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  if (!e.obj && !e.mtx) e.obj = e.mtx = true;
  if (e.mtx && r.method != Method::kAlpha)
    throw InputError("command line", "--mtx", "Matrix Market export needs --method alpha (closed forms solve no system)");
  if (e.mtx && input.boundary.m < 2 && input.boundary.n < 2) {}
  const std::string prefix = e.prefix.empty() ? input.boundary.name : e.prefix;
  std::error_code ec;
  fs::create_directories(e.out_dir, ec);
  if (ec) throw InputError(e.out_dir, "--out", "cannot create the folder: " + ec.message());
  const fs::path base = fs::path(e.out_dir) / prefix;

  std::vector<std::string> written;
  NetOutcome outcome;
  if (e.obj) {
    outcome = make_net(input.boundary, r);
    if (outcome.summary && !outcome.summary->ok()) {
      std::cout << solve_report(input.boundary, r, outcome, request.mu).dump(2) << '\n';
      return kExitSolverFailed;
    }
  }
  if (e.obj) {
    const std::string surface = base.string() + ".surface.obj", net = base.string() + ".net.obj";
    write_file_atomically(surface, [&](std::ostream& out) { write_surface_obj(out, outcome.net, e.samples); });
    write_file_atomically(net, [&](std::ostream& out) { write_net_obj(out, outcome.net); });
    written.push_back(surface);
    written.push_back(net);
  }
  if (e.mtx) {
    const MaskSystem system = assemble_mask_system(frame_net(input.boundary), r.mask, true);
    const std::string a = base.string() + ".A.mtx", b = base.string() + ".B.mtx";
    write_matrix_market(a, system.A);
    write_dense_matrix_market(b, system.B);
    written.push_back(a);
    written.push_back(b);
  }
  json report = {{"boundary", input.boundary.name}, {"written", written}};
  if (e.mtx) report["matrix_market"] = {{"matrix", "coordinate real general (both triangles stored)"},
                                        {"rhs", "array real general, #interior by 3 (x, y, z)"}};
  std::cout << report.dump(2) << '\n';
  return kExitOk;
}

// ---- batch (the main job until the alpha study) ----------------------------------------------

struct BatchRequest {
  std::vector<std::string> inputs;
  std::string out_dir = "out";
  std::vector<double> alphas = {-0.25, -0.1, 0.0};
  int samples = 33;
};

int cmd_batch(const BatchRequest& b, const NetRequest& base) {
  const std::vector<std::string> files = expand_inputs(b.inputs);
  if (files.empty()) throw InputError("command line", "BOUNDARY", "no boundary files given or found");
  if (b.samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  for (double a : b.alphas)
    if (!(a >= -0.25 && a <= 0.25)) throw InputError("command line", "--alphas", fmt::format("{} is outside [-0.25, 0.25]", a));
  // Read and validate every input before anything is written.
  std::vector<BoundaryFile> boundaries;
  for (const auto& f : files) boundaries.push_back(read_input(f, base));

  struct Row {
    std::string boundary;
    int m, n;
    std::string method;
    double alpha;
    std::string status;
    NetMetrics metrics;
  };
  std::vector<Row> rows;
  std::vector<std::pair<std::string, json>> results;  // file stem → solve report
  std::vector<std::pair<std::string, ControlNet>> nets;
  for (const auto& input : boundaries) {
    const Boundary& boundary = input.boundary;
    std::vector<std::pair<std::string, NetRequest>> runs;
    NetRequest coons = base;
    coons.method = "coons";
    runs.emplace_back("coons", coons);
    for (double a : b.alphas) {
      NetRequest r = base;
      r.method = "alpha";
      r.alpha = a;
      runs.emplace_back(fmt::format("alpha{:+.3f}", a), r);
    }
    for (const auto& [tag, request] : runs) {
      const ResolvedRequest r = resolve(request, boundary, boundary.name);
      const NetOutcome outcome = make_net(boundary, r);
      const bool ok = !outcome.summary || outcome.summary->ok();
      Row row{boundary.name, boundary.m, boundary.n, to_string(r.method), r.mask.diag,
              outcome.summary ? solvers::to_string(outcome.summary->status) : "closed-form", {}};
      if (ok) row.metrics = net_metrics(outcome.net, r.mask);
      rows.push_back(row);
      const std::string stem = boundary.name + "/" + tag;
      results.emplace_back(stem, solve_report(boundary, r, outcome, request.mu));
      if (ok) nets.emplace_back(stem, outcome.net);
    }
  }

  // Write: one folder per boundary, then the table.
  for (const auto& [stem, report] : results) {
    const fs::path p = fs::path(b.out_dir) / stem;
    fs::create_directories(p.parent_path());
    write_file_atomically(p.string() + ".json", [&](std::ostream& out) { out << report.dump(2) << '\n'; });
  }
  for (const auto& [stem, net] : nets) {
    const std::string p = (fs::path(b.out_dir) / stem).string();
    write_file_atomically(p + ".surface.obj", [&](std::ostream& out) { write_surface_obj(out, net, b.samples); });
    write_file_atomically(p + ".net.obj", [&](std::ostream& out) { write_net_obj(out, net); });
  }
  std::string table = fmt::format("| {:<22} | {:>7} | {:<6} | {:>6} | {:>11} | {:>12} | {:>12} | {:>12} | {:>12} | {:>9} | {:<11} |\n",
                                  "boundary", "degree", "method", "alpha", "twist", "thin plate", "Dirichlet",
                                  "E3", "disc. twist", "mask res.", "status");
  table += "|" + std::string(24, '-') + "|" + std::string(9, '-') + "|" + std::string(8, '-') + "|" +
           std::string(8, '-') + "|" + std::string(13, '-') + "|" + std::string(14, '-') + "|" +
           std::string(14, '-') + "|" + std::string(14, '-') + "|" + std::string(14, '-') + "|" +
           std::string(11, '-') + "|" + std::string(13, '-') + "|\n";
  for (const auto& r : rows)
    table += fmt::format("| {:<22} | {:>7} | {:<6} | {:>6.3f} | {:>11.6g} | {:>12.6g} | {:>12.6g} | {:>12.6g} | {:>12.6g} | {:>9.2e} | {:<11} |\n",
                         r.boundary, fmt::format("{}x{}", r.m, r.n), r.method, r.alpha, r.metrics.twist_energy,
                         r.metrics.thin_plate_energy, r.metrics.dirichlet_energy, r.metrics.e3_energy,
                         r.metrics.discrete_twist_energy, r.metrics.mask_residual, r.status);
  write_file_atomically((fs::path(b.out_dir) / "metrics.md").string(), [&](std::ostream& out) {
    out << "# coons batch: metrics of every bundled boundary\n\n"
        << "Coons = closed-form discrete Coons net; alpha = mask solve. Energies are exact integrals "
           "of the Bézier surface (docs/math.md §5); mask res. is the residual of the row's own mask.\n\n"
        << table;
  });
  std::cout << table << '\n'
            << fmt::format("{} boundaries, {} nets; results in {}/ (per boundary: <method>.json, "
                           ".surface.obj, .net.obj; the table in metrics.md)\n",
                           boundaries.size(), rows.size(), b.out_dir);
  for (const auto& r : rows)
    if (r.status != "success" && r.status != "closed-form") return kExitSolverFailed;
  return kExitOk;
}

}  // namespace

int run(int argc, char** argv) {
  CLI::App app{"coons — discrete Coons patches: fill a Bézier control net from its boundary "
               "(Farin & Hansford, CAGD 16, 1999)", "coons"};
  app.set_version_flag("--version", COONS_VERSION);
  app.require_subcommand(1);

  NetRequest net_request;
  std::string boundary_path;

  auto* solve = app.add_subcommand("solve", "solve one boundary; prints one JSON report (docs/formats.md)");
  solve->add_option("BOUNDARY", boundary_path, "boundary JSON file (docs/formats.md)")->required();
  add_net_options(*solve, net_request);

  bool solvers_json = false, solvers_verbose = false;
  auto* list = app.add_subcommand("solvers", "list the linear-solver backends built in");
  list->add_flag("--json", solvers_json, "print a JSON array");
  list->add_flag("-v,--verbose", solvers_verbose, "print family and description too");

  ExportRequest export_request;
  auto* exp = app.add_subcommand("export", "write the net as OBJ files and/or the mask system as Matrix Market");
  exp->add_option("BOUNDARY", boundary_path, "boundary JSON file (docs/formats.md)")->required();
  add_net_options(*exp, net_request);
  exp->add_option("--out", export_request.out_dir, "output folder")->capture_default_str();
  exp->add_option("--prefix", export_request.prefix, "file name prefix (default: the boundary's name)");
  exp->add_option("--samples", export_request.samples, "surface samples per direction")->capture_default_str();
  exp->add_flag("--obj", export_request.obj, "write <prefix>.surface.obj and <prefix>.net.obj");
  exp->add_flag("--mtx", export_request.mtx, "write <prefix>.A.mtx and <prefix>.B.mtx (Matrix Market)");

  BatchRequest batch_request;
  auto* batch = app.add_subcommand("batch", "solve many boundaries as Coons net and at several alpha; "
                                   "write nets and OBJ files and a metrics table");
  batch->add_option("BOUNDARY", batch_request.inputs, "boundary files or folders of them")->required();
  batch->add_option("--out", batch_request.out_dir, "output folder")->capture_default_str();
  batch->add_option("--alphas", batch_request.alphas, "alpha values to solve at")->capture_default_str();
  batch->add_option("--samples", batch_request.samples, "surface samples per direction")->capture_default_str();
  batch->add_option("--solver", net_request.solver, "a name from `coons solvers`, or auto")->capture_default_str();

  SearchRequest search_request;
  auto* search = app.add_subcommand("search-alpha", "the best mask parameter of one boundary for an objective "
                                    "(Ceres, analytic derivative); prints one JSON report");
  search->add_option("BOUNDARY", boundary_path, "boundary JSON file (docs/formats.md)")->required();
  add_search_options(*search, search_request);
  search->add_option("--solver", net_request.solver, "a name from `coons solvers`, or auto")->capture_default_str();

  SweepRequest sweep_request;
  auto* sweep = app.add_subcommand("sweep", "every metric on a grid of alpha (or mu): NAME.sweep.jsonl and a PNG plot");
  sweep->add_option("BOUNDARY", boundary_path, "boundary JSON file (docs/formats.md)")->required();
  add_sweep_options(*sweep, sweep_request);
  sweep->add_option("--solver", net_request.solver, "a name from `coons solvers`, or auto")->capture_default_str();

  RefitRequest refit_request;
  auto* refit = app.add_subcommand("refit", "the boundary at another degree: refitted from its analytic \"curves\", "
                                   "or elevated exactly; prints (or writes) a boundary file");
  refit->add_option("BOUNDARY", boundary_path, "boundary JSON file (docs/formats.md)")->required();
  add_refit_options(*refit, refit_request);

  StudyRequest study_request;
  auto* study = app.add_subcommand("study", "the alpha study: optima per shape and degree, the c/n^2 law, the dome "
                                   "table; a self-contained report with PNG figures");
  add_study_options(*study, study_request);
  study->add_option("--solver", net_request.solver, "a name from `coons solvers`, or auto")->capture_default_str();
  for (int a = 0; a < argc; ++a) study_request.command_line += (a ? " " : "") + std::string(a ? argv[a] : "coons");

  SurfaceRequest surface_request;
  auto* surface = add_surface_command(app, surface_request);
  JoinRequest join_request;
  auto* join = add_join_command(app, join_request);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::Success& e) {  // --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: command line: " << e.what() << " (see coons --help)\n";
    return kExitBadInput;
  }

  try {
    if (*solve) return cmd_solve(boundary_path, net_request);
    if (*list) return cmd_solvers(solvers_json, solvers_verbose);
    if (*exp) return cmd_export(boundary_path, net_request, export_request);
    if (*batch) return cmd_batch(batch_request, net_request);
    if (*search) return cmd_search_alpha(boundary_path, net_request, search_request);
    if (*sweep) return cmd_sweep(boundary_path, net_request, sweep_request);
    if (*study) return cmd_study(study_request, net_request);
    if (*refit) return cmd_refit(boundary_path, net_request, refit_request);
    if (*surface) return cmd_surface(surface_request);
    if (*join) return cmd_join(join_request);
  } catch (const InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return kExitBadInput;
  }
  return kExitBadInput;
}

}  // namespace coons::cli
