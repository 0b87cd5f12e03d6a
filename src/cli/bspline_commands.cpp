#include "bspline_commands.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "coons/io/input_error.h"
#include "coons/io/matrix_market.h"
#include "coons/io/mesh_export.h"
#include "coons/io/obj_export.h"
#include "coons/io/write_files.h"
#include "coons/mask/nonuniform_mask.h"
#include "coons/study/bspline_net.h"
#include "coons/study/bspline_search.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/net_report.h"
#include "coons/surfaces/bspline_sampling.h"
#include "report_output.h"
#include "search_inputs.h"

namespace coons::cli {

namespace {

// The memory of a B-spline solve: the sparse system (9 entries a row, twice for dA) and the dense
// Gram matrices of the energies, estimated like a Bézier net of the compatible size.
void check_bspline_memory(const GlobalOptions& global, const BSplineInput& in, const std::string& file) {
  const double count_u = in.compatible.bottom.count(), count_v = in.compatible.left.count();
  const double bytes = count_u * count_v * (2 * 9 * 16 + 200) + 8 * (count_u * count_u + count_v * count_v);
  check_memory(global, bytes, fmt::format("a B-spline net of {} x {} points", count_u, count_v), file, "knots_u");
}

BSplineNetOutcome solve_bspline(const BSplineInput& in, const BSplineResolved& r) {
  std::unique_ptr<solvers::LinearSolver> solver;
  if (r.method == Method::kAlpha) solver = solvers::make_solver(r.solver, r.options);
  return make_bspline_net(in.compatible, r.method, r.alpha, solver.get());
}

}  // namespace

BSplineResolved resolve_bspline(const NetRequest& request, const BoundaryFile& input, const std::string& source) {
  // The contradictions of every net request; but resolve's range of a Cholesky-type backend is the
  // Bézier family's [−1/4, 1/4], and a B-spline boundary's is [−1/4, U] (checked below).
  NetRequest generic = request;
  generic.allow_indefinite = true;
  const ResolvedRequest r = resolve(generic, input.boundary, source);
  if (r.method == Method::kHermiteCoons)
    throw InputError("command line", "--method",
                     "hermite-coons has no B-spline form; a B-spline boundary takes --method coons or alpha");
  if (r.mask_kind != MaskKind::kAlpha)
    throw InputError("command line", "--mask",
                     "a B-spline boundary (knots_u, knots_v) takes the non-uniform alpha family only (--mask alpha)");
  if (given(request.mu_option))
    throw InputError("command line", "--mu",
                     "--mu chooses the anisotropic Bézier mask; a B-spline boundary takes --alpha");
  BSplineResolved out;
  out.method = r.method;
  out.alpha = request.alpha;  // for --method coons, the mask its mask_residual is measured against
  out.options = r.options;
  if (r.method != Method::kAlpha) return out;
  if (request.solver == "auto") {
    out.solver = auto_bspline_solver(out.alpha);
    out.picked_automatically = true;
  } else {
    require_matrix_backend(r.solver, kBSplineNeedsMatrix);  // gmres falls back to ILUT on a matrix
    out.solver = r.solver->name;
    // U ≤ 1/4: where the non-uniform system stops being definite (a Cholesky-type backend accepted
    // an α between U and 1/4 and then failed with exit 3); found only when α is outside [−1/4, 0]
    if (r.solver->definite_only && !request.allow_indefinite && !(out.alpha >= -0.25 && out.alpha <= 0)) {
      const double upper = bspline_definite_upper(input.bspline->compatible);
      if (!(out.alpha >= -0.25 && out.alpha <= upper))
        throw InputError("command line", "--alpha",
                         fmt::format("{} is outside [-0.25, {}], where the non-uniform mask system of {} is positive "
                                     "definite; {} needs that (use eigen-lu, or --allow-indefinite to try anyway)",
                                     out.alpha, upper, source, out.solver));
    }
  }
  return out;
}

int run_bspline_solve(const std::string& file, const BoundaryFile& input, const NetRequest& request,
                      const GlobalOptions& global, Phases& phases) {
  const BSplineResolved r = resolve_bspline(request, input, file);
  const BSplineInput& in = *input.bspline;
  check_bspline_memory(global, in, file);
  phases.start("solve");
  const BSplineNetOutcome outcome = solve_bspline(in, r);
  phases.start("metrics");
  const nlohmann::json report =
      bspline_net_report(input.boundary.name, in, r.method, r.alpha, outcome, r.picked_automatically, false);
  const bool ok = !outcome.summary || outcome.summary->ok();
  print_net_report(report, ok ? &outcome.surface.net : nullptr, phases);
  if (!ok) {
    print_solver_failure(file, *outcome.summary);
    return kExitSolverFailed;
  }
  return kExitOk;
}

BSplineBatchNet bspline_batch_net(const std::string& file, const BoundaryFile& input, const NetRequest& request,
                                  const GlobalOptions& global) {
  BSplineBatchNet net;
  net.resolved = resolve_bspline(request, input, file);
  const BSplineResolved& r = net.resolved;
  check_bspline_memory(global, *input.bspline, file);
  net.outcome = solve_bspline(*input.bspline, r);
  if (net.ok()) net.metrics = bspline_metrics(net.outcome.local, r.alpha);  // r.alpha: --alpha, −1/4 by default
  net.report = bspline_net_report(input.boundary.name, *input.bspline, r.method, r.alpha, net.outcome,
                                  r.picked_automatically, true, net.metrics ? &*net.metrics : nullptr);
  return net;
}

std::string bspline_samples_comment(const std::string& name, int samples) {
  return fmt::format("B-spline surface of {} ({} x {} samples)", name, samples, samples);
}

std::vector<std::string> write_bspline_objs(OutputSet& out, const std::string& stem, const SurfaceSamples& grid,
                                            const std::string& comment, const ControlNet& net) {
  out.write(stem + ".surface.obj", [&](std::ostream& o) { write_grid_obj(o, grid, comment); });
  out.write(stem + ".net.obj", [&](std::ostream& o) { write_net_obj(o, net); });
  return {out.path_of(stem + ".surface.obj"), out.path_of(stem + ".net.obj")};
}

int run_bspline_export(const BSplineExportRequest& given_request, const BoundaryFile& input, const NetRequest& request,
                       const GlobalOptions& global, Phases& phases) {
  BSplineExportRequest e = given_request;
  const BSplineResolved r = resolve_bspline(request, input, e.file);
  const BSplineInput& in = *input.bspline;
  const bool defaults = !e.obj && !e.mtx && !e.ply && !e.vts && !e.cad.any();
  if (defaults) {  // the defaults: OBJ, and the system when there is one
    e.obj = true;
    e.mtx = r.method == Method::kAlpha;
  }
  // a net with no point to solve for has a system of no unknowns ("0 0 0"), as a Bézier net of
  // degree 1: not written by default, and asked for, bad input
  if (const ControlNet frame = bspline_frame(in.compatible); e.mtx && (frame.m < 2 || frame.n < 2)) {
    if (!defaults)
      throw InputError(e.file, "--mtx",
                       fmt::format("the {} by {} net has no point to solve for: there is no system to write",
                                   frame.m + 1, frame.n + 1));
    e.mtx = false;
  }
  check_export_options(e.samples, e.mtx, r.method == Method::kAlpha, e.prefix);
  check_bspline_memory(global, in, e.file);
  if (e.cad.any()) check_cad_export(e.cad, e.force);
  const bool sampled = e.obj || e.ply || e.vts;
  if (sampled)
    check_memory(global, samples_bytes(e.samples), fmt::format("{} x {} surface samples", e.samples, e.samples),
                 "command line", "--samples");
  const std::string prefix = e.prefix.empty() ? safe_file_stem(input.boundary.name) : e.prefix;

  OutputSet out(e.out_dir, "--out");
  std::vector<std::string> names;
  if (e.obj) names.insert(names.end(), {prefix + ".surface.obj", prefix + ".net.obj"});
  if (e.ply) names.push_back(prefix + ".surface.ply");
  if (e.vts) names.push_back(prefix + ".surface.vts");
  if (e.mtx) names.insert(names.end(), {prefix + ".A.mtx", prefix + ".B.mtx"});
  for (const auto& name : names) require_new_output(out.path_of(name), e.force, "--out");

  const BSplineSurface frame_surface = bspline_surface_on(in.compatible, bspline_frame(in.compatible));
  nlohmann::json report = {{"boundary", input.boundary.name},
                           {"degree", {frame_surface.net.m, frame_surface.net.n}},
                           {"method", to_string(r.method)}};
  report["bspline"] = bspline_block(frame_surface, in);
  BSplineNetOutcome outcome;
  // The system is solved for --mtx too: a singular one is refused (exit 3, as without --mtx)
  // rather than written.
  if (sampled || e.cad.any() || e.mtx) {
    phases.start("solve");
    outcome = solve_bspline(in, r);
    report["solver"] = solver_block(outcome.summary, r.picked_automatically);
    if (outcome.summary && !outcome.summary->ok()) {
      nlohmann::json failed =
          bspline_net_report(input.boundary.name, in, r.method, r.alpha, outcome, r.picked_automatically);
      failed["timing"] = phases.timing();
      print_json(failed);
      print_solver_failure(e.file, *outcome.summary);
      return kExitSolverFailed;
    }
  }
  std::vector<std::string> written;
  const auto write = [&](const std::string& name, const std::function<void(std::ostream&)>& body) {
    written.push_back(out.path_of(name));
    out.write(name, body);
  };
  if (sampled) {
    phases.start("write");
    const SurfaceSamples samples = sample_bspline_grid(outcome.surface, e.samples);
    const std::string comment = bspline_samples_comment(input.boundary.name, e.samples);
    if (e.obj)
      for (std::string& path : write_bspline_objs(out, prefix, samples, comment, outcome.surface.net))
        written.push_back(std::move(path));
    if (e.ply) write(prefix + ".surface.ply", [&](std::ostream& o) { write_grid_ply(o, samples, comment); });
    if (e.vts) write(prefix + ".surface.vts", [&](std::ostream& o) { write_grid_vts(o, samples); });
  }
  if (e.cad.any()) {
    phases.start("write");
    for (auto& path : write_cad_export(e.cad, outcome.surface, out)) written.push_back(path);
  }
  if (e.mtx) {
    phases.start("assemble");
    const NonUniformMaskSystem system =
        assemble_nonuniform_mask_system(bspline_frame(in.compatible), greville_grid(in.compatible), r.alpha);
    phases.start("write");
    write(prefix + ".A.mtx", [&](std::ostream& o) { write_matrix_market(o, system.A); });
    write(prefix + ".B.mtx", [&](std::ostream& o) { write_dense_matrix_market(o, system.B); });
    report["matrix_market"] = {
        {"matrix", "coordinate real general (both triangles stored): the non-uniform alpha system, rows scaled"},
        {"rhs", "array real general, #interior by 3 (x, y, z)"}};
  }
  report["written"] = written;
  report["timing"] = phases.timing();
  out.publish([&] { print_json(report); });
  return kExitOk;
}

}  // namespace coons::cli
