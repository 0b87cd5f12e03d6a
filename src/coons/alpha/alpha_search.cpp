#include "alpha_search.h"

#include <algorithm>
#include <chrono>
#include <type_traits>
#include <utility>
#include <cmath>
#include <optional>
#include <sstream>

#include <ceres/ceres.h>

#include "coons/config.h"
#include "coons/mask/assemble_mask_system.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif
#include "solvers/registry.h"

namespace coons {

MaskObjective::MaskObjective(const Boundary& boundary, Objective objective, MaskFamily family,
                             const solvers::SolverInfo& solver, const solvers::SolverOptions& options)
    : boundary_(boundary), frame_(frame_net(boundary)), objective_(std::move(objective)), family_(std::move(family)) {
  needs_matrix_ = solver.needs_matrix;
  solver_ = solvers::make_solver(solver.name, options);
}

MaskObjective::~MaskObjective() = default;

MaskObjective::Evaluation MaskObjective::evaluate(double p, bool with_derivative) {
  const MaskPoint mp = family_(p);
  std::vector<double> gradient;
  Evaluation e = evaluate_mask(mp.mask, with_derivative ? std::vector<Mask9>{mp.derivative} : std::vector<Mask9>{}, gradient);
  e.parameter = p;
  e.derivative = gradient.empty() ? 0.0 : gradient[0];
  e.has_derivative = with_derivative && e.ok();
  return e;
}

MaskObjective::Evaluation MaskObjective::evaluate_mask(const Mask9& mask, const std::vector<Mask9>& directions,
                                                       std::vector<double>& gradient) {
  ++evaluations_;
  Evaluation e;
  e.net = frame_;
  gradient.assign(directions.size(), 0.0);
  if (!solver_) {
    e.summary.status = solvers::SolveStatus::kNotApplicable;
    e.summary.message = "no such solver";
    return e;
  }
  const int rows = std::max(frame_.m - 1, 0), cols = std::max(frame_.n - 1, 0);
  const ControlNet zero(frame_.m, frame_.n);  // the variation of a net with a fixed boundary
  if (rows * cols == 0) {
    e.value = evaluate_objective(objective_, e.net, zero).value;
    return e;
  }
  solvers::LinearOperator op;
  op.stencil = mask_stencil(mask, rows, cols);
  if (needs_matrix_) {
    if (A_.rows() == 0) A_ = solvers::stencil_matrix(*op.stencil);
    else solvers::refill_stencil_matrix(*op.stencil, A_);
    op.matrix = &A_;
  }
  if (solver_->factorize(op) != solvers::SolveStatus::kSuccess) {
    e.summary = solver_->summary();
    return e;
  }
  Eigen::MatrixX3d X, dX;
  e.summary = solver_->solve(mask_rhs(frame_, mask), X);
  ++solves_;
  if (!e.summary.ok()) return e;
  e.net = fill_interior(frame_, X);
  e.value = evaluate_objective(objective_, e.net, zero).value;
  for (size_t k = 0; k < directions.size(); ++k) {
    const solvers::SolveSummary ds = solver_->solve(mask_sensitivity_rhs(e.net, directions[k]), dX);
    ++solves_;
    if (!ds.ok()) {
      e.summary = ds;
      return e;
    }
    gradient[k] = evaluate_objective(objective_, e.net, fill_interior(zero, dX)).derivative;
  }
  return e;
}

bool AlphaSearchOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower < upper)) return fail("bounds must be finite with lower < upper");
  if (scan_points < 3) return fail("scan_points must be at least 3");
  if (!(flat_tolerance > 0)) return fail("flat_tolerance must be positive");
  if (!(parameter_tolerance > 0)) return fail("parameter_tolerance must be positive");
  if (max_iterations < 1) return fail("max_iterations must be at least 1");
  return true;
}

const char* to_string(SearchStatus s) {
  switch (s) {
    case SearchStatus::kSuccess: return "success";
    case SearchStatus::kFlat: return "flat";
    case SearchStatus::kSolverFailed: return "solver_failed";
    case SearchStatus::kNotConverged: return "not_converged";
  }
  return "solver_failed";
}

std::string AlphaSearchSummary::brief_report() const {
  std::ostringstream out;
  out << to_string(status);
  if (parameter) out << ": optimum " << *parameter << ", value " << value;
  if (flat) out << " (flat objective)";
  if (at_bound) out << " (at a bound)";
  out << ", " << evaluations << " evaluations, " << solves << " solves, " << seconds << " s";
  if (!message.empty()) out << "; " << message;
  return out.str();
}

namespace {

// BFGS line search, silent, stopping on the parameter step (the objective is smooth and cheap
// to differentiate, so the curvature model pays off).
ceres::GradientProblemSolver::Options ceres_options(const AlphaSearchOptions& options) {
  ceres::GradientProblemSolver::Options o;
  o.line_search_direction_type = ceres::BFGS;
  o.max_num_iterations = options.max_iterations;
  o.parameter_tolerance = options.parameter_tolerance;
  o.function_tolerance = 1e-15;
  o.gradient_tolerance = 1e-14;
  o.logging_type = ceres::SILENT;
  return o;
}

// f(p(θ)) with p = centre + half·tanh θ keeps Ceres's unconstrained line search inside the bracket.
// The latest evaluation is kept: Ceres usually ends on it, and the caller needs it again.
template <class Obj>
class BracketedObjective : public ceres::FirstOrderFunction {
 public:
  using Evaluation = typename Obj::Evaluation;
  BracketedObjective(Obj& objective, double centre, double half, bool& failed, std::optional<Evaluation>& last)
      : objective_(objective), centre_(centre), half_(half), failed_(failed), last_(last) {}
  bool Evaluate(const double* theta, double* cost, double* gradient) const override {
    const double t = std::tanh(theta[0]);
    last_ = objective_.evaluate(centre_ + half_ * t);
    const Evaluation& e = *last_;
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    *cost = e.value;
    if (gradient) gradient[0] = e.derivative * half_ * (1 - t * t);
    return true;
  }
  int NumParameters() const override { return 1; }

 private:
  Obj& objective_;
  double centre_, half_;
  bool& failed_;
  std::optional<Evaluation>& last_;
};

}  // namespace

// The search itself, for any objective with evaluate(p, with_derivative), boundary(), objective(),
// evaluations() and solves() (MaskObjective, SpectralAlphaSearchObjective).
namespace {

// Objectives that know f'' (the sine-basis one) are refined by Ceres's bounded trust region on the
// stationarity condition f'(α) = 0 with Jacobian f''(α): Newton steps, a handful of evaluations.
template <class T, class = void>
struct HasSecondDerivative : std::false_type {};
template <class T>
struct HasSecondDerivative<T, std::void_t<decltype(std::declval<typename T::Evaluation>().second_derivative)>>
    : std::true_type {};

// Stops Ceres after an accepted step shorter than an absolute tolerance (Ceres's own
// parameter_tolerance is relative to |p|, which never triggers at an optimum α = 0).
class ShortStep : public ceres::IterationCallback {
 public:
  explicit ShortStep(double tolerance) : tolerance_(tolerance) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    return summary.iteration > 0 && summary.step_is_successful && summary.step_norm <= tolerance_
               ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
               : ceres::SOLVER_CONTINUE;
  }

 private:
  double tolerance_;
};

// The evaluation at p from `seen`, or a new one appended to it.
template <class Obj>
const typename Obj::Evaluation& evaluate_once(Obj& objective, double p, std::vector<typename Obj::Evaluation>& seen) {
  for (const auto& e : seen)
    if (e.parameter == p) return e;
  seen.push_back(objective.evaluate(p));
  return seen.back();
}

template <class Obj>
class Stationarity : public ceres::SizedCostFunction<1, 1> {
 public:
  using Evaluation = typename Obj::Evaluation;
  Stationarity(Obj& objective, double scale, bool& failed, std::vector<Evaluation>& seen)
      : objective_(objective), scale_(scale), failed_(failed), seen_(seen) {}
  bool Evaluate(double const* const* p, double* residual, double** jacobian) const override {
    // Ceres asks for the same point more than once (the trial step, then its Jacobian): reuse it.
    const Evaluation& e = evaluate_once(objective_, p[0][0], seen_);
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    // f' at rounding level is zero: Ceres then stops on a zero cost instead of chasing noise
    residual[0] = std::abs(e.derivative) <= e.derivative_noise ? 0.0 : e.derivative / scale_;
    if (jacobian && jacobian[0]) jacobian[0][0] = e.second_derivative / scale_;
    return true;
  }

 private:
  Obj& objective_;
  double scale_;
  bool& failed_;
  std::vector<Evaluation>& seen_;  // the evaluations of the refinement, shared with the caller
};

template <class Obj>
AlphaSearchSummary search_impl(Obj& objective, const AlphaSearchOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  AlphaSearchSummary s;
  auto finish = [&]() -> AlphaSearchSummary& {
    s.evaluations = objective.evaluations();
    s.solves = objective.solves();
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return s;
  };

  // 1. Coarse scan.
  const int k = options.scan_points;
  const double step = (options.upper - options.lower) / (k - 1);
  std::vector<typename Obj::Evaluation> grid;
  // A point where the solver fails (a singular α outside [−1/4, 1/4]) is a penalty, not an abort:
  // it counts as +∞ and is reported; only a scan where every point fails is a failure.
  int failed_points = 0;
  std::string first_failure;
  for (int i = 0; i < k; ++i) {
    const double p = i + 1 == k ? options.upper : options.lower + i * step;
    grid.push_back(objective.evaluate(p, /*with_derivative=*/false));  // values suffice to scan
    if (!grid.back().ok()) {
      if (failed_points++ == 0) first_failure = "at " + std::to_string(p) + ": " + grid.back().summary.brief_report();
      grid.back().value = HUGE_VAL;
    }
    s.scan.emplace_back(p, grid.back().value);
  }
  if (failed_points == k) {
    s.status = SearchStatus::kSolverFailed;
    s.message = "every scan point failed; " + first_failure;
    return finish();
  }
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  int best = -1;
  for (int i = 0; i < k; ++i) {
    if (!grid[i].ok()) continue;
    lo = std::min(lo, grid[i].value);
    hi = std::max(hi, grid[i].value);
    if (best < 0 || grid[i].value < grid[best].value) best = i;
  }
  for (int i = 1; i + 1 < k; ++i)
    if (grid[i].ok() && grid[i - 1].ok() && grid[i + 1].ok() && grid[i].value < grid[i - 1].value &&
        grid[i].value <= grid[i + 1].value)
      ++s.local_minima;
  if (failed_points > 0)
    s.message = std::to_string(failed_points) + " scan point(s) could not be solved and were skipped (first " +
                first_failure + ")";

  // 2. Flat: the range is at rounding level of the objective's natural scale. Rounding errors of
  //    size ε·diag in the net reach an energy of derivative order k amplified by degree^k, so the
  //    floor is diag²·degree^(2k)·1e-16 (far above (ε·diag·degree^k)², far below real signals).
  const Boundary& boundary = objective.boundary();
  const double diag = bounding_box_diagonal(boundary);
  //    Discrete energies of the net carry no degree factors (order 0).
  int order = 0;
  for (const EnergyTerm& t : objective.objective().energy) order = std::max(order, t.a + t.b);
  const double degree = std::max({boundary.m, boundary.n, 1});
  const bool energies = !objective.objective().energy.empty() || !objective.objective().discrete.empty();
  const double floor = energies ? 1e-16 * diag * diag * std::pow(degree, 2.0 * order) : 1e-8 * diag;
  if (hi - lo <= options.flat_tolerance * std::max({std::abs(hi), std::abs(lo), floor})) {
    s.status = SearchStatus::kFlat;
    s.flat = true;
    s.value = grid[best].value;
    s.message = "the objective does not depend on the parameter over the bounds";
    return finish();
  }
  if (s.local_minima > 1)
    s.message += std::string(s.message.empty() ? "" : "; ") + "the scan saw " + std::to_string(s.local_minima) +
                 " local minima; the lowest was refined";

  // 3. Optimum on a bound: the best grid point is a bound and the slope points outwards.
  auto with_derivative = [&](const typename Obj::Evaluation& e) { return e.has_derivative ? e : objective.evaluate(e.parameter); };
  if (best == 0 || best == k - 1) grid[best] = with_derivative(grid[best]);  // its slope decides
  // (a slope at rounding level, as at a minimum on the bound itself, counts as outwards)
  if ((best == 0 && grid[0].derivative >= -grid[0].derivative_noise) ||
      (best == k - 1 && grid[k - 1].derivative <= grid[k - 1].derivative_noise)) {
    s.parameter = grid[best].parameter;
    s.value = grid[best].value;
    s.at_bound = true;
    return finish();
  }

  // 4. Refine in the bracket of the best point's neighbours with Ceres.
  const int ia = std::max(best - 1, 0), ib = std::min(best + 1, k - 1);
  const double a = grid[ia].parameter, b = grid[ib].parameter;
  const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
  double theta = std::atanh(std::clamp((grid[best].parameter - centre) / half, -0.9, 0.9));
  bool failed = false;
  double p = grid[best].parameter;
  bool no_convergence = false;
  std::string ceres_message;
  bool refined = false;
  std::optional<typename Obj::Evaluation> last;  // the evaluation at the refined p, if made there
  if constexpr (HasSecondDerivative<Obj>::value) {
    // Newton on f' = 0 needs a start where f is convex and a bracket where f' changes sign:
    // shrink the bracket on the sign of f' until it is resolved and its new end is convex, then
    // let Ceres take Newton steps. The family's scale collapses at objective.scale_origin()
    // (α = −1/4, where α* + 1/4 ≈ c/n², docs/math.md §4), so a bracket spanning many scales of the
    // distance d to it is split at the geometric mean of its ends' distances (√(h·d_hi) from the
    // origin itself, h the Newton step there), which halves log(d_hi/d_lo) per evaluation;
    // a resolved bracket (d_hi ≤ 1.5·d_lo) is split at its midpoint.
    auto elo = grid[ia].ok() ? with_derivative(grid[ia]) : objective.evaluate(a);
    auto ehi = grid[ib].ok() ? with_derivative(grid[ib]) : objective.evaluate(b);
    if (elo.ok() && ehi.ok() && elo.derivative < 0 && ehi.derivative > 0) {
      const double origin = objective.scale_origin();
      auto split = [&]() -> std::pair<double, bool> {  // (the point, geometric)
        const double dl = elo.parameter - origin, dh = ehi.parameter - origin;
        if (dl > 0 && dh > 1.5 * dl) return {origin + std::sqrt(dl * dh), true};
        if (dl == 0 && elo.second_derivative > 0) {
          const double h = -elo.derivative / elo.second_derivative;
          if (h > 0 && 4 * h < dh) return {origin + std::sqrt(h * dh), true};
        }
        return {0.5 * (elo.parameter + ehi.parameter), false};
      };
      auto em = elo;
      for (int it = 0; it < 60; ++it) {
        em = objective.evaluate(split().first);
        if (!em.ok()) break;
        (em.derivative > 0 ? ehi : elo) = em;
        if (em.second_derivative > 0 && !split().second) break;
      }
      if (em.ok() && em.second_derivative > 0) {
        p = em.parameter;
        const double scale = std::max(em.second_derivative * (ehi.parameter - elo.parameter), 1e-300);
        ceres::Problem problem;
        std::vector<typename Obj::Evaluation> seen = {em};
        problem.AddResidualBlock(new Stationarity<Obj>(objective, scale, failed, seen), nullptr, &p);
        problem.SetParameterLowerBound(&p, 0, elo.parameter);
        problem.SetParameterUpperBound(&p, 0, ehi.parameter);
        ceres::Solver::Options o;
        o.linear_solver_type = ceres::DENSE_QR;
        o.max_num_iterations = options.max_iterations;
        o.parameter_tolerance = options.parameter_tolerance;
        o.function_tolerance = 1e-16;
        o.gradient_tolerance = 1e-16;
        o.logging_type = ceres::SILENT;
        ShortStep stop(options.parameter_tolerance * (options.upper - options.lower));
        o.callbacks.push_back(&stop);
        ceres::Solver::Summary summary;
        ceres::Solve(o, &problem, &summary);
        s.ceres_report = summary.BriefReport();
        no_convergence = summary.termination_type == ceres::NO_CONVERGENCE;
        ceres_message = summary.message;
        last = evaluate_once(objective, p, seen);
        // a minimum: f'' > 0 and the Newton step to f' = 0 is negligible
        refined = last->ok() && last->second_derivative > 0 &&
                  std::abs(last->derivative) <= 1e-6 * (b - a) * last->second_derivative;
      }
    }
  }
  if (!refined) {
    last.reset();
    ceres::GradientProblem problem(new BracketedObjective<Obj>(objective, centre, half, failed, last));
    ceres::GradientProblemSolver::Summary summary;
    ceres::Solve(ceres_options(options), problem, &theta, &summary);
    s.ceres_report = summary.BriefReport();
    no_convergence = summary.termination_type == ceres::NO_CONVERGENCE;
    ceres_message = summary.message;
    p = centre + half * std::tanh(theta);
    if (last && last->parameter != p) last.reset();
  }
  const auto e = last ? *last : objective.evaluate(p);
  if (!e.ok()) {  // (a failed trial point inside the line search only makes Ceres step back)
    s.status = SearchStatus::kSolverFailed;
    s.message = "solver failed during refinement: " + e.summary.brief_report();
    return finish();
  }
  if (failed) s.message += std::string(s.message.empty() ? "" : "; ") + "Ceres stepped back from unsolvable trial points";
  s.parameter = p;
  s.value = e.value;
  // A grid point may still be lower if the line search stalled (never report a worse point).
  bool stalled = false;
  if (grid[best].value < e.value) {
    s.parameter = grid[best].parameter;
    s.value = grid[best].value;
    stalled = true;
  }
  const double edge_tolerance = 1e-7 * (options.upper - options.lower);
  s.at_bound = std::abs(*s.parameter - options.lower) <= edge_tolerance || std::abs(*s.parameter - options.upper) <= edge_tolerance;
  if (no_convergence) {
    s.status = SearchStatus::kNotConverged;
    s.message = "Ceres: " + ceres_message;
  } else if (stalled && !s.at_bound) {
    // Never claim an optimum that is not one: a scan point that Ceres could not improve on is one
    // only if its slope vanishes (on the scale of the objective's variation over the scan).
    const auto at = with_derivative(grid[best]);
    if (at.ok() && std::abs(at.derivative) * (b - a) > 1e-6 * std::max(hi - lo, floor)) {
      s.status = SearchStatus::kNotConverged;
      s.message += std::string(s.message.empty() ? "" : "; ") + "the refinement stalled where the slope is " +
                   std::to_string(at.derivative) + ", not zero";
    }
  }
  return finish();
}
}  // namespace

AlphaSearchSummary search_mask_parameter(MaskObjective& objective, const AlphaSearchOptions& options) {
  return search_impl(objective, options);
}

namespace {
// The fallback of search_alpha and search_mu: a factorisation and solves per evaluation.
AlphaSearchSummary search_by_solving(const Boundary& boundary, const Objective& objective, MaskFamily family,
                                     const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                     const solvers::SolverOptions& solver_options) {
  MaskObjective f(boundary, objective, std::move(family), solver, solver_options);
  AlphaSearchSummary s = search_impl(f, options);
  s.evaluator = "factorize and solve";
  return s;
}
}  // namespace

AlphaSearchSummary search_alpha(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                                const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options) {
#if COONS_HAVE_FFTW
  const solvers::SolverInfo* info = &solver;
  if (info && info->family == solvers::SolverFamily::kStructured && boundary.m >= 2 && boundary.n >= 2 &&
      SpectralAlphaObjective::supports(objective)) {
    SpectralAlphaSearchObjective f(boundary, objective);
    AlphaSearchSummary s = search_impl(f, options);
    s.evaluator = "sine basis";
    return s;
  }
#endif
  return search_by_solving(boundary, objective, [](double a) { return alpha_family(a); }, solver, options,
                           solver_options);
}

AlphaSearchSummary search_mu(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                             const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options) {
  if (boundary.m == boundary.n) {
    AlphaSearchOptions on_alpha = options;
    on_alpha.lower = (options.lower - 1) / 4;
    on_alpha.upper = (options.upper - 1) / 4;
    AlphaSearchSummary s = search_alpha(boundary, objective, solver, on_alpha, solver_options);
    if (s.parameter) s.parameter = 1 + 4 * *s.parameter;
    for (auto& point : s.scan) point.first = 1 + 4 * point.first;
    return s;
  }
  return search_by_solving(boundary, objective,
                           [m = boundary.m, n = boundary.n](double t) { return mu_family_compressed(m, n, t); }, solver,
                           options, solver_options);
}

#if COONS_HAVE_FFTW
AlphaSearchSummary search_mask_parameter(SpectralAlphaSearchObjective& objective, const AlphaSearchOptions& options) {
  return search_impl(objective, options);
}
#endif

}  // namespace coons

namespace coons {
namespace {

// (α, γ) = (c + h·tanh θ₀, (1/4 + α)·0.999·tanh θ₁): inside the definite triangle.
class AlphaGammaFunction : public ceres::FirstOrderFunction {
 public:
  AlphaGammaFunction(MaskObjective& objective, double centre, double half, bool& failed)
      : objective_(objective), centre_(centre), half_(half), failed_(failed) {}
  static constexpr double kShrink = 0.999;
  std::pair<double, double> map(const double* t) const {
    const double alpha = centre_ + half_ * std::tanh(t[0]);
    return {alpha, (0.25 + alpha) * kShrink * std::tanh(t[1])};
  }
  bool Evaluate(const double* t, double* cost, double* gradient) const override {
    const auto [alpha, gamma] = map(t);
    std::vector<double> g;
    const Mask9 mask{0.25 - alpha + gamma, 0.25 - alpha - gamma, alpha};
    const auto e = objective_.evaluate_mask(mask, {Mask9{-1, -1, 1}, Mask9{1, -1, 0}}, g);
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    *cost = e.value;
    if (gradient) {
      const double t0 = std::tanh(t[0]), t1 = std::tanh(t[1]);
      const double dalpha = half_ * (1 - t0 * t0);
      // γ depends on α too: dγ/dθ₀ = kShrink·tanh θ₁·dα/dθ₀
      gradient[0] = (g[0] + g[1] * kShrink * t1) * dalpha;
      gradient[1] = g[1] * (0.25 + alpha) * kShrink * (1 - t1 * t1);
    }
    return true;
  }
  int NumParameters() const override { return 2; }

 private:
  MaskObjective& objective_;
  double centre_, half_;
  bool& failed_;
};

}  // namespace

AlphaGammaSummary search_alpha_gamma(MaskObjective& objective, const AlphaSearchOptions& options) {
  AlphaGammaSummary out;
  const AlphaSearchSummary one = search_mask_parameter(objective, options);
  out.evaluations = one.evaluations;
  out.solves = one.solves;
  if (one.status == SearchStatus::kSolverFailed) {
    out.status = one.status;
    out.message = one.message;
    return out;
  }
  if (one.flat) {
    // Flat in α at γ = 0 does not prove flat in γ, but the families that make α flat (planar and
    // bilinear boundaries) reproduce the same net for every affine-invariant mask.
    out.status = SearchStatus::kFlat;
    out.flat = true;
    out.value = out.value_at_gamma0 = one.value;
    out.message = "flat in alpha; gamma not searched";
    return out;
  }
  out.value_at_gamma0 = one.value;
  const double lower = std::max(options.lower, -0.25), upper = std::min(options.upper, 0.25);
  const double centre = 0.5 * (lower + upper), half = 0.5 * (upper - lower);
  double t[2] = {std::atanh(std::clamp((*one.parameter - centre) / half, -0.999, 0.999)), 0.0};
  bool failed = false;
  auto* function = new AlphaGammaFunction(objective, centre, half, failed);
  ceres::GradientProblem problem(function);
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(ceres_options(options), problem, t, &summary);
  out.ceres_report = summary.BriefReport();
  const auto [alpha, gamma] = function->map(t);
  std::vector<double> g;
  const auto e = objective.evaluate_mask(Mask9{0.25 - alpha + gamma, 0.25 - alpha - gamma, alpha}, {}, g);
  out.evaluations = objective.evaluations();
  out.solves = objective.solves();
  if (failed || !e.ok()) {
    out.status = SearchStatus::kSolverFailed;
    out.message = "solver failed during the (alpha, gamma) refinement";
    return out;
  }
  out.alpha = alpha;
  out.gamma = gamma;
  out.value = e.value;
  if (one.value < e.value) {  // never report a worse point than the symmetric optimum
    out.alpha = *one.parameter;
    out.gamma = 0;
    out.value = one.value;
  }
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    out.status = SearchStatus::kNotConverged;
    out.message = "Ceres: " + summary.message;
  }
  return out;
}

}  // namespace coons
