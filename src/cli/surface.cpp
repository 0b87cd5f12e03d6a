// `coons surface SPEC.json --samples K`: build any surface of the continuous Coons family from its
// JSON description (docs/formats.md "Curves and surfaces"), print {"type", "points": K×K} with the
// Bézier net (exact when the surface is polynomial, else over Bézier fits of its curves, with the
// deviations), exact energies of that net, its distance to the closed-form discrete nets of its
// boundary, the corner twists and the compatibility diagnostics; optionally write meshes (OBJ,
// PLY with per-vertex scalars, ParaView .vts), a PNG of surface and net, and the net as a boundary
// file that `coons solve` reads. Every file is published together, only when all are complete.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/mesh_export.h"
#include "coons/io/net_json.h"
#include "coons/io/plot.h"
#include "coons/io/surface_io.h"
#include "coons/io/write_files.h"
#include "coons/metrics/energies.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/surface_report.h"
#include "coons/surfaces/sampling.h"
#include "registry.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct SurfaceRequest {
  std::string spec;
  int samples = 21;
  std::string obj, ply, vts, png, net_out;
  std::string reference;  //!< a surface description, or a file with "net" (a boundary file, a solve report)
  int fit_degree = 5;
  double corner_tolerance = 1e-9;
  double derivative_tolerance = 1e-7;
  GlobalOptions global;
};

void check_output(const std::string& path, const char* option, bool force) { require_new_file(path, force, option); }

int run_surface(const SurfaceRequest& r) {
  // Everything is read and checked before anything is written.
  if (r.samples < 2) throw InputError("command line", "--samples", fmt::format("must be >= 2, not {}", r.samples));
  check_memory(r.global, samples_bytes(r.samples), fmt::format("{} x {} surface samples", r.samples, r.samples),
               "command line", "--samples");
  if (r.fit_degree < 1 || r.fit_degree > 30)
    throw InputError("command line", "--fit-degree", fmt::format("must be in [1, 30], not {}", r.fit_degree));
  check_corner_tolerance(r.corner_tolerance);
  if (!(r.derivative_tolerance >= 0 && std::isfinite(r.derivative_tolerance)))
    throw InputError("command line", "--derivative-tolerance", "must be a finite number >= 0");
  check_output(r.obj, "--obj", r.global.force);
  check_output(r.ply, "--ply", r.global.force);
  check_output(r.vts, "--vts", r.global.force);
  check_output(r.png, "--png", r.global.force);
  check_output(r.net_out, "--net-out", r.global.force);
  SurfaceReadOptions options;
  options.min_model_size = kMinModelSize;  // curvatures and distances: surface_io.h
  options.corner_tolerance = r.corner_tolerance;
  options.derivative_tolerance = r.derivative_tolerance;
  const SurfaceFile input = read_surface_file(r.spec, options);
  std::optional<SurfaceFile> reference;
  if (!r.reference.empty()) reference = read_surface_reference(r.reference, options);

  // The net (a degree-30000 curve makes a 30001 by 2 one) is held to the limit before its
  // energies are taken: their banded Gram matrices are the largest part.
  FittedNet fitted_net_of_input = fitted_net(input.surface, r.fit_degree);
  const ControlNet& made_net = fitted_net_of_input.net;
  check_memory(r.global, net_metrics_bytes(made_net.m, made_net.n),
               fmt::format("the exact energies of its {} by {} Bezier net", made_net.m + 1, made_net.n + 1), r.spec,
               net_degree_field(input.surface, fitted_net_of_input));
  SurfaceReportOptions report_options{r.samples, r.fit_degree, r.corner_tolerance, r.derivative_tolerance, r.reference};
  SurfaceReport made = surface_report(input, std::move(fitted_net_of_input), reference, report_options);
  // The reader checked 65 samples of each curve; a pole between them shows in the fits.
  for (const CurveFitReport& fit : made.fitted.fits)
    if (!std::isfinite(fit.max_deviation))
      throw InputError(r.spec, fit.curve,
                       fmt::format("is not finite between the samples the reader checks (a pole?): its Bezier fit "
                                   "of degree {} is not finite",
                                   fit.degree));
  nlohmann::ordered_json& report = made.report;
  const SurfaceSamples& samples = made.samples;
  const FittedNet& fitted = made.fitted;
  const ControlNet& net = fitted.net;
  const Surface& surface = input.surface;
  const int k = r.samples;

  // Writing: everything staged, published together after the report is out.
  OutputSet out(".", "output");
  nlohmann::ordered_json written = nlohmann::ordered_json::array();
  const std::string comment = fmt::format("{} ({})", input.name, to_string(surface.type()));
  if (!r.png.empty()) {
    const std::string title = fmt::format(
        "{} ({}){}", input.name, to_string(surface.type()),
        fitted.exact ? ", exact Bezier net" : fmt::format(", net over Bezier fits of degree <= {}", fitted.fit_degree));
    if (const std::string why = plot_surface(out.stage_path(r.png), samples.points, k, &net, title); !why.empty())
      throw InputError(r.png, "--png", why);
    written.push_back(r.png);
  }
  if (!r.obj.empty()) {
    out.write_path(r.obj, [&](std::ostream& o) { write_grid_obj(o, samples, comment); });
    written.push_back(r.obj);
  }
  if (!r.ply.empty()) {
    out.write_path(r.ply, [&](std::ostream& o) { write_grid_ply(o, samples, comment); });
    written.push_back(r.ply);
  }
  if (!r.vts.empty()) {
    out.write_path(r.vts, [&](std::ostream& o) { write_grid_vts(o, samples); });
    written.push_back(r.vts);
  }
  if (!r.net_out.empty()) {
    const json doc = {
        {"name", input.name}, {"degree", {net.m, net.n}}, {"exact", fitted.exact}, {"net", net_to_json(net)}};
    out.write_path(r.net_out, [&](std::ostream& o) { o << dump(doc, 2) << '\n'; });
    written.push_back(r.net_out);
  }
  if (!written.empty()) report["written"] = std::move(written);
  report["net"] = std::move(made.net_block);
  report["points"] = std::move(made.points);
  out.publish([&] { print_json(report); });
  return kExitOk;
}

}  // namespace

void register_surface(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<SurfaceRequest>();
  SurfaceRequest& r = *request;
  auto* cmd = app.add_subcommand("surface",
                                 "build a surface of the continuous Coons family from its JSON description "
                                 "(docs/formats.md); prints points, Bezier net, metrics; writes meshes and a PNG");
  cmd->add_option("SPEC", r.spec,
                  "surface description JSON (types: ruled, sectorial, bilinear, conoid, "
                  "bilinear-coons, hermite-coons, ferguson, hermite16, general-coons, bezier)")
      ->required();
  cmd->add_option("--samples,--sample", r.samples, "K: print r(a/(K-1), b/(K-1)) on a K x K grid; meshes use it too")
      ->capture_default_str();
  cmd->add_option("--obj", r.obj, "write the sampled surface as Wavefront OBJ");
  cmd->add_option("--ply", r.ply, "write PLY with per-vertex normals and scalars (curvatures, twist, distance)");
  cmd->add_option("--vts", r.vts, "write a ParaView structured grid (.vts) with the same point fields");
  cmd->add_option("--png", r.png, "render the surface and its control net (gnuplot)");
  cmd->add_option("--net-out", r.net_out,
                  "write the Bezier net as a boundary file {\"net\": ...} (coons solve reads it)");
  cmd->add_option("--reference", r.reference, "a surface description or a file with \"net\": adds the distance field");
  cmd->add_option("--fit-degree", r.fit_degree,
                  "largest degree of the Bezier fits of non-Bezier curves for the net "
                  "(a lower one when it reproduces the curve to rounding)")
      ->capture_default_str();
  cmd->add_option("--corner-tolerance", r.corner_tolerance,
                  "corners must agree to this fraction of the boundary's size")
      ->capture_default_str();
  cmd->add_option("--derivative-tolerance", r.derivative_tolerance,
                  "general-coons tangent and twist conditions: this fraction of the data's size")
      ->capture_default_str();
  cmd->add_flag("--force", r.global.force, "overwrite existing output files");
  add_memory_option(*cmd, r.global);
  set_example(*cmd, "coons surface data/surfaces/seed000_ferguson_1.json --samples 21 --obj ferguson.obj");
  registry.add(cmd, [request] { return run_surface(*request); });
}

}  // namespace coons::cli
