// Internal to the one-parameter mask searches (alpha_search.cpp, family_search.cpp): the search
// itself, for any evaluator with evaluate(p, with_derivative), unit_frame(), evaluations() and
// solves() whose Evaluation has parameter, value, derivative, derivative_noise, has_derivative,
// summary and ok() (MaskObjective, SpectralAlphaSearchObjective, StencilFamilyObjective):
//   InUnitFrame   the evaluator seen in its normalised frame (normalised_frame.h), every
//                 evaluation logged as (parameter, succeeded);
//   SearchRun     coarse scan, flat and bound verdicts, refinement of the best scan point and of
//                 the scan's other minima (search_in_frame: one run).
// The entry point, search_impl, and the search between poles are in search_impl.h.
// Sizes: the scan (scan_points evaluations) and the log, one entry per evaluation.
// Based on: Ceres Solver's GradientProblemSolver and Problem (S. Agarwal, K. Mierle et al.).
#pragma once

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/ceres_refinement.h"
#include "coons/alpha/downhill.h"
#include "coons/alpha/search_failures.h"
#include "solvers/linear_solver.h"

namespace coons::detail {

template <class T, class = void>
struct HasSingularParameters : std::false_type {};
template <class T>
struct HasSingularParameters<T, std::void_t<decltype(std::declval<const T&>().singular_parameters(0.0, 0.0))>>
    : std::true_type {};

// An evaluator seen in its normalised frame: values divided by the frame's value factor (a power
// of two, so exactly), the frame's boundary and objective. Every tolerance of the search is then
// met by values of the size a unit boundary gives, whatever the caller's coordinates.
template <class Obj>
class InUnitFrame {
 public:
  using Evaluation = typename Obj::Evaluation;
  explicit InUnitFrame(Obj& objective) : objective_(objective), k_(objective.unit_frame().value_factor) {}
  Evaluation evaluate(double p, bool with_derivative = true) {
    Evaluation e = objective_.evaluate(p, with_derivative);
    log_.push_back({p, e.ok()});
    if (!e.ok() && first_failure_ == solvers::SolveStatus::kSuccess) first_failure_ = e.summary.status;
    e.value /= k_;
    e.derivative /= k_;
    e.derivative_noise /= k_;
    if constexpr (HasSecondDerivative<Obj>::value) e.second_derivative /= k_;
    return e;
  }
  [[nodiscard]] const Boundary& boundary() const { return objective_.unit_frame().boundary; }
  [[nodiscard]] const Objective& objective() const { return objective_.unit_frame().objective; }
  [[nodiscard]] int evaluations() const { return objective_.evaluations(); }
  [[nodiscard]] int solves() const { return objective_.solves(); }
  [[nodiscard]] static double scale_origin() { return Obj::scale_origin(); }
  [[nodiscard]] double value_factor() const { return k_; }
  //! The parameters in (lower, upper) where the evaluator is singular, increasing, when it knows
  //! them (the α family's RegularAlphas, alpha_search.cpp); else none.
  [[nodiscard]] std::vector<double> singular_parameters(double lower, double upper) const {
    if constexpr (HasSingularParameters<Obj>::value) return objective_.singular_parameters(lower, upper);
    return {};
  }
  //! Every evaluation made through this view: (parameter, succeeded), in order.
  [[nodiscard]] const std::vector<std::pair<double, bool>>& log() const { return log_; }
  [[nodiscard]] solvers::SolveStatus first_failure() const { return first_failure_; }

 private:
  Obj& objective_;
  double k_;
  std::vector<std::pair<double, bool>> log_;
  solvers::SolveStatus first_failure_ = solvers::SolveStatus::kSuccess;
};

// A line search on values cannot place α* closer than √(ε·f/f'') (f is flat at rounding level
// there: about 1e−9 relative for the discrete thin plate of the dome); secant steps on the exact
// derivative, f' = 0, can. Steps stay in [a, b] and are kept only while |f'| decreases.
template <class Obj>
typename Obj::Evaluation polish_stationary(Obj& objective, typename Obj::Evaluation at, double a, double b) {
  if (!at.ok() || !at.has_derivative || at.derivative == 0) return at;
  const double width = b - a, h = 1e-6 * width;
  auto other = objective.evaluate(std::clamp(at.parameter + (at.derivative > 0 ? -h : h), a, b));
  for (int it = 0; it < 8 && other.ok() && other.parameter != at.parameter; ++it) {
    const double slope = (other.derivative - at.derivative) / (other.parameter - at.parameter);
    if (!(slope > 0)) break;  // not convex here: leave it to the line search's point
    const double next = at.parameter - at.derivative / slope;
    if (!(next >= a && next <= b) || std::abs(next - at.parameter) <= 1e-15 * width) break;
    auto e = objective.evaluate(next);
    if (!e.ok() || !(std::abs(e.derivative) < std::abs(at.derivative))) break;
    other = std::move(at);
    at = std::move(e);
  }
  return at;
}

// One search, step by step: scan, the flat and bound verdicts, the refinement of the best scan
// point (Newton on f' = 0 where f'' is known, else Ceres's line search and a secant polish), and
// the verdict on the refined point. Each step returns true when it has decided the summary.
template <class Obj>
class SearchRun {
 public:
  using Evaluation = typename Obj::Evaluation;
  SearchRun(Obj& objective, const AlphaSearchOptions& options) : objective_(objective), options_(options) {}

  AlphaSearchSummary run() {
    if (!scan() && !flat()) {
      if (!on_bound()) refine(best_);
      refine_other_minima();
    }
    s_.evaluations = objective_.evaluations();
    s_.solves = objective_.solves();
    s_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    return s_;
  }

 private:
  void append(const std::string& text) { s_.message += (s_.message.empty() ? "" : "; ") + text; }
  Evaluation with_derivative(const Evaluation& e) { return e.has_derivative ? e : objective_.evaluate(e.parameter); }

  // 1. Coarse scan. A point where the solver fails (a singular α outside [−1/4, 1/4]) is a
  //    penalty, not an abort: it counts as +∞ and is reported; a scan where every point fails is a
  //    failure.
  bool scan() {
    const int k = options_.scan_points;
    int failed_points = 0;
    std::string first_failure;
    for (int i = 0; i < k; ++i) {
      const double p = scan_point(options_.lower, options_.upper, k, i);
      grid_.push_back(objective_.evaluate(p, /*with_derivative=*/false));  // values suffice to scan
      if (!grid_.back().ok()) {
        if (failed_points++ == 0)
          first_failure = "at " + solvers::format_g(p) + ": " + grid_.back().summary.brief_report();
        grid_.back().value = HUGE_VAL;
      }
      s_.scan.emplace_back(p, grid_.back().value);
    }
    if (failed_points == k) {
      s_.status = SearchStatus::kSolverFailed;
      s_.message = "every scan point failed; " + first_failure;
      return true;
    }
    for (int i = 0; i < k; ++i) {
      if (!grid_[i].ok()) continue;
      lo_ = std::min(lo_, grid_[i].value);
      hi_ = std::max(hi_, grid_[i].value);
      if (best_ < 0 || grid_[i].value < grid_[best_].value) best_ = i;
    }
    s_.local_minima = count_local_minima();
    if (failed_points > 0)
      s_.message = std::to_string(failed_points) + " scan point(s) could not be solved and were skipped (first " +
                   first_failure + ")";
    return false;
  }

  // The interior local minima of the scan, with a hysteresis of a few hundred ε of the values: a
  // minimum is counted where the values, having fallen by more than that, rise by more than that
  // (a fine scan near the optimum saw two "minima" 1e-15 deep in 13.4247065809274, and a bottom
  // of equal values is one minimum, not none). Failed points end a run: a minimum must be seen
  // between two solved neighbours on each side.
  int count_local_minima() const {
    const double tolerance = 256 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo_), std::abs(hi_));
    int count = 0;
    bool falling = false;  // the values fell by more than the tolerance since the last maximum
    double low = 0, high = 0;
    bool open = false;  // a run of solved points has started
    for (const Evaluation& e : grid_) {
      if (!e.ok()) {
        open = falling = false;
        continue;
      }
      if (!open) {
        open = true;
        low = high = e.value;
        continue;
      }
      if (e.value < low) low = e.value;
      if (e.value > high) high = e.value;
      if (!falling && e.value < high - tolerance) {
        falling = true;
        low = e.value;
      } else if (falling && e.value > low + tolerance) {
        ++count;
        falling = false;
        high = e.value;
      }
    }
    return count;
  }

  // 2. Flat: the range is at rounding level of the objective's natural scale. Rounding errors of
  //    size ε·diag in the net reach an energy of derivative order k amplified by degree^k, so the
  //    floor is diag²·degree^(2k)·1e-16 (far above (ε·diag·degree^k)², far below real signals).
  //    Discrete energies of the net carry no degree factors (order 0). The rms distance to a
  //    target is a length, not a square: it carries rounding errors of ε·diag itself, so its floor
  //    is 1e-2·diag, a range of 1e-14·diag after flat_tolerance (1e-8·diag let a surface lying on
  //    its target report an optimum picked from 5e-18 of noise).
  bool flat() {
    const Boundary& boundary = objective_.boundary();
    const double diag = bounding_box_diagonal(boundary);
    const Objective& objective = objective_.objective();
    int order = 0;
    for (const EnergyTerm& t : objective.energy) order = std::max(order, t.a + t.b);
    const double degree = std::max({boundary.m, boundary.n, 1});
    const bool energies = !objective.energy.empty() || !objective.discrete.empty();
    floor_ = (energies ? 1e-16 * diag * diag * std::pow(degree, 2.0 * order) : 0.0) +
             (objective.target_weight > 0 ? objective.target_weight * 1e-2 * diag : 0.0);
    s_.rounding_floor = floor_;
    const double rounding = options_.flat_tolerance * std::max({std::abs(hi_), std::abs(lo_), floor_});
    if (hi_ - lo_ <= std::max(rounding, solver_noise(diag, degree, energies ? order : -1))) {
      s_.status = SearchStatus::kFlat;
      s_.flat = true;
      s_.local_minima = 0;  // dips of rounding noise are no minima (their count changed with the last bit)
      s_.value = grid_[best_].value;
      s_.message = "the objective does not depend on the parameter over the bounds";
      if (hi_ - lo_ > rounding) s_.message += ", to within what the iterative solver's relative residuals resolve";
      return true;
    }
    return false;
  }

  // How far an iterative solver's error moves the objective: its nets are exact to about its
  //    largest relative residual r over the scan times the condition of the mask system (at most
  //    about degree⁴ on [−1/4, 1/4], docs/math.md §3), a net error d = r·degree⁴·diag, which moves an
  //    energy E of derivative order k by about 2√E·d·degreeᵏ + (d·degreeᵏ)² and a distance to a
  //    target by d. 0 for exact solvers (r at rounding level, or not computed): jacobi's scan of the
  //    saddle's e3, exactly 0, held values from 3e-22 to 3.5e-30, and an optimum was picked from them.
  //    order < 0: no energy term.
  [[nodiscard]] double solver_noise(double diag, double degree, int order) const {
    double r = 0;
    for (const Evaluation& e : grid_)
      if (e.ok() && std::isfinite(e.summary.relative_residual)) r = std::max(r, e.summary.relative_residual);
    if (!(r > 1e-13)) return 0;
    const double d = r * std::pow(degree, 4.0) * diag;
    double noise = 0;
    if (order >= 0) {
      const double dk = d * std::pow(degree, order);
      noise += 2 * std::sqrt(std::max(std::abs(hi_), std::abs(lo_))) * dk + dk * dk;
    }
    if (objective_.objective().target_weight > 0) noise += objective_.objective().target_weight * d;
    return noise;
  }

  // 3. Optimum on a bound: the best grid point is a bound and the slope points outwards (a slope
  //    at rounding level, as at a minimum on the bound itself, counts as outwards).
  //    Every objective is ≥ 0, so a bound whose value is 0 to rounding (the flat test's floor) is
  //    a minimum whatever its slope: at the kink of an rms distance that vanishes there (a target
  //    net solved at α = −1/4) the slope is noise, and it read as pointing inwards.
  bool on_bound() {
    const int k = int(grid_.size());
    if (best_ == 0 || best_ == k - 1) grid_[best_] = with_derivative(grid_[best_]);  // its slope decides
    const bool zero = (best_ == 0 || best_ == k - 1) && grid_[best_].value <= options_.flat_tolerance * floor_;
    if (zero || (best_ == 0 && grid_[0].derivative >= -grid_[0].derivative_noise) ||
        (best_ == k - 1 && grid_[k - 1].derivative <= grid_[k - 1].derivative_noise)) {
      s_.parameter = grid_[best_].parameter;
      s_.value = grid_[best_].value;
      s_.at_bound = true;
      return true;
    }
    return false;
  }

  // Newton on f' = 0 needs a start where f is convex and a bracket where f' changes sign: shrink
  // the bracket on the sign of f' until it is resolved and its new end is convex, then let Ceres
  // take Newton steps. The family's scale collapses at objective.scale_origin() (α = −1/4, where
  // α* + 1/4 ≈ c/n², docs/math.md §4), so a bracket spanning many scales of the distance d to it is
  // split at the geometric mean of its ends' distances (√(h·d_hi) from the origin itself, h the
  // Newton step there), which halves log(d_hi/d_lo) per evaluation; a resolved bracket
  // (d_hi ≤ 1.5·d_lo) is split at its midpoint. Returns the evaluation at the minimum, if found.
  std::optional<Evaluation> refine_by_newton(int ia, int ib) {
    const double a = grid_[ia].parameter, b = grid_[ib].parameter;
    auto elo = grid_[ia].ok() ? with_derivative(grid_[ia]) : objective_.evaluate(a);
    auto ehi = grid_[ib].ok() ? with_derivative(grid_[ib]) : objective_.evaluate(b);
    if (!(elo.ok() && ehi.ok() && elo.derivative < 0 && ehi.derivative > 0)) return std::nullopt;
    const double origin = objective_.scale_origin();
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
      em = objective_.evaluate(split().first);
      if (!em.ok()) break;
      (em.derivative > 0 ? ehi : elo) = em;
      if (em.second_derivative > 0 && !split().second) break;
    }
    if (!(em.ok() && em.second_derivative > 0)) return std::nullopt;
    double p = em.parameter;
    const double scale = std::max(em.second_derivative * (ehi.parameter - elo.parameter), 1e-300);
    ceres::Problem problem;
    std::vector<Evaluation> seen = {em};
    problem.AddResidualBlock(new Stationarity<Obj>(objective_, scale, failed_, seen), nullptr, &p);
    problem.SetParameterLowerBound(&p, 0, elo.parameter);
    problem.SetParameterUpperBound(&p, 0, ehi.parameter);
    ceres::Solver::Options o;
    o.linear_solver_type = ceres::DENSE_QR;
    set_search_tolerances(o, options_, 1e-16, 1e-16);
    ShortStep stop(options_.parameter_tolerance * step_scale(b - a));
    o.callbacks.push_back(&stop);
    ceres::Solver::Summary summary;
    ceres::Solve(o, &problem, &summary);
    s_.ceres_report = summary.BriefReport();
    no_convergence_ = summary.termination_type == ceres::NO_CONVERGENCE;
    ceres_message_ = summary.message;
    Evaluation last = evaluate_once(objective_, p, seen);
    // a minimum: f'' > 0 and the Newton step to f' = 0 is negligible
    if (last.ok() && last.second_derivative > 0 && std::abs(last.derivative) <= 1e-6 * (b - a) * last.second_derivative)
      return last;
    return std::nullopt;
  }

  // Ceres's line search on f(centre + half·tanh θ) from the scan point `start`, then secant steps
  // on f' = 0.
  Evaluation refine_by_line_search(int ia, int ib, int start) {
    const double a = grid_[ia].parameter, b = grid_[ib].parameter;
    const double centre = 0.5 * (a + b), half = 0.5 * (b - a);
    double theta = std::atanh(std::clamp((grid_[start].parameter - centre) / half, -0.9, 0.9));
    std::vector<Evaluation> latest;  // Ceres usually ends on its latest evaluation
    ceres::GradientProblem problem(new BracketedObjective<Obj>(objective_, centre, half, failed_, latest));
    ceres::GradientProblemSolver::Summary summary;
    ceres::Solve(ceres_options(options_), problem, &theta, &summary);
    s_.ceres_report = summary.BriefReport();
    no_convergence_ = summary.termination_type == ceres::NO_CONVERGENCE;
    ceres_message_ = summary.message;
    Evaluation e = evaluate_once(objective_, centre + half * std::tanh(theta), latest);
    if (!no_convergence_) e = polish_stationary(objective_, std::move(e), a, b);
    return e;
  }

  // 4. Refine in the bracket of the scan point `start`'s neighbours (the best one first), then the
  //    verdict on the result: a grid point may still be lower if the line search stalled (never
  //    report a worse point), and a scan point that Ceres could not improve on is an optimum only
  //    if its slope vanishes (on the scale of the objective's variation over the scan).
  void refine(int start) {
    const int k = int(grid_.size());
    const int ia = std::max(start - 1, 0), ib = std::min(start + 1, k - 1);
    const double a = grid_[ia].parameter, b = grid_[ib].parameter;
    failed_ = no_convergence_ = false;
    std::optional<Evaluation> refined;
    if constexpr (HasSecondDerivative<Obj>::value) refined = refine_by_newton(ia, ib);
    const Evaluation e = refined ? *refined : refine_by_line_search(ia, ib, start);
    if (!e.ok()) {  // (a failed trial point inside the line search only makes Ceres step back)
      s_.status = SearchStatus::kSolverFailed;
      s_.message = "solver failed during refinement: " + e.summary.brief_report();
      return;
    }
    if (failed_) append("Ceres stepped back from unsolvable trial points");
    s_.parameter = e.parameter;
    s_.value = e.value;
    bool stalled = false;
    if (grid_[start].value < e.value) {
      s_.parameter = grid_[start].parameter;
      s_.value = grid_[start].value;
      stalled = true;
    }
    s_.at_bound = lies_on_bound(*s_.parameter, options_.lower, options_.upper);
    if (no_convergence_) {
      s_.status = SearchStatus::kNotConverged;
      s_.message = "Ceres: " + ceres_message_;
    } else if (stalled) {
      // The scan point Ceres could not improve on is an optimum only where its slope vanishes, or,
      // on a bound, points out of the interval. Where the bracket holds a singular α (a pole of the
      // objective, with --allow-indefinite bounds) the line search crossed it and stalled, and the
      // bound α = 1/4 was reported as the optimum where the objective still falls into the interval.
      const auto at = with_derivative(grid_[start]);
      const bool outward = (start == 0 && at.derivative >= -at.derivative_noise) ||
                           (start == k - 1 && at.derivative <= at.derivative_noise);
      if (at.ok() && !(s_.at_bound && outward) && !vanishing(at, b - a)) {
        if (const std::optional<Evaluation> d = refine_downhill(at, ia, ib)) {
          s_.parameter = d->parameter;
          s_.value = d->value;
          s_.at_bound = lies_on_bound(d->parameter, options_.lower, options_.upper);
        } else {
          s_.status = SearchStatus::kNotConverged;
          append("the refinement stalled where the slope is " + solvers::format_g(at.derivative) + ", not zero");
        }
      }
    }
  }

  // 5. The other interior minima of the scan, refined as the best point was, and the lowest
  //    result kept: a dip between scan points can hold the minimum (a random 5 × 3 boundary over
  //    [−1, 1] with --allow-indefinite: the best scan point, the bound 1, was reported at 13.38101
  //    while the scan point 0.5 leads to 13.32405 at α = 0.3138). A scan point is a minimum where
  //    it lies more than the scan's hysteresis (count_local_minima) below its left neighbour and
  //    not above its right one; a refinement that fails leaves the verdict of the others.
  void refine_other_minima() {
    if (s_.status != SearchStatus::kSuccess && s_.status != SearchStatus::kNotConverged) return;
    if (s_.value <= options_.flat_tolerance * floor_) return;  // 0 to rounding: nothing is lower
    const double tolerance = 256 * std::numeric_limits<double>::epsilon() * std::max(std::abs(lo_), std::abs(hi_));
    const int k = int(grid_.size());
    const double first = *s_.parameter, first_value = s_.value;
    int refined = 0;
    for (int i = 1; i + 1 < k; ++i) {
      if (i == best_ || !grid_[i - 1].ok() || !grid_[i].ok() || !grid_[i + 1].ok() ||
          !(grid_[i].value < grid_[i - 1].value - tolerance && grid_[i].value <= grid_[i + 1].value))
        continue;
      ++refined;
      const auto kept = std::make_tuple(s_.parameter, s_.value, s_.status, s_.at_bound, s_.message, s_.ceres_report);
      s_.status = SearchStatus::kSuccess;
      refine(i);
      const bool better = (s_.status == SearchStatus::kSuccess || s_.status == SearchStatus::kNotConverged) &&
                          s_.value < std::get<1>(kept);
      if (!better) std::tie(s_.parameter, s_.value, s_.status, s_.at_bound, s_.message, s_.ceres_report) = kept;
    }
    if (refined == 0) return;
    if (*s_.parameter != first)
      append("the best scan point and " + std::to_string(refined) +
             " other minima of the scan were refined and the lowest result kept (the best scan point led to " +
             solvers::format_g(first) + ", value " + solvers::format_g(first_value * objective_.value_factor()) + ")");
    else
      append("the best scan point and " + std::to_string(refined) +
             " other minima of the scan were refined; the best scan point's result is lowest");
  }

  // The length the parameter tolerance is relative to: the bounds' width, or on bounds scanned in
  // asinh (scan_point) the bracket's, which is small where the scan is fine (1e-10 of [−0.3, 1e12]
  // let a refinement stop 0.03 from the minimum).
  [[nodiscard]] double step_scale(double bracket) const {
    const double width = options_.upper - options_.lower;
    return width > kWideScanWidth ? bracket : width;
  }

  // A slope that vanishes on the scale of the objective's variation over the scan.
  bool vanishing(const Evaluation& e, double width) const {
    return std::abs(e.derivative) * width <= 1e-6 * std::max(hi_ - lo_, floor_);
  }

  // From the scan point g downhill inside the bracket [grid ia, grid ib] to a point below it where
  // the slope vanishes (downhill.h), or nothing.
  std::optional<Evaluation> refine_downhill(Evaluation g, int ia, int ib) {
    const double end = grid_[g.derivative < 0 ? ib : ia].parameter, width = grid_[ib].parameter - grid_[ia].parameter;
    if (end == g.parameter) return std::nullopt;
    const auto vanishes = [&](const Evaluation& e) { return vanishing(e, width); };
    Downhill<Evaluation> d =
        go_downhill([&](double c) { return objective_.evaluate(c); }, std::move(g), end,
                    options_.parameter_tolerance * step_scale(width), 4 * options_.max_iterations, vanishes);
    // (a failed evaluation: judge_failures withholds a verdict that rests on it)
    if (d.failed || !vanishes(d.lowest)) return std::nullopt;
    return std::move(d.lowest);
  }

  Obj& objective_;
  const AlphaSearchOptions& options_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  AlphaSearchSummary s_;
  std::vector<Evaluation> grid_;
  double lo_ = HUGE_VAL, hi_ = -HUGE_VAL, floor_ = 0;
  int best_ = -1;
  bool failed_ = false, no_convergence_ = false;
  std::string ceres_message_;
};

template <class Obj>
AlphaSearchSummary search_in_frame(Obj& objective, const AlphaSearchOptions& options) {
  return SearchRun<Obj>(objective, options).run();
}

}  // namespace coons::detail
