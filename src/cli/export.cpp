// `coons export BOUNDARY`: the net as OBJ files and/or the mask system as Matrix Market, written
// whole or not at all (an OutputSet), inside --out only.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <optional>

#include "bspline_commands.h"
#include "cad_commands.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/matrix_market.h"
#include "coons/io/obj_export.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/write_files.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/stencil_system.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/net_report.h"
#include "net_request.h"
#include "registry.h"
#include "tri_commands.h"

namespace coons::cli {

namespace {

struct ExportRequest {
  std::string boundary;
  NetRequest net;
  GlobalOptions global;
  std::string out_dir = ".";
  std::string prefix;
  int samples = 33;
  bool obj = false, mtx = false, ply = false, vtu = false, vts = false;
  CadExportRequest cad;  // --step, --iges (cad_commands.h)
};

// Each flag names the boundaries that have it (--ply: triangles and B-splines, --vtu: triangles
// only, --vts: B-splines only): on a Bézier boundary they are bad input.
void refuse_flags_of_other_boundaries(const ExportRequest& e) {
  if (e.ply)
    throw InputError("command line", "--ply",
                     "is written for triangular and B-spline boundaries (for a Bézier one: coons surface --ply)");
  if (e.vtu)
    throw InputError("command line", "--vtu",
                     "is written for triangular boundaries (a Bézier one's surface as VTK: coons surface --vts)");
  if (e.vts)
    throw InputError("command line", "--vts",
                     "is written for B-spline boundaries (for a Bézier one: coons surface --vts)");
}

// A failed solve: its report (with the timing) on standard output, the error line, exit 3.
int report_failed_solve(nlohmann::json failed, Phases& phases, const std::string& file,
                        const solvers::SolveSummary& summary) {
  failed["timing"] = phases.timing();
  print_json(failed);
  print_solver_failure(file, summary);
  return kExitSolverFailed;
}

// The system --mtx writes: the stencil problem's (`run`) or the classical one's of `b`.
void assemble_export_system(const StencilRun* run, const Boundary& b, const ResolvedRequest& r,
                            Eigen::SparseMatrix<double>& A, Eigen::MatrixX3d& B) {
  if (run) {
    StencilSystem system = assemble_stencil_system(run->problem, run->stencil);
    A.swap(system.A);  // Eigen::SparseMatrix has no move assignment
    B = std::move(system.B);
  } else {
    MaskSystem system = assemble_mask_system(frame_net(b), r.mask, true);
    A.swap(system.A);
    B = std::move(system.B);
  }
}

int run_export(ExportRequest e) {
  if (is_triangle_file(e.boundary) && e.vts)
    throw InputError("command line", "--vts", "is written for B-spline boundaries (triangles: --vtu)");
  if (is_triangle_file(e.boundary) && e.cad.any())
    throw InputError("command line", e.cad.step.empty() ? "--iges" : "--step",
                     "is written for rectangular nets (STEP and IGES have no triangular Bézier surface)");
  if (is_triangle_file(e.boundary))
    return run_tri_export({e.boundary, &e.net, &e.global, e.out_dir, e.prefix, e.samples, e.obj, e.mtx, e.ply, e.vtu});
  Phases phases("export");
  phases.start("read");
  const BoundaryFile input = read_input(e.boundary, e.net.corner_tolerance, true);
  if (input.bspline) {  // every output, --step/--iges included, from the B-spline path (its knots)
    // the curvatures of --ply and --vts leave the doubles below kMinModelSize: a model of 1e-160
    // wrote a Gaussian curvature of 0 (it is about 1e319), unflagged (read again to name its point)
    if (e.ply || e.vts) (void)read_input(e.boundary, e.net.corner_tolerance, true, kMinModelSize);
    if (e.vtu) throw InputError("command line", "--vtu", "is written for triangular boundaries (B-spline: --vts)");
    return run_bspline_export(
        {e.boundary, e.out_dir, e.prefix, e.samples, e.obj, e.mtx, e.ply, e.vts, e.global.force, e.cad}, input, e.net,
        e.global, phases);
  }
  refuse_flags_of_other_boundaries(e);
  const Boundary& b = input.boundary;
  const ResolvedRequest r = resolve(e.net, b, e.boundary);
  const bool defaults = !e.obj && !e.mtx && !e.cad.any();
  if (defaults) {  // the defaults: OBJ, and the system when there is one
    e.obj = true;
    e.mtx = r.method == Method::kAlpha;
  }
  check_export_options(e.samples, e.mtx, r.method == Method::kAlpha, e.prefix);
  check_net_memory(e.global, b, r.solver, e.boundary, stencil_nonzeros(r));
  // Beyond the classical problem (two data rings, a free grid, a mask other than alpha): the
  // stencil solve of `coons solve`, checked here, before anything is written.
  const bool classical = is_classical_request(input, r);
  std::optional<StencilRun> run;
  if (!classical)
    run = check_stencil_request(input, r, e.boundary);
  else
    check_classical_request(input, r, e.boundary);
  // A system of no unknowns (degree 1, or a free grid with none) was written as "0 0 0", which no
  // reader takes (bench-matrix: rows and columns must be at least 1): not by default, and asked
  // for, bad input.
  const long long unknowns =
      run ? (long long)free_points(run->problem).count() : (long long)(b.m - 1) * (long long)(b.n - 1);
  if (e.mtx && unknowns == 0) {
    if (!defaults)
      throw InputError(
          e.boundary, "--mtx",
          fmt::format("the {} by {} net has no point to solve for: there is no system to write", b.m + 1, b.n + 1));
    e.mtx = false;
  }
  if (e.cad.any()) check_cad_export(e.cad, e.global.force);
  const bool solve_net = e.obj || e.cad.any();
  if (e.obj)
    check_memory(e.global, samples_bytes(e.samples), fmt::format("{} x {} surface samples", e.samples, e.samples),
                 "command line", "--samples");
  const std::string prefix = e.prefix.empty() ? safe_file_stem(b.name) : e.prefix;

  OutputSet out(e.out_dir, "--out");
  std::vector<std::string> names;
  if (e.obj) names.insert(names.end(), {prefix + ".surface.obj", prefix + ".net.obj"});
  if (e.mtx) names.insert(names.end(), {prefix + ".A.mtx", prefix + ".B.mtx"});
  for (const auto& name : names) require_new_output(out.path_of(name), e.global.force, "--out");

  nlohmann::json report = {{"boundary", b.name}, {"degree", {b.m, b.n}}, {"method", to_string(r.method)}};
  NetOutcome outcome;
  if (run) {
    report["mask"] = r.mask_name;
    if (r.weight) report["weight"] = *r.weight;
    report["rings"] = run->problem.rings;
    report["free_points"] = free_points(run->problem).count();
  }
  if (solve_net && run) {
    phases.start("solve");
    *run = solve_stencil_request(input, r, e.net, e.global, e.boundary);
    report["solver"] = solver_block(run->result.summary, run->picked_automatically);
    if (!run->result.summary.ok()) {
      return report_failed_solve(stencil_report(input, r, *run, e.net.mu), phases, e.boundary, run->result.summary);
    }
    print_solver_warning(e.boundary, run->result.summary);
    outcome.net = run->result.net;
  } else if (solve_net) {
    phases.start("solve");
    outcome = make_net(b, r);
    report["solver"] = solver_block(outcome.summary, r.picked_automatically);
    if (outcome.summary && !outcome.summary->ok()) {
      return report_failed_solve(solve_report(b, r, outcome, e.net.mu), phases, e.boundary, *outcome.summary);
    }
    if (outcome.summary) print_solver_warning(e.boundary, *outcome.summary);
  }
  std::vector<std::string> written;
  if (e.obj) {
    phases.start("write");
    written.push_back(out.path_of(names[0]));
    out.write(names[0], [&](std::ostream& o) { write_surface_obj(o, outcome.net, e.samples); });
    written.push_back(out.path_of(names[1]));
    out.write(names[1], [&](std::ostream& o) { write_net_obj(o, outcome.net); });
  }
  if (e.mtx) {
    phases.start("assemble");
    Eigen::SparseMatrix<double> A;
    Eigen::MatrixX3d B;
    assemble_export_system(run ? &*run : nullptr, b, r, A, B);
    phases.start("write");
    const std::string& a = names[e.obj ? 2 : 0];
    const std::string& rhs = names[e.obj ? 3 : 1];
    written.push_back(out.path_of(a));
    out.write(a, [&](std::ostream& o) { write_matrix_market(o, A); });
    written.push_back(out.path_of(rhs));
    out.write(rhs, [&](std::ostream& o) { write_dense_matrix_market(o, B); });
    report["matrix_market"] = {{"matrix", "coordinate real general (both triangles stored)"},
                               {"rhs",
                                "array real general, #free by 3 (x, y, z; the interior points for the "
                                "classical problem)"}};
  }
  if (e.cad.any()) {
    phases.start("write");
    for (auto& path : write_cad_export(e.cad, bezier_surface_for_cad(outcome.net), out)) written.push_back(path);
  }
  report["written"] = written;
  report["timing"] = phases.timing();
  out.publish([&] { print_json(report); });
  return kExitOk;
}

}  // namespace

void register_export(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<ExportRequest>();
  auto* cmd = app.add_subcommand("export", "write the net as OBJ files and/or the mask system as Matrix Market");
  cmd->add_option("BOUNDARY", request->boundary, "boundary JSON file (docs/formats.md)")->required();
  add_net_options(*cmd, request->net);
  add_mask_options(*cmd, request->net);
  cmd->add_option("--out", request->out_dir, "output folder")->capture_default_str();
  cmd->add_option("--prefix", request->prefix, "file name prefix (default: the boundary's name, made safe)");
  cmd->add_option("--samples", request->samples, "surface samples per direction")->capture_default_str();
  cmd->add_flag("--obj", request->obj, "write <prefix>.surface.obj and <prefix>.net.obj");
  cmd->add_flag("--mtx", request->mtx, "write <prefix>.A.mtx and <prefix>.B.mtx (Matrix Market)");
  cmd->add_flag("--ply", request->ply, "triangles and B-spline boundaries: write <prefix>.surface.ply");
  cmd->add_flag("--vtu", request->vtu, "triangles: write <prefix>.surface.vtu (VTK unstructured grid)");
  add_cad_export_options(*cmd, request->cad);
  cmd->add_flag("--vts", request->vts, "B-spline boundaries: write <prefix>.surface.vts (VTK structured grid)");
  cmd->add_flag("--force", request->global.force, "overwrite existing files of the same names");
  add_memory_option(*cmd, request->global);
  set_example(*cmd, "coons export data/boundaries/pillow.json --alpha -0.1 --samples 33 --out out/pillow");
  registry.add(cmd, [request] { return run_export(*request); });
}

}  // namespace coons::cli
