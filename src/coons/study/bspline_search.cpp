#include "coons/study/bspline_search.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include "coons/alpha/search_failures.h"
#include "coons/mask/near_singular.h"
#include "coons/mask/nonuniform_mask.h"
#include "coons/study/bspline_net.h"
#include "coons/surfaces/bspline_energy.h"
#include "solvers/registry.h"

namespace coons {

AlphaSearchOptions default_bspline_search_options() {
  AlphaSearchOptions options;
  options.lower = -0.25;
  options.upper = 0.0;
  // The Gram forms of short knot spans cancel large terms: the energies of one net vary by ~1e-11
  // relative between equivalent solves, so flatness is judged at 1e-9.
  options.flat_tolerance = 1e-9;
  return options;
}

double bspline_definite_upper(const BSplineBoundary& compatible) {
  const ControlNet frame = bspline_frame(compatible);
  const GrevilleGrid grid = greville_grid(compatible);
  const auto definite = [&](double alpha) {
    const auto backend = solvers::make_solver("eigen-llt");
    return backend && solve_nonuniform_mask_net(frame, grid, alpha, *backend, false, 10 * kNearSingularEigenvalueRatio)
                          .summary.ok();
  };
  if (definite(0.25)) return 0.25;
  double lo = 0.0, hi = 0.25;
  while (hi - lo > 0.25e-6) {
    const double mid = 0.5 * (lo + hi);
    (definite(mid) ? lo : hi) = mid;
  }
  return lo;
}

AlphaSearchOptions bspline_search_options(const BSplineBoundary& compatible) {
  AlphaSearchOptions options = default_bspline_search_options();
  options.upper = bspline_definite_upper(compatible);
  return options;
}

std::string bspline_pole_note(const AlphaSearchSummary& s, const AlphaSearchOptions& options, double definite_upper) {
  if (!s.parameter || !(definite_upper < 0.25) || options.upper != definite_upper) return "";
  const double gap = definite_upper - *s.parameter;
  if (!(gap <= 0.02 * (options.upper - options.lower))) return "";
  if (s.at_bound)  // the objective still falls at U (a knot vector with spans of 2e-9: the note said it rose)
    return fmt::format(
        "the optimum is {}, the end of the range where the non-uniform system is definite (a singular alpha lies "
        "just above it), where the objective still falls: the range, not the boundary, ends this minimum",
        definite_upper);
  return fmt::format(
      "the optimum lies {:.3g} below {}, the end of the range where the non-uniform system is definite (a singular "
      "alpha lies just above it): the objective rises there because of that singular alpha, so this minimum is made "
      "by it, not by the boundary",
      gap, definite_upper);
}

bool bspline_objective_supported(const Objective& objective, std::string* why) {
  if (objective.target_weight > 0) {
    if (why) *why = "a target term compares Bézier nets; a B-spline boundary takes energies only";
    return false;
  }
  return true;
}

std::optional<BSplineObjectiveValue> bspline_alpha_objective(const BSplineBoundary& b, const Objective& objective,
                                                             double alpha, solvers::LinearSolver& solver,
                                                             solvers::SolveStatus* status, int* solves) {
  // outside [−1/4, 0] a near-singular system is a failed evaluation, never a value (near_singular.h)
  const NonUniformSolveResult r =
      solve_nonuniform_mask_net(bspline_frame(b), greville_grid(b), alpha, solver, true, kNearSingularEigenvalueRatio);
  if (status) *status = r.summary.status;
  if (solves) *solves = r.solves;
  if (!r.summary.ok()) return std::nullopt;
  const BSplineSurface s = bspline_surface_on(b, r.net);
  std::vector<BSplineEnergyTerm> terms;
  for (const EnergyTerm& t : objective.energy) terms.push_back({t.a, t.b, t.weight});
  BSplineObjectiveValue out;
  out.value = bspline_combined_energy(s, terms);
  out.derivative = 2 * bspline_combined_energy_form(s, r.net, r.derivative, terms);
  for (const auto& [kind, weight] : objective.discrete) {
    out.value += weight * discrete_energy_form(r.net, r.net, kind);
    out.derivative += 2 * weight * discrete_energy_form(r.net, r.derivative, kind);
  }
  if (!std::isfinite(out.value) || !std::isfinite(out.derivative)) return std::nullopt;
  return out;
}

namespace {

struct Point {
  double alpha = 0;
  std::optional<BSplineObjectiveValue> f;
};

class Evaluator {
 public:
  Evaluator(const BSplineBoundary& b, const Objective& o, std::string solver, const solvers::SolverOptions& options,
            AlphaSearchSummary& summary)
      : b_(b), objective_(o), solver_(std::move(solver)), options_(options), summary_(summary) {}

  Point operator()(double alpha) {
    auto backend = solvers::make_solver(solver_, options_);
    solvers::SolveStatus status = solvers::SolveStatus::kFailure;
    int solves = 0;
    Point p{alpha, backend ? bspline_alpha_objective(b_, objective_, alpha, *backend, &status, &solves) : std::nullopt};
    ++summary_.evaluations;
    summary_.solves += solves;
    if (!p.f && std::none_of(log_.begin(), log_.end(), [](const auto& e) { return !e.second; }))
      summary_.first_failure = status;
    log_.emplace_back(alpha, bool(p.f));
    return p;
  }
  //! Every evaluation as (α, succeeded), for detail::judge_failures.
  [[nodiscard]] const std::vector<std::pair<double, bool>>& log() const { return log_; }

 private:
  const BSplineBoundary& b_;
  const Objective& objective_;
  std::string solver_;
  solvers::SolverOptions options_;
  AlphaSearchSummary& summary_;
  std::vector<std::pair<double, bool>> log_;
};

// The root of f′ in [left, right] with f′(left) ≤ 0 ≤ f′(right): Illinois regula falsi, a
// bisection step whenever it stalls. Returns the last point evaluated inside (or an end).
Point derivative_root(Evaluator& eval, Point left, Point right, const AlphaSearchOptions& options) {
  double fl = left.f->derivative, fr = right.f->derivative;
  int side = 0;
  Point best = std::abs(fl) < std::abs(fr) ? left : right;
  for (int it = 0; it < options.max_iterations && right.alpha - left.alpha > options.parameter_tolerance; ++it) {
    double x = fr != fl ? (left.alpha * fr - right.alpha * fl) / (fr - fl) : 0.5 * (left.alpha + right.alpha);
    const double width = right.alpha - left.alpha;
    if (!(x > left.alpha + 0.01 * width && x < right.alpha - 0.01 * width)) x = 0.5 * (left.alpha + right.alpha);
    const Point p = eval(x);
    if (!p.f) return p;  // a failure inside the bracket: the caller reports it
    best = p;
    const double d = p.f->derivative;
    // The derivative is zero to rounding: the change over the bracket is below the value's last digits.
    if (std::abs(d) * (right.alpha - left.alpha) <= 1e-15 * std::abs(p.f->value)) break;
    if (d < 0) {
      left = p;
      fl = d;
      if (side == -1) fr /= 2;
      side = -1;
    } else {
      right = p;
      fr = d;
      if (side == 1) fl /= 2;
      side = 1;
    }
  }
  return best;
}

}  // namespace

AlphaSearchSummary search_bspline_alpha(const BSplineBoundary& b, const Objective& objective,
                                        const std::string& solver_name, const AlphaSearchOptions& options,
                                        const solvers::SolverOptions& solver_options) {
  const auto started = std::chrono::steady_clock::now();
  AlphaSearchSummary s;
  s.evaluator = "factorize and solve (non-uniform B-spline family)";
  // in the frame centred on the boundary (bspline_net.h): the energies do not move with it, and a
  // boundary at 1e12 no longer loses the shape's digits to the offset
  const BSplineBoundary local = bspline_translated(b, -bspline_centre(b));
  Evaluator eval(local, objective, solver_name, solver_options, s);
  // Failed evaluations are judged as in the Bézier search (search_failures.h): counted, grouped
  // into intervals, and a verdict that rests on one becomes failed_region, with where in the message.
  const auto finish = [&]() -> AlphaSearchSummary {
    detail::judge_failures(s, eval.log());
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    return s;
  };
  std::vector<Point> scan;
  const int n = std::max(options.scan_points, 2);
  for (int k = 0; k < n; ++k) {
    // the last point is the upper bound itself (lower + width·k/(n−1) can miss it by an ulp)
    const double alpha = k + 1 == n ? options.upper : options.lower + (options.upper - options.lower) * k / (n - 1);
    scan.push_back(eval(alpha));
    s.scan.emplace_back(alpha, scan.back().f ? scan.back().f->value : HUGE_VAL);
  }
  int best = -1;
  double lowest = HUGE_VAL, highest = -HUGE_VAL;
  for (int k = 0; k < n; ++k)
    if (scan[std::size_t(k)].f) {
      const double v = scan[std::size_t(k)].f->value;
      if (best < 0 || v < lowest) best = k;
      lowest = std::min(lowest, v);
      highest = std::max(highest, v);
    }
  if (best < 0) {
    s.status = SearchStatus::kSolverFailed;
    s.message = "no evaluation succeeded";
    return finish();
  }
  for (int k = 1; k + 1 < n; ++k) {
    const auto& here = scan[std::size_t(k)].f;
    const auto& before = scan[std::size_t(k) - 1].f;
    const auto& after = scan[std::size_t(k) + 1].f;
    if (here && before && after && here->value < before->value && here->value < after->value) ++s.local_minima;
  }
  s.value = lowest;
  const bool near_failure =
      (best > 0 && !scan[std::size_t(best) - 1].f) || (best + 1 < n && !scan[std::size_t(best) + 1].f);
  if (highest - lowest <= options.flat_tolerance * std::max({std::abs(highest), std::abs(lowest), 1e-300})) {
    s.flat = true;
    s.status = SearchStatus::kFlat;
    return finish();
  }
  const Point& at = scan[std::size_t(best)];
  if (near_failure) {  // the lowest scan point, next to a failure: judge_failures claims nothing
    s.parameter = at.alpha;
    return finish();
  }
  Point optimum = at;
  const double d = at.f->derivative;
  if ((best == 0 && d >= 0) || (best == n - 1 && d <= 0)) {
    optimum = at;  // on a bound, the objective rising into the interval
  } else {
    const bool go_left = d > 0;
    const Point& other = scan[go_left ? std::size_t(best) - 1 : std::size_t(best) + 1];
    if (!other.f) {
      s.parameter = at.alpha;
      return finish();
    }
    const Point left = go_left ? other : at, right = go_left ? at : other;
    if (left.f->derivative <= 0 && right.f->derivative >= 0) {
      optimum = derivative_root(eval, left, right, options);
    } else {
      s.status = SearchStatus::kNotConverged;
      s.message = "the derivative does not change sign next to the lowest scan point";
    }
  }
  if (!optimum.f) {
    s.status = SearchStatus::kSolverFailed;
    s.message = "the evaluation at the refined optimum failed";
    return finish();
  }
  if (optimum.f->value > lowest) optimum = at;  // never report worse than the scan
  s.parameter = optimum.alpha;
  s.value = optimum.f->value;
  // as in the search of Bézier boundaries (under the old rule of the parameter tolerance, 1e-10, a
  // degree-5 boundary's twist minimum at −0.24999999907 had at_bound false)
  s.at_bound = lies_on_bound(optimum.alpha, options.lower, options.upper);
  return finish();
}

}  // namespace coons
