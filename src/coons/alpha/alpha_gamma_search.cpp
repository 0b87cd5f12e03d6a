// The two-parameter symmetric family (α, γ) of alpha_search.h: a 1-D α search at γ = 0, then
// Ceres's line search in both, inside the triangle where the operator is definite.
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/ceres_refinement.h"

namespace coons {
namespace {

using detail::ceres_options;

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
  const double edge_tolerance = 1e-7 * (upper - lower);
  out.at_bound = std::abs(alpha - lower) <= edge_tolerance || std::abs(alpha - upper) <= edge_tolerance;
  if (one.value < e.value) {  // never report a worse point than the symmetric optimum
    out.alpha = *one.parameter;
    out.gamma = 0;
    out.value = one.value;
    out.at_bound = one.at_bound;
  }
  if (summary.termination_type == ceres::NO_CONVERGENCE) {
    out.status = SearchStatus::kNotConverged;
    out.message = "Ceres: " + summary.message;
  }
  return out;
}

}  // namespace coons
