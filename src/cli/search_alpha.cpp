// `coons search-alpha BOUNDARY --objective NAME`: the best mask parameter of one boundary for an
// objective (Ceres, analytic derivative); one JSON report (docs/formats.md).
#include <fmt/format.h>

#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/family_search.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/stencil_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/mask/mask9.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/study/backend_choice.h"
#include "coons/study/bspline_net.h"
#include "coons/study/bspline_search.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/search_report.h"
#include "coons/study/two_ring_problem.h"
#include "net_request.h"
#include "registry.h"
#include "search_inputs.h"
#include "tri_commands.h"

namespace coons::cli {

namespace {

using Parameter = SearchParameter;

struct SearchRequest {
  std::string boundary;
  std::string objective;
  Parameter parameter = Parameter::kAlpha;
  std::optional<double> lower, upper;
  bool allow_indefinite = false;
  std::string target;
  int scan_points = 9;
  int samples = 41;
  std::string solver = "auto";
  double corner_tolerance = 1e-9;
  GlobalOptions global;
  CLI::Option *target_option = nullptr, *samples_option = nullptr;
};

struct SearchSetup {
  Objective objective;
  MaskFamily family;
  AlphaSearchOptions options;
  const solvers::SolverInfo* solver = nullptr;
  bool picked_automatically = false;
  //! μ's bounds as given (options holds them on the compressed scale, which does not read back
  //! to the last digit: 9000 came back as 9000.000000000306)
  std::optional<MuScale> mu_scale;
};

SearchSetup setup_search(const SearchRequest& r, const Boundary& b) {
  SearchSetup s;
  std::string why;
  auto objective = parse_objective(objective_text(r.objective), &why);
  if (!objective) throw InputError("command line", "--objective", why);
  s.objective = *objective;
  if (s.objective.target_weight > 0) {
    // (the samples' memory only where they are taken: a search for e3 was refused naming
    // --samples, which it neither uses nor was given)
    check_target_samples(r.global, r.samples);
    s.objective.target = resolve_target(r.target, r.boundary, b, r.samples);
    if (!s.objective.target)
      throw InputError("command line", "--target",
                       "the objective uses 'target' but neither --target nor the boundary file gives one");
  } else if (r.target_option->count() > 0) {
    throw InputError("command line", "--target",
                     "--target is given but --objective '" + r.objective + "' has no target term");
  } else if (r.samples_option->count() > 0) {
    throw samples_without_target(r.objective);
  }
  bool indefinite = false;
  switch (r.parameter) {
    case Parameter::kAlpha:
      s.family = [](double a) { return alpha_family(a); };
      s.options.lower = r.lower.value_or(-0.25);
      s.options.upper = r.upper.value_or(0.25);
      indefinite = s.options.lower < -0.25 || s.options.upper > 0.25;
      if (indefinite && !r.allow_indefinite)
        throw InputError(
            "command line", r.lower && *r.lower < -0.25 ? "--lower" : "--upper",
            "bounds outside [-0.25, 0.25] make the system indefinite; add --allow-indefinite to search there");
      break;
    case Parameter::kMu: {
      // searched on the compressed scale s = μ/(μ + mn), so the scan spans μ's orders of magnitude
      const int m = b.m, n = b.n;
      s.family = [m, n](double t) { return mu_family_compressed(m, n, t); };
      const double lower = r.lower.value_or(0.0), upper = r.upper.value_or(1000.0 * m * n);
      if (!(lower >= 0 && std::isfinite(upper) && upper > lower))
        throw InputError("command line", "--lower/--upper", "mu bounds need 0 <= lower < upper < infinity");
      // μ = mn·s/(1 − s) loses ε·(μ + mn)/mn of μ: --upper 1e19 came back as null, 1e12 as
      // 999997450094.85. Up to 1e9·mn it keeps 2e-7, and α(μ) is within 1e-9 of its μ → ∞ limit.
      if (const double most = 1e9 * m * n; upper > most)
        throw InputError("command line", "--upper",
                         fmt::format("mu up to 1e9 * m * n = {:g}: beyond it mu/(mu + mn) cannot resolve mu (and the "
                                     "family is within 1e-9 of its mu -> infinity limit, alpha = 0)",
                                     most));
      s.mu_scale = MuScale{m, n, lower, upper};
      s.options.lower = s.mu_scale->s_lower();
      s.options.upper = s.mu_scale->s_upper();
      // (the check of the search's options would name the compressed values)
      if (!(s.options.lower < s.options.upper))
        throw InputError("command line", "--lower/--upper",
                         fmt::format("mu bounds {} and {} are too close together for the search's scale "
                                     "mu/(mu + mn) to tell apart",
                                     lower, upper));
      break;
    }
    case Parameter::kAlphaGamma:
      s.family = [](double a) { return alpha_family(a); };
      s.options.lower = r.lower.value_or(-0.25);
      s.options.upper = r.upper.value_or(0.25);
      if (s.options.lower < -0.25 || s.options.upper > 0.25)
        throw InputError("command line", "--lower/--upper", "the (alpha, gamma) search stays in [-0.25, 0.25]");
      break;
    case Parameter::kWeight:  // the C1 family, a 5×5 stencil: searched by search_weight, no 3×3 family
      s.options.lower = r.lower.value_or(0.0);
      s.options.upper = r.upper.value_or(1.0);
      if (!(s.options.lower >= 0 && s.options.upper <= 1))
        throw InputError("command line", "--lower/--upper", "the C1 family's weight is searched in [0, 1]");
      break;
  }
  if (r.allow_indefinite && r.parameter != Parameter::kAlpha)
    throw InputError("command line", "--allow-indefinite",
                     std::string("--allow-indefinite applies to --parameter alpha, not ") + to_string(r.parameter));
  s.options.scan_points = r.scan_points;
  require_valid_search_options(s.options);
  const solvers::SolverInfo* requested = solver_from_name(r.solver);
  if (r.parameter == Parameter::kWeight) {
    require_weight_search_backend(requested);
    s.solver = &weight_search_backend(requested);
  } else {
    require_search_backend(requested, b, indefinite);
    s.solver = &search_backend(requested, b, indefinite);
  }
  s.picked_automatically = requested == nullptr;
  return s;
}

// The two data rings the C1 family needs, from the file: bad input when it has one ring, or when
// the 5×5 stencil does not fit its free points.
StencilProblem weight_problem(const std::string& path, const BoundaryFile& file) {
  TwoRingProblem two = two_ring_problem(file);
  if (!two.problem) throw InputError(path, two.field, two.reason);
  require_valid_problem(*two.problem, c1_family_stencil(0.5), path);
  return std::move(*two.problem);
}

TriSearchArgs tri_search_args(const SearchRequest& r) {
  TriSearchArgs a{r.boundary,    r.objective, r.solver,           r.lower,   r.upper,
                  r.scan_points, r.samples,   r.corner_tolerance, &r.global, ""};
  if (r.parameter != Parameter::kAlpha) a.rejected = "--parameter";
  if (r.allow_indefinite) a.rejected = "--allow-indefinite";
  if (r.target_option->count() > 0) a.rejected = "--target";
  a.samples_given = r.samples_option->count() > 0;
  return a;
}

int finish(nlohmann::json report, Phases& phases, SearchStatus status, const SearchRequest& r,
           const std::string& message) {
  report["timing"] = phases.timing();
  print_json(report);
  // no optimum without its evidence: every evaluation failed, or the verdict rests on failures
  if (status != SearchStatus::kSolverFailed && status != SearchStatus::kFailedRegion &&
      status != SearchStatus::kNotApplicable)
    return kExitOk;
  std::cerr << fmt::format("error: {}: solver: {} search failed ({})\n", r.boundary,
                           report["solver"]["name"].get<std::string>(),
                           message.empty() ? "no successful evaluation" : message);
  return kExitSolverFailed;
}

// A B-spline boundary: the non-uniform α family (docs/math.md §10), energies and discrete
// energies as objectives, a backend that takes an assembled matrix.
int run_bspline_search(const SearchRequest& r, const BoundaryFile& file, Phases& phases) {
  if (r.parameter != Parameter::kAlpha)
    throw InputError("command line", "--parameter",
                     "a B-spline boundary is searched over alpha of the non-uniform family only");
  if (r.target_option->count() > 0 || r.samples_option->count() > 0)
    throw InputError("command line", r.target_option->count() > 0 ? "--target" : "--samples",
                     "target objectives compare Bézier nets; a B-spline boundary takes energies only");
  std::string why;
  const auto objective = parse_objective(objective_text(r.objective), &why);
  if (!objective || !bspline_objective_supported(*objective, &why))
    throw InputError("command line", "--objective", why);
  const BSplineInput& in = *file.bspline;
  // [-1/4, U]: U ≤ 1/4, where the non-uniform system stops being definite (1/4 where it does not)
  AlphaSearchOptions options = bspline_search_options(in.compatible);
  const double definite_upper = options.upper;
  options.lower = r.lower.value_or(options.lower);
  options.upper = r.upper.value_or(options.upper);
  options.scan_points = r.scan_points;
  if ((options.lower < -0.25 || options.upper > definite_upper) && !r.allow_indefinite)
    throw InputError("command line", r.lower && *r.lower < -0.25 ? "--lower" : "--upper",
                     fmt::format("the non-uniform system of this B-spline boundary is definite for alpha in [-0.25, "
                                 "{}] only (it can be singular above); add --allow-indefinite to search outside",
                                 definite_upper));
  require_valid_search_options(options);
  const solvers::SolverInfo* requested = require_matrix_backend(solver_from_name(r.solver), kBSplineNeedsMatrix);
  // a Cholesky-type backend wherever the system is definite
  const std::string solver =
      requested ? requested->name
                : solvers::default_matrix_solver(options.lower >= -0.25 && options.upper <= definite_upper).name;
  phases.start("solve");
  AlphaSearchSummary s = search_bspline_alpha(in.compatible, *objective, solver, options);
  if (const std::string note = bspline_pole_note(s, options, definite_upper); !note.empty())
    s.message += (s.message.empty() ? "" : "; ") + note;
  const BSplineSurface frame = bspline_surface_on(in.compatible, bspline_frame(in.compatible));
  Boundary shape = file.boundary;
  shape.m = frame.net.m;
  shape.n = frame.net.n;
  nlohmann::json out = search_report(
      shape, objective_text(r.objective), Parameter::kAlpha, [](double a) { return alpha_family(a); }, options, s);
  out["beta"] = nullptr;  // the non-uniform weights differ from point to point
  out["mu"] = nullptr;
  out.erase("beta_ij");
  out["bspline"] = bspline_block(frame, in);
  out["solver"] = search_solver_block(*solvers::find_solver(solver), requested == nullptr, s.status, s.solves,
                                      s.seconds, s.message);
  return finish(out, phases, s.status, r, s.message);
}

// The α family on a file that is not the one-ring rectangle (two data rings, a free grid): the
// stencil-problem search (family_search.h), every evaluation a factorisation from the matrix.
int run_problem_alpha_search(const SearchRequest& r, const BoundaryFile& file, Phases& phases) {
  const Boundary& b = file.boundary;
  const solvers::SolverInfo* requested = require_matrix_backend(
      solver_from_name(r.solver),
      "the alpha search of a file with two data rings or a free grid needs a backend that works from the matrix");
  SearchSetup setup = setup_search(r, b);
  // outside [−1/4, 1/4] the systems can be indefinite: auto is then a sparse LU, not a Cholesky
  // that would fail at every indefinite α (a named definite-only backend is refused by setup_search)
  const bool indefinite = setup.options.lower < -0.25 || setup.options.upper > 0.25;
  const solvers::SolverInfo& solver =
      requested != nullptr || !indefinite ? weight_search_backend(requested) : solvers::default_matrix_solver(false);
  const StencilProblem problem = stencil_problem(file);
  require_valid_problem(problem, alpha_stencil(alpha_mask(-0.1)), r.boundary);
  check_net_memory(r.global, b, &solver, r.boundary);
  phases.start("solve");
  const AlphaSearchSummary s = search_alpha_on_problem(problem, setup.objective, solver, setup.options);
  nlohmann::json out = search_report(b, objective_text(r.objective), r.parameter, setup.family, setup.options, s);
  out["mu"] = nullptr;  // μ names the one-ring rectangle's anisotropic masks
  out["rings"] = problem.rings;
  out["free_points"] = free_points(problem).count();
  out["solver"] = search_solver_block(solver, requested == nullptr, s.status, s.solves, s.seconds, s.message);
  return finish(out, phases, s.status, r, s.message);
}

int run_search_alpha(const SearchRequest& r) {
  if (is_triangle_file(r.boundary)) return run_tri_search(tri_search_args(r));
  Phases phases("search-alpha");
  phases.start("read");
  const BoundaryFile file = read_input(r.boundary, r.corner_tolerance, true, kMinModelSize);
  if (file.bspline) return run_bspline_search(r, file, phases);
  const Boundary& b = file.boundary;
  if (r.parameter == Parameter::kAlpha && !is_classical(file)) return run_problem_alpha_search(r, file, phases);
  if (r.parameter != Parameter::kWeight)
    require_one_ring(file, r.boundary, "search-alpha --parameter mu or alpha-gamma");
  const SearchSetup setup = setup_search(r, b);
  // the C1 family's weight is searched on the 5×5 stencil's system
  check_net_memory(r.global, b, setup.solver, r.boundary,
                   r.parameter == Parameter::kWeight ? kStencil5Nonzeros : kMask3Nonzeros);
  const std::string objective = objective_text(r.objective);
  if (r.parameter == Parameter::kWeight) {
    const StencilProblem problem = weight_problem(r.boundary, file);
    phases.start("solve");
    WeightSearchOptions options;
    options.search = setup.options;
    const AlphaSearchSummary s = search_weight(problem, setup.objective, *setup.solver, options);
    nlohmann::json out = weight_search_report(b, objective, options.search, s);
    out["solver"] =
        search_solver_block(*setup.solver, setup.picked_automatically, s.status, s.solves, s.seconds, s.message);
    return finish(out, phases, s.status, r, s.message);
  }
  phases.start("solve");
  if (r.parameter == Parameter::kAlphaGamma) {
    MaskObjective f(b, setup.objective, setup.family, *setup.solver);
    const auto started = std::chrono::steady_clock::now();
    const AlphaGammaSummary g = search_alpha_gamma(f, setup.options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    nlohmann::json out = alpha_gamma_report(b, objective, setup.options, g);
    out["solver"] =
        search_solver_block(*setup.solver, setup.picked_automatically, g.status, g.solves, seconds, g.message);
    return finish(out, phases, g.status, r, g.message);
  }
  // The α family is searched in the sine basis when it can be (search_alpha): no solve per evaluation.
  const AlphaSearchSummary s = r.parameter == Parameter::kAlpha
                                   ? search_alpha(b, setup.objective, *setup.solver, setup.options)
                                   : search_mu(b, setup.objective, *setup.solver, setup.options);
  nlohmann::json out = search_report(b, objective, r.parameter, setup.family, setup.options, s, setup.mu_scale);
  out["solver"] =
      search_solver_block(*setup.solver, setup.picked_automatically, s.status, s.solves, s.seconds, s.message);
  return finish(out, phases, s.status, r, s.message);
}

}  // namespace

void register_search_alpha(CLI::App& app, Registry& registry) {
  auto r = std::make_shared<SearchRequest>();
  auto* cmd = app.add_subcommand("search-alpha",
                                 "the best mask parameter of one boundary for an objective "
                                 "(Ceres, analytic derivative); prints one JSON report");
  cmd->add_option("BOUNDARY", r->boundary, "boundary JSON file (docs/formats.md)")->required();
  cmd->add_option("--objective", r->objective,
                  "thin_plate, twist, dirichlet, e3, target, discrete_twist, discrete_dirichlet, discrete_thin_plate, "
                  "or a weighted sum such as \"thin_plate + 10*target\" (spaces allowed)")
      ->required();
  const std::map<std::string, Parameter> parameters = {{"alpha", Parameter::kAlpha},
                                                       {"mu", Parameter::kMu},
                                                       {"alpha-gamma", Parameter::kAlphaGamma},
                                                       {"weight", Parameter::kWeight}};
  cmd->add_option("--parameter", r->parameter,
                  "alpha (the Farin-Hansford family), mu (the anisotropic mask), "
                  "alpha-gamma (every symmetric 3x3 mask) or weight (the 5x5 c1-family; needs two data rings)")
      ->transform(choice_of(parameters))
      ->default_str("alpha");
  cmd->add_option("--lower", r->lower, "lower bound (alpha: -0.25, mu: 0, weight: 0)")->transform(fold_negative_zero());
  cmd->add_option("--upper", r->upper, "upper bound (alpha: 0.25, mu: 1000·m·n, weight: 1)")
      ->transform(fold_negative_zero());
  cmd->add_flag("--allow-indefinite", r->allow_indefinite, "accept alpha bounds outside [-0.25, 0.25]");
  r->target_option = cmd->add_option("--target", r->target,
                                     "hermite-coons | coons | NET.json | sphere:cx,cy,cz,r | "
                                     "cylinder:px,py,pz,dx,dy,dz,r | plane:px,py,pz,nx,ny,nz (default: the boundary "
                                     "file's \"target\")");
  cmd->add_option("--scan", r->scan_points, "points of the coarse scan")->capture_default_str();
  r->samples_option =
      cmd->add_option("--samples", r->samples, "target objective: samples per direction")->capture_default_str();
  cmd->add_option("--corner-tolerance", r->corner_tolerance,
                  "corners must agree to this fraction of the bounding-box diagonal")
      ->capture_default_str();
  add_solver_option(*cmd, r->solver);
  add_memory_option(*cmd, r->global);
  set_example(*cmd, "coons search-alpha data/boundaries/dome.json --objective \"thin_plate + 10*target\"");
  registry.add(cmd, [r] { return run_search_alpha(*r); });
}

}  // namespace coons::cli
