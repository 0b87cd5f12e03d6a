// The two-parameter symmetric family (α, γ) of alpha_search.h: a 1-D α search at γ = 0, then
// Ceres's line search in both, inside the triangle |γ| ≤ 0.999(1/4 + α) where the operator is
// definite on every grid, and a polish by coordinate searches (Brent) on that box in (α, γ/(1/4 + α)).
#include <ceres/ceres.h>

#include <algorithm>
#include <boost/math/tools/minima.hpp>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/ceres_refinement.h"

namespace coons {
namespace {

using detail::ceres_options;

// The symmetric 3×3 mask of (α, γ): β_i = 1/4 − α + γ, β_j = 1/4 − α − γ.
Mask9 symmetric_mask(double alpha, double gamma) { return Mask9{0.25 - alpha + gamma, 0.25 - alpha - gamma, alpha}; }

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
    const Mask9 mask = symmetric_mask(alpha, gamma);
    const auto e = objective_.evaluate_mask(mask, {Mask9{-1, -1, 1}, Mask9{1, -1, 0}}, g);
    if (!e.ok()) {
      failed_ = true;
      return false;
    }
    // (values in the normalised frame, as the 1-D search sees them: Ceres's tolerances are absolute)
    const double k = objective_.unit_frame().value_factor;
    *cost = e.value / k;
    if (gradient) {
      const double t0 = std::tanh(t[0]), t1 = std::tanh(t[1]);
      const double dalpha = half_ * (1 - t0 * t0);
      // γ depends on α too: dγ/dθ₀ = kShrink·tanh θ₁·dα/dθ₀
      gradient[0] = (g[0] + g[1] * kShrink * t1) * dalpha / k;
      gradient[1] = g[1] * (0.25 + alpha) * kShrink * (1 - t1 * t1) / k;
    }
    return true;
  }
  int NumParameters() const override { return 2; }

 private:
  MaskObjective& objective_;
  double centre_, half_;
  bool& failed_;
};

// f(α, r) at γ = (1/4 + α)·r; nullopt where the solve fails.
using AlphaRFunction = std::function<std::optional<double>(double, double)>;

// Where the 2-D search starts (α, r = γ/(1/4 + α)) and whether the objective is flat over the
// triangle. Flat in α at γ = 0 does not make it flat in γ (i² − j² on a 3 × 5 net: every α
// reproduces it at γ = 0, but not the masks with γ ≠ 0): γ is probed over the triangle before
// saying so.
struct GammaStart {
  double alpha = 0, r = 0;
  bool flat = false;
};

GammaStart probe_gamma(const AlphaRFunction& f, const AlphaSearchSummary& one, double lower, double upper,
                       double flat_tolerance) {
  GammaStart start{one.parameter.value_or(0.5 * (lower + upper)), 0, false};
  if (!one.flat) return start;
  double best = one.value, lo = one.value, hi = one.value;
  for (const double a : {lower + 0.1 * (upper - lower), 0.5 * (lower + upper), upper})
    for (const double r : {-0.9, -0.5, 0.5, 0.9})
      if (const auto v = f(a, r)) {
        lo = std::min(lo, *v);
        hi = std::max(hi, *v);
        if (*v < best) {
          best = *v;
          start.alpha = a;
          start.r = r;
        }
      }
  // (the α search's rounding floor: an objective that is 0 for every mask varies by rounding, and
  // 4e-32 against 1e-31 read as an optimum of the bundled sixteen_vector_twist)
  start.flat = hi - lo <= flat_tolerance * std::max({std::abs(hi), std::abs(lo), one.rounding_floor, 1e-300});
  return start;
}

// Polish by coordinate searches (Brent in α at fixed r, then in r at fixed α) on the closed box
// [lower, upper] × [−kShrink, kShrink], then its ends (Brent never evaluates an end): near the
// box's edges the tanh map flattens the gradient, and Ceres stopped on the edge
// |γ| = 0.999(1/4 + α) at (0.2036, 0.4532) with 2.57269 where (0.25, 0.45303) has 2.56598.
void polish_on_box(const AlphaRFunction& f, const bool& failed, double lower, double upper, double& alpha, double& r,
                   std::optional<double>& value) {
  constexpr double kShrink = AlphaGammaFunction::kShrink;
  for (int round = 0; round < 8 && value && !failed; ++round) {
    const double before = *value;
    const auto along = [&](auto g, double lo, double hi) {
      const auto [x, fx] =
          boost::math::tools::brent_find_minima([&](double v) { return g(v).value_or(HUGE_VAL); }, lo, hi, 40);
      return std::pair{x, fx};
    };
    if (const auto [a, fa] = along([&](double a) { return f(a, r); }, lower, upper); fa < *value) {
      alpha = a;
      value = fa;
    }
    if (const auto [rr, fr] = along([&](double x) { return f(alpha, x); }, -kShrink, kShrink); fr < *value) {
      r = rr;
      value = fr;
    }
    if (!(before - *value > 1e-12 * std::abs(before))) break;
  }
  for (const double a : {lower, upper})
    if (const auto v = f(a, r); v && value && *v < *value) {
      alpha = a;
      value = v;
    }
  for (const double rr : {-kShrink, kShrink})
    if (const auto v = f(alpha, rr); v && value && *v < *value) {
      r = rr;
      value = v;
    }
}

}  // namespace

AlphaGammaSummary search_alpha_gamma(MaskObjective& objective, const AlphaSearchOptions& options) {
  AlphaGammaSummary out;
  const AlphaSearchSummary one = search_mask_parameter(objective, options);
  out.evaluations = one.evaluations;
  out.solves = one.solves;
  if (one.status == SearchStatus::kSolverFailed || one.status == SearchStatus::kFailedRegion) {
    out.status = one.status;
    out.message = one.message;
    return out;
  }
  out.value_at_gamma0 = one.value;
  const double lower = std::max(options.lower, -0.25), upper = std::min(options.upper, 0.25);
  const double centre = 0.5 * (lower + upper), half = 0.5 * (upper - lower);
  constexpr double kShrink = AlphaGammaFunction::kShrink;
  // f at (α, r): γ = (1/4 + α)·r, |r| ≤ kShrink (the triangle where the operator is definite on
  // every grid); nullopt where the solve fails
  bool failed = false;
  const AlphaRFunction f = [&](double alpha, double r) -> std::optional<double> {
    const double gamma = (0.25 + alpha) * r;
    std::vector<double> g;
    const auto e = objective.evaluate_mask(symmetric_mask(alpha, gamma), {}, g);
    if (!e.ok()) {
      failed = true;
      return std::nullopt;
    }
    return e.value;
  };
  const GammaStart start = probe_gamma(f, one, lower, upper, options.flat_tolerance);
  if (start.flat) {
    out.status = SearchStatus::kFlat;
    out.flat = true;
    out.value = one.value;
    out.message = "flat in alpha and gamma (gamma probed at 12 points of the definite triangle)";
    out.evaluations = objective.evaluations();
    out.solves = objective.solves();
    return out;
  }
  double t[2] = {std::atanh(std::clamp((start.alpha - centre) / half, -0.999, 0.999)),
                 std::atanh(std::clamp(start.r / kShrink, -0.999, 0.999))};
  auto* function = new AlphaGammaFunction(objective, centre, half, failed);
  ceres::GradientProblem problem(function);
  ceres::GradientProblemSolver::Summary summary;
  ceres::Solve(ceres_options(options), problem, t, &summary);
  out.ceres_report = summary.BriefReport();
  const std::pair<double, double> mapped = function->map(t);
  double alpha = mapped.first, gamma = mapped.second;
  double r = gamma / (0.25 + alpha);
  std::optional<double> value = f(alpha, r);
  polish_on_box(f, failed, lower, upper, alpha, r, value);
  gamma = (0.25 + alpha) * r;
  out.evaluations = objective.evaluations();
  out.solves = objective.solves();
  if (failed || !value) {
    out.status = SearchStatus::kSolverFailed;
    out.message = "solver failed during the (alpha, gamma) refinement";
    return out;
  }
  out.alpha = alpha;
  out.gamma = gamma;
  out.value = *value;
  out.at_bound = lies_on_bound(alpha, lower, upper) || std::abs(r) >= kShrink * (1 - 1e-7);
  if (!one.flat && one.value < *value) {  // never report a worse point than the symmetric optimum
    out.alpha = *one.parameter;
    out.gamma = 0;
    out.value = one.value;
    out.at_bound = one.at_bound;
  }
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    out.status = SearchStatus::kNotConverged;
    out.message = "Ceres: " + summary.message;
  }
  // On γ = 0 a boundary whose symmetric family is flat has a line of optima: α* is any α of the
  // bounds (the saddle's thin plate is 128 for every α at γ = 0 and rises with |γ|).
  if (one.flat && std::abs(out.gamma) <= 1e-12 * (0.25 + std::abs(out.alpha))) {
    out.message += std::string(out.message.empty() ? "" : "; ") +
                   "flat in alpha along gamma = 0 (the symmetric family does not depend on alpha): gamma = 0 is the "
                   "optimum, alpha is not determined";
  }
  return out;
}

}  // namespace coons
