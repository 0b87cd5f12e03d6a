#include "alpha_search.h"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

#include "coons/alpha/search_impl.h"
#include "coons/config.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "coons/mask/near_singular.h"
#include "coons/net/control_net.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif
#include "solvers/registry.h"

namespace coons {

SearchOptionsProblem options_problem(const AlphaSearchOptions& o) {
  using F = SearchOptionsField;
  if (!std::isfinite(o.lower)) return {F::kLower, "must be a finite number"};
  if (!std::isfinite(o.upper)) return {F::kUpper, "must be a finite number"};
  // (±1e308 passed the finiteness test, and the scan's step (upper − lower)/k overflowed to a NaN α)
  static_assert(kMaxAlpha == 1e60, "the messages below name kMaxAlpha");
  if (std::abs(o.lower) > kMaxAlpha) return {F::kLower, "must lie in [-1e60, 1e60]"};
  if (std::abs(o.upper) > kMaxAlpha) return {F::kUpper, "must lie in [-1e60, 1e60]"};
  if (!(o.lower < o.upper)) return {F::kBounds, fmt::format("need lower < upper, not {} and {}", o.lower, o.upper)};
  // a scan is a coarse grid before the refinement: --scan 1e8 ran for minutes and 7 GB
  if (o.scan_points < 3 || o.scan_points > kMaxScanPoints)
    return {F::kScanPoints, fmt::format("must be in [3, {}], not {}", kMaxScanPoints, o.scan_points)};
  if (!(o.flat_tolerance > 0)) return {F::kFlatTolerance, "must be positive"};
  if (!(o.parameter_tolerance > 0)) return {F::kParameterTolerance, "must be positive"};
  if (o.max_iterations < 1) return {F::kMaxIterations, "must be at least 1"};
  return {};
}

const char* to_string(SearchOptionsField field) {
  switch (field) {
    case SearchOptionsField::kNone:
      return "";
    case SearchOptionsField::kLower:
      return "lower";
    case SearchOptionsField::kUpper:
      return "upper";
    case SearchOptionsField::kBounds:
      return "bounds";
    case SearchOptionsField::kScanPoints:
      return "scan_points";
    case SearchOptionsField::kFlatTolerance:
      return "flat_tolerance";
    case SearchOptionsField::kParameterTolerance:
      return "parameter_tolerance";
    case SearchOptionsField::kMaxIterations:
      return "max_iterations";
  }
  return "unknown";
}

bool AlphaSearchOptions::is_valid(std::string* why) const {
  const SearchOptionsProblem problem = options_problem(*this);
  if (problem.field == SearchOptionsField::kNone) return true;
  if (why) *why = std::string(to_string(problem.field)) + " " + problem.reason;
  return false;
}

const char* to_string(SearchStatus s) {
  switch (s) {
    case SearchStatus::kSuccess:
      return "success";
    case SearchStatus::kFlat:
      return "flat";
    case SearchStatus::kSolverFailed:
      return "solver_failed";
    case SearchStatus::kNotConverged:
      return "not_converged";
    case SearchStatus::kFailedRegion:
      return "failed_region";
    case SearchStatus::kNotApplicable:
      return "not_applicable";
  }
  return "solver_failed";
}

std::string AlphaSearchSummary::brief_report() const {
  std::ostringstream out;
  out << to_string(status);
  if (parameter) out << ": optimum " << *parameter << ", value " << value;
  if (flat) out << " (flat objective)";
  if (at_bound) out << " (at a bound)";
  if (failed_evaluations > 0) out << ", " << failed_evaluations << " failed evaluation(s)";
  out << ", " << evaluations << " evaluations, " << solves << " solves, " << seconds << " s";
  if (!message.empty()) out << "; " << message;
  return out.str();
}

AlphaSearchSummary search_mask_parameter(MaskObjective& objective, const AlphaSearchOptions& options) {
  return detail::search_impl(objective, options);
}

namespace {

// Whether the ring data of b excite a mode whose eigenvalue vanishes at the singular α: the
// right-hand side b(α) has a sine coefficient there above 1e-5 of its norm, so that the net, and
// the objective, have a pole at α that reaches beyond the near-singular evaluations the search
// refuses (ratio ≤ 1e-6). A threshold of 1e-8 counted the rounding of symmetric files written
// with 7 digits, or moved by 1e9, as poles (coefficients 1e-7 to 2e-6): 24 of 364 such runs
// went from success to failed_region. A symmetric boundary leaves some modes alone (the
// dome's thin plate is smooth through α = 1/2); searched as poles, the interval's optimum sat at
// its end next to one, closer and closer, until the near-singular evaluations there made it a
// failed_region.
bool excites_pole(const Boundary& b, double alpha) {
  const int m = b.m, n = b.n;
  if (m < 2 || n < 2) return false;
  const Mask9 mask = alpha_mask(alpha);
  const Eigen::MatrixX3d B = mask_rhs(frame_net(b), mask);
  const double scale = B.norm();
  if (!(scale > 0)) return false;
  for (int p = 1; p < m; ++p) {
    const double cp = std::cos(M_PI * p / m);
    for (int q = 1; q < n; ++q) {
      const double cq = std::cos(M_PI * q / n);
      if (std::abs(mask9_eigenvalue(mask, cp, cq)) > 1e-9) continue;  // not a mode that vanishes here
      // the normalised sine coefficient Σ_ij B_ij s_i t_j (B is zero off the ring next to the frame)
      Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
      const double norm = 2 / std::sqrt(double(m) * n);
      for (int i = 1; i < m; ++i)
        for (int j = 1; j < n; ++j) {
          if (i != 1 && i != m - 1 && j != 1 && j != n - 1) continue;
          c += std::sin(M_PI * p * i / m) * std::sin(M_PI * q * j / n) * B.row(Eigen::Index(i - 1) * (n - 1) + (j - 1));
        }
      if ((norm * c).cwiseAbs().maxCoeff() > 1e-5 * scale) return true;
    }
  }
  return false;
}

// An α-family evaluator that does not evaluate at a (near-)singular α. Inside [−1/4, 1/4] the
// system is positive definite and every α is evaluated; outside (--allow-indefinite), an α whose
// mask system on the boundary's (m−1)×(n−1) interior has mask9_eigenvalue_ratio ≤
// kNearSingularEigenvalueRatio is a failed evaluation (singular), never a value computed from that system,
// so the search's failure machinery (failed_intervals, failed_region) reports it and no optimum is
// claimed there. (The same criterion on the other problems, estimated: near_singular.h.)
template <class Obj>
class RegularAlphas {
 public:
  using Evaluation = typename Obj::Evaluation;
  RegularAlphas(Obj& objective, const Boundary& boundary) : objective_(objective), m_(boundary.m), n_(boundary.n) {}
  Evaluation evaluate(double alpha, bool with_derivative = true) {
    const double ratio = alpha >= -0.25 && alpha <= 0.25 ? 1.0 : mask9_eigenvalue_ratio(alpha_mask(alpha), m_, n_);
    if (ratio > kNearSingularEigenvalueRatio) return objective_.evaluate(alpha, with_derivative);
    ++refused_;
    Evaluation e;
    e.parameter = alpha;
    e.has_derivative = false;
    e.summary = near_singular_summary(ratio, "closed-form eigenvalues");
    return e;
  }
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return objective_.unit_frame(); }
  [[nodiscard]] int evaluations() const { return objective_.evaluations() + refused_; }
  [[nodiscard]] int solves() const { return objective_.solves(); }
  [[nodiscard]] static double scale_origin() { return Obj::scale_origin(); }
  //! The singular α inside the bounds where the boundary excites the vanishing mode, so that the
  //! objective has a pole (search_impl.h searches between them one interval at a time); all of
  //! them, unchecked, when there are more than kMaxSingularIntervals.
  [[nodiscard]] std::vector<double> singular_parameters(double lower, double upper) const {
    std::vector<double> alphas = alpha_family_singular_alphas(m_, n_, lower, upper);
    if (alphas.size() > detail::kMaxSingularIntervals) return alphas;
    const Boundary& b = objective_.unit_frame().boundary;
    alphas.erase(std::remove_if(alphas.begin(), alphas.end(), [&](double a) { return !excites_pole(b, a); }),
                 alphas.end());
    return alphas;
  }

 private:
  Obj& objective_;
  int m_, n_;
  int refused_ = 0;
};

// The search of the α family through RegularAlphas.
template <class Obj>
AlphaSearchSummary search_regular_alphas(Obj& objective, const Boundary& boundary, const AlphaSearchOptions& options) {
  RegularAlphas<Obj> regular(objective, boundary);
  return detail::search_impl(regular, options);
}

// The fallback of search_mu on a non-square net: a factorisation and solves per evaluation (the α
// family's fallback, in search_alpha, goes through RegularAlphas).
AlphaSearchSummary search_by_solving(const Boundary& boundary, const Objective& objective, MaskFamily family,
                                     const solvers::SolverInfo& solver, const AlphaSearchOptions& options,
                                     const solvers::SolverOptions& solver_options) {
  MaskObjective f(boundary, objective, std::move(family), solver, solver_options);
  AlphaSearchSummary s = detail::search_impl(f, options);
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
    AlphaSearchSummary s = search_regular_alphas(f, boundary, options);
    s.evaluator = "sine basis";
    return s;
  }
#endif
  MaskObjective f(
      boundary, objective, [](double a) { return alpha_family(a); }, solver, solver_options);
  AlphaSearchSummary s = search_regular_alphas(f, boundary, options);
  s.evaluator = "factorize and solve";
  return s;
}

AlphaSearchSummary search_mu(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                             const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options) {
  if (boundary.m == boundary.n) {
    AlphaSearchOptions on_alpha = options;
    on_alpha.lower = (options.lower - 1) / 4;
    on_alpha.upper = (options.upper - 1) / 4;
    AlphaSearchSummary s = search_alpha(boundary, objective, solver, on_alpha, solver_options);
    // back to s = 1 + 4α, the bounds exactly: (s − 1)/4 and back rounds (the scan of μ over [5, 6]
    // began at 5.000000000000002, and one over [1e-300, 2e-300] ended at 1e-300)
    const auto to_s = [&](double alpha) {
      return alpha == on_alpha.lower ? options.lower : alpha == on_alpha.upper ? options.upper : 1 + 4 * alpha;
    };
    if (s.parameter) s.parameter = to_s(*s.parameter);
    for (auto& point : s.scan) point.first = to_s(point.first);
    if (!s.scan.empty()) {  // the scan holds both bounds, also where they are one α
      s.scan.front().first = options.lower;
      s.scan.back().first = options.upper;
    }
    for (auto& run : s.failed_intervals) run = {to_s(run.first), to_s(run.second)};
    if (!s.message.empty()) s.message += " (parameters in this message are alpha = (s - 1)/4)";
    return s;
  }
  return search_by_solving(
      boundary, objective, [m = boundary.m, n = boundary.n](double t) { return mu_family_compressed(m, n, t); }, solver,
      options, solver_options);
}

#if COONS_HAVE_FFTW
AlphaSearchSummary search_mask_parameter(SpectralAlphaSearchObjective& objective, const AlphaSearchOptions& options) {
  return detail::search_impl(objective, options);
}
#endif

}  // namespace coons
