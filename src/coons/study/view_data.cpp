#include "view_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/family_search.h"
#include "coons/alpha/objective.h"
#include "coons/curves/bspline_curve.h"
#include "coons/mask/nonuniform_mask.h"
#include "coons/mask/solve_stencil_net.h"
#include "coons/mask/stencil_system.h"
#include "coons/metrics/energies.h"
#include "coons/study/bspline_net.h"
#include "coons/study/bspline_search.h"
#include "coons/study/sweep.h"
#include "coons/study/tri_search.h"
#include "coons/surfaces/bspline_sampling.h"
#include "coons/surfaces/sampling.h"
#include "coons/surfaces/surface.h"
#include "coons/tri/tri_energy.h"
#include "coons/tri/tri_mask.h"
#include "coons/tri/tri_sampling.h"
#include "coons/tri/tri_solve.h"

namespace coons {

namespace {

// The energies a curve can show, by objective name: their field of NetMetrics (what a sweep row
// holds) and the function that computes one alone (for a single net).
struct CurveEnergy {
  const char* name;
  double NetMetrics::*field;
  double (*of)(const ControlNet&);
};
constexpr CurveEnergy kCurveEnergies[] = {
    {"thin_plate", &NetMetrics::thin_plate_energy, thin_plate_energy},
    {"e3", &NetMetrics::e3_energy, e3_energy},
    {"dirichlet", &NetMetrics::dirichlet_energy, dirichlet_energy},
    {"twist", &NetMetrics::twist_energy, twist_energy},
    {"discrete_twist", &NetMetrics::discrete_twist_energy, discrete_twist_energy},
    {"discrete_dirichlet", &NetMetrics::discrete_dirichlet_energy, discrete_dirichlet_energy},
};

const CurveEnergy* curve_energy(const std::string& name) {
  for (const CurveEnergy& e : kCurveEnergies)
    if (name == e.name) return &e;
  return nullptr;
}

// NaN for a name that is no curve's.
double metric_of(const NetMetrics& m, const std::string& name) {
  const CurveEnergy* e = curve_energy(name);
  return e ? m.*(e->field) : NAN;
}

double energy_of(const ControlNet& net, const std::string& name) {
  const CurveEnergy* e = curve_energy(name);
  return e ? e->of(net) : NAN;
}

// The grid of a slider with the optima (and the marks) added, increasing, without repeats.
std::vector<double> slider_values(double lower, double upper, int count, const std::vector<ViewCurve>& curves,
                                  const std::vector<double>& marks) {
  // The optima are frames exactly, then the marks, then the grid: a value within rounding of one
  // already taken gives way to it (the twist optimum of a cubic triangle is 0 up to 1e-16, next to
  // the mark and grid value 0).
  std::vector<double> values;
  const auto add = [&values](double x) {
    if (std::none_of(values.begin(), values.end(),
                     [x](double v) { return std::abs(x - v) <= 1e-12 * (1 + std::abs(v)); }))
      values.push_back(x);
  };
  for (const ViewCurve& c : curves)
    if (c.optimum) add(*c.optimum);
  for (double mark : marks)
    if (mark >= lower && mark <= upper) add(mark);
  for (double g : linspace(lower, upper, count)) add(g);
  std::sort(values.begin(), values.end());
  return values;
}

// One energy curve per objective name with the optimum and status of `search` (name ↦ the search's
// summary, or nothing where the objective does not apply: not_applicable); the values come later.
std::vector<ViewCurve> searched_curves(
    const std::vector<std::string>& names,
    const std::function<std::optional<AlphaSearchSummary>(const std::string& name)>& search) {
  std::vector<ViewCurve> curves;
  for (const std::string& name : names) {
    ViewCurve c;
    c.name = name;
    const std::optional<AlphaSearchSummary> found = search(name);
    c.status = found ? to_string(found->status) : "not_applicable";
    if (found && found->status == SearchStatus::kSuccess) c.optimum = found->parameter;
    curves.push_back(c);
  }
  return curves;
}

}  // namespace

ViewOptionsProblem options_problem(const ViewOptions& o) {
  using F = ViewOptionsField;
  if (o.frames < 2 || o.frames > 2001)
    return {F::kFrames, fmt::format("the number of frames must be in [2, 2001], not {}", o.frames)};
  if (o.samples < 2 || o.samples > 257) return {F::kSamples, fmt::format("must be in [2, 257], not {}", o.samples)};
  if (!(std::isfinite(o.lower) && std::isfinite(o.upper) && o.lower < o.upper && o.lower >= -0.25 && o.upper <= 0.25))
    return {F::kInterval, "the interval must lie in [-0.25, 0.25] with lower < upper"};
  // frames closer than slider_values' rounding tolerance merge: [0, 1e-300] in 5 gave one frame
  const double step = (o.upper - o.lower) / (o.frames - 1),
               merged = 2e-12 * (1 + std::max(std::abs(o.lower), std::abs(o.upper)));
  if (!(step > merged))
    return {F::kInterval,
            fmt::format("the interval [{}, {}] is too narrow for {} distinct frames (their spacing must exceed {})",
                        o.lower, o.upper, o.frames, merged)};
  for (const std::string& name : o.objectives)
    if (!curve_energy(name)) return {F::kObjectives, fmt::format("no energy curve for '{}'", name)};
  return {};
}

bool ViewOptions::is_valid(std::string* why) const {
  ViewOptionsProblem problem = options_problem(*this);
  if (why) *why = std::move(problem.reason);
  return problem.field == ViewOptionsField::kNone;
}

void open_at_thin_plate_optimum(ViewSlider& slider) {
  for (const ViewCurve& c : slider.curves)
    if (c.name == "thin_plate" && c.optimum) slider.initial = *c.optimum;
}

void sample_view_frame(const ControlNet& net, int samples, ViewFrame& frame) {
  const SurfaceSamples s = sample_grid(make_bezier_surface(net), samples);
  frame.net = net.points;
  frame.points = s.points;
  frame.normals = s.normals;
}

namespace {

// An α slider over [options.lower, options.upper] labelled `label`, opening at `initial`, with
// the faces of options.samples² surface samples; its frames, curves and marks come later.
ViewSlider alpha_slider(const ViewOptions& options, const char* label, double initial) {
  ViewSlider slider;
  slider.parameter = "alpha";
  slider.symbol = "α";
  slider.label = label;
  slider.lower = options.lower;
  slider.upper = options.upper;
  slider.initial = initial;
  slider.faces = grid_faces(options.samples);
  return slider;
}

// The marks α = −1/4 (the Coons net) and α = 0 (the Laplace net) that lie in the slider's range.
void add_alpha_marks(ViewSlider& slider) {
  for (const auto& [name, alpha] : {std::pair<const char*, double>{"Coons", -0.25}, {"Laplace", 0.0}})
    if (alpha >= slider.lower && alpha <= slider.upper) slider.marks.push_back({name, alpha});
}

}  // namespace

ViewSlider alpha_view_slider(const Boundary& boundary, const ViewOptions& options, const solvers::SolverInfo& solver,
                             double initial) {
  ViewSlider slider = alpha_slider(options, "α (the 3×3 mask family)", initial);
  slider.net_edges = grid_edges(boundary.m + 1, boundary.n + 1);

  // the optima first: their α are frames too, so that the page shows each exactly
  AlphaSearchOptions search;
  search.lower = options.lower;
  search.upper = options.upper;
  std::vector<ViewCurve> curves =
      searched_curves(options.objectives, [&](const std::string& name) -> std::optional<AlphaSearchSummary> {
        const std::optional<Objective> objective = parse_objective(name, nullptr);
        if (!objective) return std::nullopt;
        // (a net without an interior point is flat, as search-alpha says; the page said not_applicable)
        return search_alpha(boundary, *objective, solver, search);
      });
  const std::vector<double> values =
      slider_values(options.lower, options.upper, options.frames, curves, {-0.25, 0.0, initial});

  std::vector<ControlNet> nets;
  const std::vector<SweepRow> rows =
      run_sweep(boundary, values, sweep_family(SweepParameter::kAlpha, boundary), solver, std::nullopt, {}, &nets);
  for (size_t k = 0; k < rows.size(); ++k) {
    ViewFrame f;
    f.parameter = rows[k].parameter;
    f.ok = rows[k].summary.ok() || boundary.m < 2 || boundary.n < 2;
    f.mu = mu_of_alpha(boundary, f.parameter);
    sample_view_frame(nets[k], options.samples, f);
    slider.frames.push_back(std::move(f));
  }
  for (ViewCurve& c : curves) {
    for (const SweepRow& row : rows) c.values.push_back(row.summary.ok() ? metric_of(row.metrics, c.name) : NAN);
    slider.curves.push_back(std::move(c));
  }
  add_alpha_marks(slider);
  if (boundary.m >= 2 && boundary.n >= 2) {  // the page solves any α of the interval itself
    slider.ring = frame_net(boundary).points;
    slider.ring_m = boundary.m;
    slider.ring_n = boundary.n;
  }
  return slider;
}

ViewSlider bspline_view_slider(const BSplineBoundary& compatible, const ViewOptions& options,
                               const std::string& solver_name, double initial) {
  ViewSlider slider = alpha_slider(options, "α (the non-uniform mask family of the B-spline net)", initial);

  AlphaSearchOptions search = default_bspline_search_options();
  search.lower = options.lower;
  search.upper = options.upper;
  std::vector<ViewCurve> curves =
      searched_curves(options.objectives, [&](const std::string& name) -> std::optional<AlphaSearchSummary> {
        const std::optional<Objective> objective = parse_objective(name, nullptr);
        if (!objective || !bspline_objective_supported(*objective, nullptr)) return std::nullopt;
        return search_bspline_alpha(compatible, *objective, solver_name, search);
      });
  const std::vector<double> values =
      slider_values(options.lower, options.upper, options.frames, curves, {-0.25, 0.0, initial});
  const auto backend = solvers::make_solver(solver_name);
  for (const double alpha : values) {
    const BSplineNetOutcome outcome = make_bspline_net(compatible, NetMethod::kAlpha, alpha, backend.get());
    ViewFrame f;
    f.parameter = alpha;
    f.ok = !outcome.summary || outcome.summary->ok();
    const BSplineSurface& surface = outcome.surface;
    if (slider.net_edges.empty()) slider.net_edges = grid_edges(surface.net.m + 1, surface.net.n + 1);
    f.net = surface.net.points;
    const SurfaceSamples samples = sample_bspline_grid(surface, options.samples);
    f.points = samples.points;
    f.normals = samples.normals;
    const NetMetrics metrics = bspline_metrics(outcome.local, alpha);
    for (ViewCurve& c : curves) c.values.push_back(f.ok ? metric_of(metrics, c.name) : NAN);
    slider.frames.push_back(std::move(f));
  }
  slider.curves = std::move(curves);
  add_alpha_marks(slider);
  slider.system = bspline_view_system(compatible, options.samples);
  return slider;
}

ViewSlider weight_view_slider(const StencilProblem& problem, const ViewOptions& options,
                              const solvers::SolverInfo& solver, double initial) {
  ViewSlider slider;
  slider.parameter = "weight";
  slider.symbol = "w";
  slider.label = "w (the C1 family on the ribbons: 0 biharmonic, 1 C1 Coons)";
  slider.lower = 0;
  slider.upper = 1;
  slider.initial = initial;
  slider.net_edges = grid_edges(problem.net.m + 1, problem.net.n + 1);
  slider.faces = grid_faces(options.samples);
  std::vector<ViewCurve> curves =
      searched_curves(options.objectives, [&](const std::string& name) -> std::optional<AlphaSearchSummary> {
        const std::optional<Objective> objective = parse_objective(name, nullptr);
        if (!objective) return std::nullopt;
        return search_weight(problem, *objective, solver);
      });
  const std::vector<double> values = slider_values(0, 1, options.frames, curves, {0.0, 1.0, initial});
  std::vector<Stencil> members;
  members.reserve(values.size());
  for (double w : values) members.push_back(c1_family_stencil(w));
  auto backend = solvers::make_solver(solver.name);
  solve_stencil_sweep(problem, members, *backend, [&](size_t k, const StencilSolveResult& result) {
    ViewFrame f;
    f.parameter = values[k];
    f.ok = result.summary.ok();
    sample_view_frame(result.net, options.samples, f);
    for (ViewCurve& c : curves) c.values.push_back(f.ok ? energy_of(result.net, c.name) : NAN);
    slider.frames.push_back(std::move(f));
  });
  slider.curves = std::move(curves);
  slider.marks = {{"biharmonic", 0.0}, {"C1 Coons", 1.0}};
  slider.system = weight_view_system(problem, options.samples);
  return slider;
}

std::optional<ViewSystem> tri_view_system(const tri::TriNet& frame, int samples) {
  const int n = frame.n;
  const Eigen::Index free = tri::interior_size(n);
  if (free == 0 || free > ViewSystem::kMaxFree) return std::nullopt;
  const tri::TriMaskSystem at0 = tri::assemble_tri_mask_system(frame, tri::TriMask{0.0});
  const tri::TriMaskSystem at1 = tri::assemble_tri_mask_system(frame, tri::TriMask{1.0});
  ViewSystem v;
  v.sampler = ViewSystem::Sampler::kTriangle;
  v.n = n;
  v.samples = samples;
  v.free.resize(free);
  for (int k = 1; k <= n - 2; ++k)
    for (int j = 1; j + k <= n - 1; ++j) v.free[tri::interior_index(n, j, k)] = int(tri::net_index(n, j, k));
  v.A0 = at0.A;
  v.A1 = at1.A - at0.A;
  v.B0 = at0.B;
  v.B1 = at1.B - at0.B;
  v.net = frame.points;
  return v;
}

namespace {

// The basis functions of one direction of `surface` and their derivatives d/ds at the k samples
// s = a/(k − 1) of its domain, as bspline_surface_point evaluates them.
void sample_basis(const Eigen::VectorXd& knots, int degree, int samples, Eigen::MatrixXd& basis,
                  Eigen::MatrixXd& derivative) {
  const auto count = Eigen::Index(knots.size()) - degree - 1;
  const double u0 = knots(0), u1 = knots(knots.size() - 1);
  basis = Eigen::MatrixXd::Zero(samples, count);
  derivative = Eigen::MatrixXd::Zero(samples, count);
  for (int a = 0; a < samples; ++a) {
    const double u = u0 + double(a) / (samples - 1) * (u1 - u0);
    const int span = find_span(knots, degree, u);
    const Eigen::MatrixXd d = basis_derivatives(knots, degree, span, u, 1);
    for (int r = 0; r <= degree; ++r) {
      basis(a, span - degree + r) = d(0, r);
      derivative(a, span - degree + r) = (u1 - u0) * d(1, r);
    }
  }
}

}  // namespace

std::optional<ViewSystem> bspline_view_system(const BSplineBoundary& compatible, int samples) {
  const ControlNet frame = bspline_frame(compatible);
  const Eigen::Index free = Eigen::Index(std::max(frame.m - 1, 0)) * std::max(frame.n - 1, 0);
  if (free == 0 || free > ViewSystem::kMaxFree) return std::nullopt;
  const NonUniformMaskSystem system = assemble_nonuniform_mask_system(frame, greville_grid(compatible), 0.0);
  ViewSystem v;
  v.sampler = ViewSystem::Sampler::kTensor;
  v.m = frame.m;
  v.n = frame.n;
  v.samples = samples;
  for (int i = 1; i < frame.m; ++i)  // the unknowns of the assembly: (i − 1)(n − 1) + (j − 1)
    for (int j = 1; j < frame.n; ++j) v.free.push_back(int(frame.index(i, j)));
  v.A0 = system.A;
  v.A1 = system.dA;
  v.B0 = system.B;
  v.B1 = system.dB;
  v.net = frame.points;
  const BSplineSurface surface = bspline_surface_on(compatible, frame);  // the frames' knots and degrees
  sample_basis(surface.knots_u, surface.degree_u, samples, v.basis_u, v.dbasis_u);
  sample_basis(surface.knots_v, surface.degree_v, samples, v.basis_v, v.dbasis_v);
  return v;
}

std::optional<ViewSystem> weight_view_system(const StencilProblem& problem, int samples) {
  // the centres of T (biharmonic, w = 0) and C (c1-coons, w = 1): W_w·(20 + 16w) is affine in w
  constexpr double kCentreT = 20, kCentreC = 36;
  const StencilSystem at0 = assemble_stencil_system(problem, c1_family_stencil(0));
  const StencilSystem at1 = assemble_stencil_system(problem, c1_family_stencil(1));
  const int free = at0.numbering.size();
  if (free == 0 || free > ViewSystem::kMaxFree) return std::nullopt;
  ViewSystem v;
  v.sampler = ViewSystem::Sampler::kBezier;
  v.m = problem.net.m;
  v.n = problem.net.n;
  v.samples = samples;
  for (const auto& [i, j] : at0.numbering.points) v.free.push_back(int(problem.net.index(i, j)));
  v.A0 = kCentreT * at0.A;
  v.A1 = kCentreC * at1.A - kCentreT * at0.A;
  v.B0 = kCentreT * at0.B;
  v.B1 = kCentreC * at1.B - kCentreT * at0.B;
  v.net = problem.net.points;
  return v;
}

std::vector<std::array<int, 2>> tri_net_edges(int n) {
  std::vector<std::array<int, 2>> edges;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j + k <= n; ++j) {
      const int p = int(tri::net_index(n, j, k));
      if (j + k + 1 <= n) edges.push_back({p, int(tri::net_index(n, j + 1, k))});
      if (j + k + 1 <= n) edges.push_back({p, int(tri::net_index(n, j, k + 1))});
      if (j >= 1 && k + 1 <= n) edges.push_back({p, int(tri::net_index(n, j - 1, k + 1))});
    }
  return edges;
}

ViewSlider tri_view_slider(const tri::TriBoundary& boundary, const ViewOptions& options,
                           const solvers::SolverInfo& solver, double initial) {
  const tri::TriNet frame = tri::frame_net(boundary);
  ViewSlider slider;
  slider.parameter = "alpha";
  slider.symbol = "c";
  slider.label = "c (the triangular mask family)";
  std::tie(slider.lower, slider.upper) = default_tri_bounds(frame.n);
  if (options.lower < options.upper) std::tie(slider.lower, slider.upper) = std::pair(options.lower, options.upper);
  slider.initial = initial;
  slider.net_edges = tri_net_edges(frame.n);
  for (const auto& t : tri::tri_grid_triangles(options.samples)) slider.faces.push_back(t);
  AlphaSearchOptions search;
  search.lower = slider.lower;
  search.upper = slider.upper;
  std::vector<ViewCurve> curves = searched_curves(
      {"thin_plate", "e3", "dirichlet", "twist"}, [&](const std::string& name) -> std::optional<AlphaSearchSummary> {
        const std::optional<TriObjective> objective = parse_tri_objective(name, nullptr);
        if (!objective) return std::nullopt;
        // (below degree 3 there is no interior point: the search says flat, as search-alpha does;
        // the page said not_applicable)
        return search_tri_c(frame, *objective, solver, search);
      });
  const std::vector<double> values =
      slider_values(slider.lower, slider.upper, options.frames, curves, {-1.0 / 6.0, 0.0, initial});
  for (double c : values) {
    tri::TriSolveOptions solve;
    solve.mask = tri::TriMask{c};
    solve.solver = &solver;
    const tri::TriSolveResult result = tri::solve_tri_net(frame, solve);
    ViewFrame f;
    f.parameter = c;
    f.ok = result.summary.ok() || frame.n < 3;
    const tri::TriSurfaceSamples samples = tri::sample_tri_surface(result.net, options.samples);
    f.net = result.net.points;
    f.points = samples.points;
    f.normals = samples.normals;
    curves[0].values.push_back(f.ok ? tri::tri_thin_plate_energy(result.net) : NAN);
    curves[1].values.push_back(f.ok ? tri::tri_e3_energy(result.net) : NAN);
    curves[2].values.push_back(f.ok ? tri::tri_dirichlet_energy(result.net) : NAN);
    curves[3].values.push_back(f.ok ? tri::tri_twist_energy(result.net) : NAN);
    slider.frames.push_back(std::move(f));
  }
  slider.curves = std::move(curves);
  for (const auto& [name, c] : {std::pair<const char*, double>{"quadratic precision", -1.0 / 6.0}, {"Laplace", 0.0}})
    if (c >= slider.lower && c <= slider.upper) slider.marks.push_back({name, c});
  slider.system = tri_view_system(frame, options.samples);
  return slider;
}

}  // namespace coons
