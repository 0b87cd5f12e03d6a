// `coons surface SPEC.json --samples K`: build any surface of the continuous Coons family from its
// JSON description (docs/formats.md "Curves and surfaces"), print {"type", "points": K×K} with the
// Bézier net (exact when the surface is polynomial, else over Bézier fits of its curves, with the
// deviations), exact energies of that net, its distance to the closed-form discrete nets of its
// boundary, the corner twists and the compatibility diagnostics; optionally write meshes (OBJ,
// PLY with per-vertex scalars, ParaView .vts), a PNG of surface and net, and the net as a boundary
// file that `coons solve` reads. Every file is published together, only when all are complete.
#include <memory>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "registry.h"
#include "coons/io/input_error.h"
#include "coons/io/mesh_export.h"
#include "coons/io/net_json.h"
#include "coons/io/plot.h"
#include "coons/io/surface_io.h"
#include "coons/io/write_files.h"
#include "coons/net/bernstein.h"
#include "coons/study/memory_estimate.h"
#include "coons/metrics/energies.h"
#include "coons/net/coons_net.h"
#include "coons/surfaces/sampling.h"

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

json point_json(const Eigen::RowVector3d& p) { return json::array({number_or_null(p(0)), number_or_null(p(1)), number_or_null(p(2))}); }

double finite_max(const Eigen::VectorXd& x, bool absolute) {
  double m = 0;
  for (Eigen::Index k = 0; k < x.size(); ++k)
    if (std::isfinite(x(k))) m = std::max(m, absolute ? std::abs(x(k)) : x(k));
  return m;
}

// A reference: a surface description, or any file holding "net" (boundary file, solve report).
SurfaceFile read_reference(const std::string& path, const SurfaceReadOptions& options) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the file (--reference)");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception&) {
    throw InputError(path, "", "malformed JSON (--reference)");
  }
  if (doc.is_object() && !doc.contains("type") && doc.contains("net"))
    return parse_surface(json{{"type", "bezier"}, {"net", doc["net"]}}, path, options);
  return parse_surface(doc, path, options);
}

void check_output(const std::string& path, const char* option, bool force) {
  if (path.empty()) return;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw InputError("command line", option, fmt::format("the folder '{}' does not exist", parent.string()));
  if (!force && fs::exists(path)) throw InputError(path, "--force", "exists; give --force to overwrite it");
}

json energies_json(const ControlNet& net) {
  return {{"twist_energy", twist_energy(net)},
          {"thin_plate_energy", thin_plate_energy(net)},
          {"dirichlet_energy", dirichlet_energy(net)},
          {"e3_energy", e3_energy(net)},
          {"discrete_twist_energy", discrete_twist_energy(net)},
          {"discrete_dirichlet_energy", discrete_dirichlet_energy(net)}};
}

double max_difference(const ControlNet& a, const ControlNet& b) { return (a.points - b.points).cwiseAbs().maxCoeff(); }

int run_surface(const SurfaceRequest& r) {
  // Everything is read and checked before anything is written.
  if (r.samples < 2) throw InputError("command line", "--samples", fmt::format("must be >= 2, not {}", r.samples));
  check_memory(r.global, samples_bytes(r.samples), fmt::format("{} x {} surface samples", r.samples, r.samples),
               "command line", "--samples");
  if (r.fit_degree < 1 || r.fit_degree > 30)
    throw InputError("command line", "--fit-degree", fmt::format("must be in [1, 30], not {}", r.fit_degree));
  if (!(r.corner_tolerance >= 0)) throw InputError("command line", "--corner-tolerance", "must be >= 0");
  if (!(r.derivative_tolerance >= 0)) throw InputError("command line", "--derivative-tolerance", "must be >= 0");
  check_output(r.obj, "--obj", r.global.force);
  check_output(r.ply, "--ply", r.global.force);
  check_output(r.vts, "--vts", r.global.force);
  check_output(r.png, "--png", r.global.force);
  check_output(r.net_out, "--net-out", r.global.force);
  SurfaceReadOptions options;
  options.corner_tolerance = r.corner_tolerance;
  options.derivative_tolerance = r.derivative_tolerance;
  const SurfaceFile input = read_surface_file(r.spec, options);
  std::optional<SurfaceFile> reference;
  if (!r.reference.empty()) reference = read_reference(r.reference, options);

  const Surface& surface = input.surface;
  const int k = r.samples;
  SurfaceSamples samples = sample_grid(surface, k);
  if (reference) add_reference_distance(samples, reference->surface);
  const FittedNet fitted = fitted_net(surface, r.fit_degree);

  nlohmann::ordered_json report;  // read top-down: what it is, diagnostics, metrics, then the big arrays
  report["surface"] = input.name;
  report["type"] = to_string(surface.type());
  report["sample"] = k;
  report["polynomial"] = fitted.exact;
  json curves = json::object();
  for (const auto& [field, curve] : surface.curves()) curves[field] = curve->kind();
  if (!curves.empty()) report["curves"] = std::move(curves);
  json points = json::array();
  for (int a = 0; a < k; ++a) {
    json row = json::array();
    for (int b = 0; b < k; ++b) row.push_back(point_json(samples.points.row(a * k + b)));
    points.push_back(std::move(row));
  }

  // The net: exact, or over fitted curves with the deviations.
  const ControlNet& net = fitted.net;
  json net_block = {{"degree", {net.m, net.n}}, {"exact", fitted.exact}};
  if (!fitted.exact) {
    net_block["fit_degree"] = fitted.fit_degree;
    json fits = json::array();
    for (const auto& f : fitted.fits)
      fits.push_back({{"curve", f.curve}, {"degree", f.degree}, {"max_deviation", number_or_null(f.max_deviation)}});
    net_block["max_curve_deviation"] = number_or_null(fitted.max_curve_deviation);
    net_block["curve_fits"] = std::move(fits);
    double worst = 0;
    const Eigen::MatrixX3d S = sample_surface(net, k, k);
    for (int row = 0; row < k * k; ++row) worst = std::max(worst, (S.row(row) - samples.points.row(row)).norm());
    net_block["max_surface_deviation"] = number_or_null(worst);
  }
  net_block["net"] = net_to_json(net);

  json metrics = energies_json(net);
  metrics["of"] = fitted.exact ? "the exact Bezier net" : "the net over the Bezier fits";
  report["metrics"] = std::move(metrics);

  // The closed-form discrete nets of the same boundary, in the same space.
  json discrete;
  const Boundary boundary = boundary_of(net, input.name);
  const ControlNet coons = discrete_coons_net(boundary);
  discrete["coons"] = {{"max_difference", max_difference(net, coons)}, {"energies", energies_json(coons)}};
  if (net.m >= 3 && net.n >= 3) {
    const ControlNet hermite = hermite_coons_net(boundary);
    discrete["hermite_coons"] = {{"max_difference", max_difference(net, hermite)}, {"energies", energies_json(hermite)}};
  }
  report["discrete_nets"] = std::move(discrete);

  json twists = json::array();
  for (auto [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
    twists.push_back(point_json(surface.evaluate(u, v).duv));
  report["corner_twists"] = std::move(twists);
  report["sampled"] = {{"max_abs_mean_curvature", finite_max(samples.mean_curvature, true)},
                       {"max_abs_gaussian_curvature", finite_max(samples.gaussian_curvature, true)},
                       {"max_twist", finite_max(samples.twist, false)}};

  if (!input.conditions.empty()) {
    json conditions = json::array();
    double worst_position = 0, worst_derivative = 0;
    for (const auto& c : input.conditions) {
      conditions.push_back({{"field", c.field}, {"corner", c.corner}, {"condition", c.condition}, {"gap", number_or_null(c.gap)}});
      double& worst = c.order == 0 ? worst_position : worst_derivative;
      worst = std::max(worst, c.gap);
    }
    report["compatibility"] = {{"size", input.size},
                               {"corner_tolerance", r.corner_tolerance},
                               {"derivative_tolerance", r.derivative_tolerance},
                               {"max_corner_gap", worst_position},
                               {"max_derivative_gap", worst_derivative},
                               {"conditions", std::move(conditions)}};
  }
  if (reference) {
    const Eigen::VectorXd& d = *samples.distance;
    report["reference"] = {{"file", r.reference},
                           {"type", to_string(reference->surface.type())},
                           {"max_distance", finite_max(d, false)},
                           {"rms_distance", std::sqrt(d.squaredNorm() / double(d.size()))},
                           {"max_parametric_distance", finite_max(*samples.parametric_distance, false)}};
  }

  // Writing: everything staged, published together after the report is out.
  OutputSet out(".", "output");
  json written = json::array();
  const std::string comment = fmt::format("{} ({})", input.name, to_string(surface.type()));
  if (!r.png.empty()) {
    const std::string title = fmt::format("{} ({}){}", input.name, to_string(surface.type()),
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
    const json doc = {{"name", input.name}, {"degree", {net.m, net.n}}, {"exact", fitted.exact}, {"net", net_to_json(net)}};
    out.write_path(r.net_out, [&](std::ostream& o) { o << dump(doc, 2) << '\n'; });
    written.push_back(r.net_out);
  }
  if (!written.empty()) report["written"] = std::move(written);
  report["net"] = std::move(net_block);
  report["points"] = std::move(points);
  print_json(report);
  out.commit();
  return kExitOk;
}

}  // namespace


void register_surface(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<SurfaceRequest>();
  SurfaceRequest& r = *request;
  auto* cmd = app.add_subcommand("surface", "build a surface of the continuous Coons family from its JSON description "
                                 "(docs/formats.md); prints points, Bezier net, metrics; writes meshes and a PNG");
  cmd->add_option("SPEC", r.spec, "surface description JSON (types: ruled, sectorial, bilinear, conoid, "
                  "bilinear-coons, hermite-coons, ferguson, hermite16, general-coons, bezier)")->required();
  cmd->add_option("--samples,--sample", r.samples, "K: print r(a/(K-1), b/(K-1)) on a K x K grid; meshes use it too")
      ->capture_default_str();
  cmd->add_option("--obj", r.obj, "write the sampled surface as Wavefront OBJ");
  cmd->add_option("--ply", r.ply, "write PLY with per-vertex normals and scalars (curvatures, twist, distance)");
  cmd->add_option("--vts", r.vts, "write a ParaView structured grid (.vts) with the same point fields");
  cmd->add_option("--png", r.png, "render the surface and its control net (gnuplot)");
  cmd->add_option("--net-out", r.net_out, "write the Bezier net as a boundary file {\"net\": ...} (coons solve reads it)");
  cmd->add_option("--reference", r.reference, "a surface description or a file with \"net\": adds the distance field");
  cmd->add_option("--fit-degree", r.fit_degree, "largest degree of the Bezier fits of non-Bezier curves for the net "
                  "(a lower one when it reproduces the curve to rounding)")
      ->capture_default_str();
  cmd->add_option("--corner-tolerance", r.corner_tolerance, "corners must agree to this fraction of the boundary's size")
      ->capture_default_str();
  cmd->add_option("--derivative-tolerance", r.derivative_tolerance,
                  "general-coons tangent and twist conditions: this fraction of the data's size")->capture_default_str();
  cmd->add_flag("--force", r.global.force, "overwrite existing output files");
  add_memory_option(*cmd, r.global);
  set_example(*cmd, "coons surface data/surfaces/seed000_ferguson_1.json --samples 21 --obj ferguson.obj");
  registry.add(cmd, [request] { return run_surface(*request); });
}


}  // namespace coons::cli
