#include "view_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/study/sweep.h"
#include "coons/surfaces/sampling.h"
#include "coons/surfaces/surface.h"

namespace coons {

namespace {

double metric_of(const NetMetrics& m, const std::string& name) {
  if (name == "thin_plate") return m.thin_plate_energy;
  if (name == "e3") return m.e3_energy;
  if (name == "dirichlet") return m.dirichlet_energy;
  if (name == "twist") return m.twist_energy;
  if (name == "discrete_twist") return m.discrete_twist_energy;
  if (name == "discrete_dirichlet") return m.discrete_dirichlet_energy;
  return NAN;
}

}  // namespace

bool ViewOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (frames < 2 || frames > 2001) return fail(fmt::format("frames must be in [2, 2001], not {}", frames));
  if (samples < 2 || samples > 257) return fail(fmt::format("samples must be in [2, 257], not {}", samples));
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower < upper && lower >= -0.25 && upper <= 0.25))
    return fail("the interval must lie in [-0.25, 0.25] with lower < upper");
  for (const std::string& name : objectives)
    if (std::isnan(metric_of(NetMetrics{}, name))) return fail(fmt::format("no energy curve for '{}'", name));
  return true;
}

void sample_view_frame(const ControlNet& net, int samples, ViewFrame& frame) {
  const SurfaceSamples s = sample_grid(make_bezier_surface(net), samples);
  frame.net = net.points;
  frame.points = s.points;
  frame.normals = s.normals;
}

ViewSlider alpha_view_slider(const Boundary& boundary, const ViewOptions& options, const solvers::SolverInfo& solver,
                             double initial) {
  ViewSlider slider;
  slider.parameter = "alpha";
  slider.label = "α (the 3×3 mask family)";
  slider.lower = options.lower;
  slider.upper = options.upper;
  slider.initial = initial;
  slider.net_edges = grid_edges(boundary.m + 1, boundary.n + 1);
  slider.faces = grid_faces(options.samples);

  // the optima first: their α are frames too, so that the page shows each exactly
  std::vector<ViewCurve> curves;
  for (const std::string& name : options.objectives) {
    ViewCurve c;
    c.name = name;
    std::string why;
    const std::optional<Objective> objective = parse_objective(name, &why);
    if (objective && boundary.m >= 2 && boundary.n >= 2) {
      AlphaSearchOptions search;
      search.lower = options.lower;
      search.upper = options.upper;
      const AlphaSearchSummary found = search_alpha(boundary, *objective, solver, search);
      c.status = to_string(found.status);
      if (found.status == SearchStatus::kSuccess) c.optimum = found.parameter;
    } else {
      c.status = "not_applicable";
    }
    curves.push_back(c);
  }
  std::vector<double> values = linspace(options.lower, options.upper, options.frames);
  for (const ViewCurve& c : curves)
    if (c.optimum) values.push_back(*c.optimum);
  for (double mark : {-0.25, 0.0})
    if (mark >= options.lower && mark <= options.upper) values.push_back(mark);
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end(),
                           [](double a, double b) { return std::abs(a - b) <= 1e-12 * (1 + std::abs(a)); }),
               values.end());

  std::vector<ControlNet> nets;
  const std::vector<SweepRow> rows =
      run_sweep(boundary, values, sweep_family(SweepParameter::kAlpha, boundary), solver, std::nullopt, {}, &nets);
  for (size_t k = 0; k < rows.size(); ++k) {
    ViewFrame f;
    f.parameter = rows[k].parameter;
    f.ok = rows[k].summary.ok() || boundary.m < 2 || boundary.n < 2;
    sample_view_frame(nets[k], options.samples, f);
    slider.frames.push_back(std::move(f));
  }
  for (ViewCurve& c : curves) {
    for (const SweepRow& row : rows) c.values.push_back(row.summary.ok() ? metric_of(row.metrics, c.name) : NAN);
    slider.curves.push_back(std::move(c));
  }
  for (const auto& [name, alpha] : {std::pair<const char*, double>{"Coons", -0.25}, {"Laplace", 0.0}})
    if (alpha >= options.lower && alpha <= options.upper) slider.marks.push_back({name, alpha});
  return slider;
}

}  // namespace coons
