#include "surface_report.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/net_json.h"
#include "coons/metrics/energies.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"

namespace coons {

using nlohmann::json;

namespace {

// The least grid (per direction) on which the net over fitted curves is compared with the surface.
constexpr int kDeviationGrid = 65;

json energies_json(const ControlNet& net) {
  return {{"twist_energy", twist_energy(net)},
          {"thin_plate_energy", thin_plate_energy(net)},
          {"dirichlet_energy", dirichlet_energy(net)},
          {"e3_energy", e3_energy(net)},
          {"discrete_twist_energy", discrete_twist_energy(net)},
          {"discrete_dirichlet_energy", discrete_dirichlet_energy(net)}};
}

double max_difference(const ControlNet& a, const ControlNet& b) { return (a.points - b.points).cwiseAbs().maxCoeff(); }

json point_json(const Eigen::RowVector3d& p) {
  return json::array({number_or_null(p(0)), number_or_null(p(1)), number_or_null(p(2))});
}

double finite_max(const Eigen::VectorXd& x, bool absolute) {
  double m = 0;
  for (Eigen::Index k = 0; k < x.size(); ++k)
    if (std::isfinite(x(k))) m = std::max(m, absolute ? std::abs(x(k)) : x(k));
  return m;
}

// finite_max, or null where no sample has a value (every one singular: a maximum of 0 read as a
// flat surface, for a cylinder whose derivatives could not be taken)
json finite_max_or_null(const Eigen::VectorXd& x, bool absolute) {
  const bool any = std::any_of(x.data(), x.data() + x.size(), [](double v) { return std::isfinite(v); });
  return any ? json(finite_max(x, absolute)) : json(nullptr);
}

}  // namespace

SurfaceFile read_surface_reference(const std::string& path, const SurfaceReadOptions& options) {
  const json doc = read_json_file(path);
  // A B-spline net (a B-spline boundary file's knots, or the "bspline" block of its solve report)
  // is no Bézier net: read as one, its points would be a different surface.
  for (const char* field : {"knots_u", "knots_v", "degree_spline", "bspline"})
    if (doc.is_object() && doc.contains(field))
      throw InputError(path, field,
                       "a B-spline net is not a Bézier net; --reference takes a surface description or a Bézier net "
                       "(\"net\" without knots)");
  if (doc.is_object() && !doc.contains("type") && doc.contains("net"))
    return parse_surface(json{{"type", "bezier"}, {"net", doc["net"]}}, path, options);
  return parse_surface(doc, path, options);
}

std::string net_degree_field(const Surface& s, const FittedNet& fitted) {
  if (s.type() == SurfaceType::kBezier) return "net";
  std::string field = "type";
  int degree = -1;
  for (const auto& [name, curve] : s.curves()) {
    int d = curve->bezier() ? curve->bezier()->degree() : 0;
    for (const CurveFitReport& fit : fitted.fits)
      if (fit.curve == name) d = fit.degree;
    if (d > degree) {
      field = name;
      degree = d;
    }
  }
  return field;
}

SurfaceReport surface_report(const SurfaceFile& input, FittedNet fitted_input,
                             const std::optional<SurfaceFile>& reference, const SurfaceReportOptions& options) {
  const Surface& surface = input.surface;
  const int k = options.samples;
  SurfaceReport out;
  out.samples = sample_grid(surface, k);
  SurfaceSamples& samples = out.samples;
  if (reference) add_reference_distance(samples, reference->surface);
  out.fitted = std::move(fitted_input);
  const FittedNet& fitted = out.fitted;

  nlohmann::ordered_json& report = out.report;  // read top-down: what it is, diagnostics, metrics, then the big arrays
  report["surface"] = input.name;
  report["type"] = to_string(surface.type());
  report["sample"] = k;
  report["polynomial"] = fitted.exact;
  json curves = json::object();
  for (const auto& [field, curve] : surface.curves()) curves[field] = curve->kind();
  if (!curves.empty()) report["curves"] = curves;
  nlohmann::ordered_json& points = out.points;
  points = nlohmann::ordered_json::array();
  for (int a = 0; a < k; ++a) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (int b = 0; b < k; ++b) row.push_back(nlohmann::ordered_json(point_json(samples.points.row(a * k + b))));
    points.push_back(std::move(row));
  }

  // The net: exact, or over fitted curves with the deviations.
  const ControlNet& net = fitted.net;
  nlohmann::ordered_json& net_block = out.net_block;
  net_block = {{"degree", {net.m, net.n}}, {"exact", fitted.exact}};
  if (!fitted.exact) {
    net_block["fit_degree"] = fitted.fit_degree;
    json fits = json::array();
    for (const auto& f : fitted.fits)
      fits.push_back({{"curve", f.curve},
                      {"degree", f.degree},
                      {"fitted_degree", f.fitted_degree},
                      {"max_deviation", number_or_null(f.max_deviation)}});
    net_block["max_curve_deviation"] = number_or_null(fitted.max_curve_deviation);
    net_block["curve_fits"] = fits;
    // On a grid of at least kDeviationGrid² parameters, not only the --samples grid (2 × 2 saw the
    // corners only and said 0), and never below the deviation on the sides, which are part of
    // the surface: the true maximum over the patch is at least both. Not the fits of the cross
    // derivatives of a general Coons patch, which are tangents, not points: they made the pillow's
    // 0.00092 read 0.0028.
    const int g = std::max(k, kDeviationGrid);
    const SurfaceSamples dense = g == k ? SurfaceSamples() : sample_grid(surface, g);
    const Eigen::MatrixX3d& P = g == k ? samples.points : dense.points;
    const Eigen::MatrixX3d S = sample_surface(net, g, g);
    double worst = 0;
    for (const auto& f : fitted.fits)
      if (f.on_surface && std::isfinite(f.max_deviation)) worst = std::max(worst, f.max_deviation);
    for (int row = 0; row < g * g; ++row) worst = std::max(worst, (S.row(row) - P.row(row)).norm());
    net_block["max_surface_deviation"] = number_or_null(worst);
  }
  net_block["net"] = net_to_json(net);

  json metrics = energies_json(net);
  metrics["of"] = fitted.exact ? "the exact Bezier net" : "the net over the Bezier fits";
  report["metrics"] = metrics;

  // The closed-form discrete nets of the same boundary, in the same space.
  json discrete;
  const Boundary boundary = boundary_of(net, input.name);
  const ControlNet coons = discrete_coons_net(boundary);
  discrete["coons"] = {{"max_difference", max_difference(net, coons)}, {"energies", energies_json(coons)}};
  if (net.m >= 3 && net.n >= 3) {
    const ControlNet hermite = hermite_coons_net(boundary);
    discrete["hermite_coons"] = {{"max_difference", max_difference(net, hermite)},
                                 {"energies", energies_json(hermite)}};
  }
  report["discrete_nets"] = discrete;

  json twists = json::array();
  for (auto [u, v] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
    twists.push_back(point_json(surface.evaluate(u, v).duv));
  report["corner_twists"] = twists;
  const auto singular =
      std::count_if(samples.mean_curvature.data(), samples.mean_curvature.data() + samples.mean_curvature.size(),
                    [](double v) { return !std::isfinite(v); });
  report["sampled"] = {{"max_abs_mean_curvature", finite_max_or_null(samples.mean_curvature, true)},
                       {"max_abs_gaussian_curvature", finite_max_or_null(samples.gaussian_curvature, true)},
                       {"max_twist", finite_max_or_null(samples.twist, false)},
                       {"singular_samples", singular}};

  if (!input.conditions.empty()) {
    json conditions = json::array();
    double worst_position = 0, worst_derivative = 0;
    for (const auto& c : input.conditions) {
      conditions.push_back(
          {{"field", c.field}, {"corner", c.corner}, {"condition", c.condition}, {"gap", number_or_null(c.gap)}});
      double& worst = c.order == 0 ? worst_position : worst_derivative;
      worst = std::max(worst, c.gap);
    }
    report["compatibility"] = {{"size", input.size},
                               {"corner_tolerance", options.corner_tolerance},
                               {"derivative_tolerance", options.derivative_tolerance},
                               {"max_corner_gap", worst_position},
                               {"max_derivative_gap", worst_derivative},
                               {"conditions", std::move(conditions)}};
  }
  if (reference) {
    const Eigen::VectorXd& d = *samples.distance;
    report["reference"] = {{"file", options.reference_file},
                           {"type", to_string(reference->surface.type())},
                           {"max_distance", finite_max(d, false)},
                           {"rms_distance", std::sqrt(d.squaredNorm() / double(d.size()))},
                           {"max_parametric_distance", finite_max(*samples.parametric_distance, false)}};
  }
  return out;
}

}  // namespace coons
