// The search for the best mask parameter (α, μ, ...) of a boundary, by Ceres with the analytic
// derivative. The search scans a coarse grid first (so that several minima are seen), then
// refines the best grid point, and every other minimum of the scan, inside the bracket of its
// neighbours and keeps the lowest result, and reports a flat objective and an optimum on a bound
// as such. Bounds holding singular α of the α family (poles of the objective) are searched one
// interval between poles at a time (search_impl.h). Two evaluators:
// - MaskObjective, any family and objective: for each parameter value one factorisation, two
//   solves (the net N and its sensitivity dN/dp = A⁻¹·[dmask-weighted neighbour sums of N],
//   docs/math.md §3) and the objective's exact value and derivative; refined by Ceres's line-search
//   minimiser.
// - SpectralAlphaSearchObjective (spectral_objective.h), the α family with any objective: no solve
//   at all, f, f' and f'' in the sine basis; refined by Ceres's trust region on f' = 0.
// search_alpha picks the second whenever it applies. Both evaluate in the normalised frame of the
// boundary (normalised_frame.h), so that the optimum does not depend on where the boundary lies or
// how large it is. No optimum without its evidence: an optimum (or a flat verdict) that rests on a
// failed evaluation is not claimed (SearchStatus::kFailedRegion, search_failures.h).
// Units: mask_objective.* (the solve-based evaluator), alpha_search.cpp (the search's steps),
// ceres_refinement.h, search_failures.*, alpha_gamma_search.cpp.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700; Ceres Solver's
// GradientProblemSolver and Problem (S. Agarwal, K. Mierle et al.).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/mask_objective.h"
#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "coons/config.h"
#include "coons/mask/mask_families.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

//! The most points a coarse scan may have (a grid before Ceres refines; not a sweep).
inline constexpr int kMaxScanPoints = 10001;

struct AlphaSearchOptions {
  double lower = -0.25, upper = 0.25;  //!< bounds of the parameter
  int scan_points = 9;                 //!< coarse grid, bounds included, in [3, kMaxScanPoints]
  double flat_tolerance = 1e-12;       //!< relative range below which the objective is flat
  double parameter_tolerance = 1e-10;  //!< Ceres: stop when the step is below this (in the bracket)
  int max_iterations = 100;            //!< Ceres iterations

  bool is_valid(std::string* why) const;
};

//! The member of AlphaSearchOptions at fault, so that a caller can name what set it; kBounds:
//! lower < upper fails (both are finite and within ±kMaxAlpha).
enum class SearchOptionsField {
  kNone,
  kLower,
  kUpper,
  kBounds,
  kScanPoints,
  kFlatTolerance,
  kParameterTolerance,
  kMaxIterations
};

struct SearchOptionsProblem {
  SearchOptionsField field = SearchOptionsField::kNone;
  std::string reason;  //!< without the member's name: "must be in [3, 10001]"
};

//! The first rule of AlphaSearchOptions::is_valid that `options` breaks (field kNone: none).
SearchOptionsProblem options_problem(const AlphaSearchOptions& options);
//! The member's name: "lower", "upper", "bounds", "scan_points", … ("" for kNone).
const char* to_string(SearchOptionsField field);

//! kSuccess: an optimum (parameter) resting only on successful evaluations; kFlat: no optimum,
//! the objective does not depend on the parameter; kSolverFailed: no evaluation succeeded, or the
//! one at the refined optimum failed; kNotConverged: Ceres or the refinement did not converge;
//! kFailedRegion: some evaluations failed where the optimum (or the flatness) would rest on them
//! — next to the lowest successful point, or anywhere when the rest is flat — so none is claimed;
//! kNotApplicable: the problem does not fit the family (e.g. one data ring for the 5×5 C1
//! family, family_search.h); nothing was evaluated.
enum class SearchStatus { kSuccess, kFlat, kSolverFailed, kNotConverged, kFailedRegion, kNotApplicable };
//! "success", "flat", "solver_failed", "not_converged", "failed_region", "not_applicable".
const char* to_string(SearchStatus status);

//! Whether `parameter` lies on a bound of [lower, upper] as the searches decide at_bound: within
//! 1e-7 of the interval's length, or of the bound's own size when that is smaller and above 1 (a
//! minimum on the bound is approached from inside: the twist energy's, the Coons net at α = −1/4,
//! came back 9e-10 inside on a degree-5 boundary; over [−0.3, 1e8] the interval's length put α* =
//! −0.0185 "on" the bound −0.3).
inline bool lies_on_bound(double parameter, double lower, double upper) {
  const auto near = [&](double bound) {
    return std::abs(parameter - bound) <= 1e-7 * std::min(upper - lower, std::max(1.0, std::abs(bound)));
  };
  return near(lower) || near(upper);
}

//! Intervals wider than this are scanned uniformly in asinh(parameter / kWideScanScale), not in
//! the parameter itself (scan_point): the α family's objectives vary on the scale of 1/4 and tend
//! to a limit as |α| grows, so a linear scan of [−0.3, 1e12] put one point below 1e11 and missed
//! the minimum at −0.0185.
inline constexpr double kWideScanWidth = 4;
inline constexpr double kWideScanScale = 0.25;

//! Point i of a scan of k ≥ 2 points over [lower, upper], both bounds included exactly: uniform in
//! the parameter, or on intervals wider than kWideScanWidth uniform in asinh(parameter / kWideScanScale).
inline double scan_point(double lower, double upper, int k, int i) {
  if (i <= 0) return lower;
  if (i + 1 >= k) return upper;
  if (!(upper - lower > kWideScanWidth)) return lower + i * ((upper - lower) / (k - 1));
  const double a = std::asinh(lower / kWideScanScale), b = std::asinh(upper / kWideScanScale);
  return std::clamp(kWideScanScale * std::sinh(a + i * ((b - a) / (k - 1))), lower, upper);
}

struct AlphaSearchSummary {
  SearchStatus status = SearchStatus::kSuccess;
  std::string message;
  std::optional<double> parameter;  //!< the optimum (absent when flat or failed)
  //! The objective at the optimum; when flat, at the best scan point; with kFailedRegion, the
  //! lowest successful evaluation (not an optimum); NaN (reported as null) when no evaluation
  //! succeeded.
  double value = std::numeric_limits<double>::quiet_NaN();
  bool flat = false, at_bound = false;
  //! The objective's rounding scale, the floor of the flat test (a range below flat_tolerance
  //! times the larger of it and the values is flat): 0 until the scan has run.
  double rounding_floor = 0;
  int local_minima = 0;  //!< interior local minima seen by the scan
  int evaluations = 0, solves = 0;
  //! (parameter, value) of the coarse grid; a failed point's value is +∞ (HUGE_VAL)
  std::vector<std::pair<double, double>> scan;
  //! Evaluations (scan and refinement) whose solve failed; the status of the first of them.
  int failed_evaluations = 0;
  solvers::SolveStatus first_failure = solvers::SolveStatus::kSuccess;
  //! [lowest, highest] parameter of each run of failed evaluations with no successful one
  //! between them, in increasing order (a single failed point is [p, p]).
  std::vector<std::pair<double, double>> failed_intervals;
  double seconds = 0;
  std::string ceres_report;  //!< Ceres's BriefReport of the refinement, if any
  std::string evaluator;     //!< "sine basis" or "factorize and solve" (search_alpha)

  [[nodiscard]] std::string brief_report() const;
};

AlphaSearchSummary search_mask_parameter(MaskObjective& objective, const AlphaSearchOptions& options = {});

#if COONS_HAVE_FFTW
class SpectralAlphaSearchObjective;
//! The same search on the α family, evaluated in the sine basis (no
//! solves; see spectral_objective.h).
AlphaSearchSummary search_mask_parameter(SpectralAlphaSearchObjective& objective,
                                         const AlphaSearchOptions& options = {});
#endif

//! The search over the α family with the cheapest exact evaluator: the sine basis (no solve per
//! evaluation; spectral_objective.h) when FFTW is built, `solver` names a structured backend,
//! m, n ≥ 2 (any objective); otherwise a factorisation and solves per evaluation (MaskObjective).
//! `solver` is a backend of the registry.
AlphaSearchSummary search_alpha(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                                const AlphaSearchOptions& options = {},
                                const solvers::SolverOptions& solver_options = {});

//! The search over μ on the compressed scale s = μ/(μ + mn) (mu_family_compressed; bounds and
//! the result in s). For m = n that scale is α itself, s = 1 + 4α (docs/math.md §4), so the search runs
//! as search_alpha does, in the sine basis where it applies, and maps back; for m ≠ n (the
//! anisotropic masks) it factorizes and solves per evaluation.
AlphaSearchSummary search_mu(const Boundary& boundary, const Objective& objective, const solvers::SolverInfo& solver,
                             const AlphaSearchOptions& options, const solvers::SolverOptions& solver_options = {});

//! The two-parameter symmetric family (α, γ): e_i = 1/4 − α + γ, e_j = 1/4 − α − γ, d = α, i.e.
//! every affine-invariant symmetric 3×3 mask (4α + 2β_i + 2β_j = 1). The operator is positive
//! definite for α ∈ [−1/4, 1/4], |γ| < 1/4 + α; the search stays inside. It starts from the best
//! α at γ = 0 (a 1-D search) and refines both with Ceres.
struct AlphaGammaSummary {
  SearchStatus status = SearchStatus::kSuccess;
  std::string message;
  double alpha = 0, gamma = 0, value = 0;
  double value_at_gamma0 = 0;  //!< the best of the symmetric family, for comparison
  bool flat = false;
  bool at_bound = false;  //!< α* on a bound of the search interval (within 1e-7 of its length)
  int evaluations = 0, solves = 0;
  std::string ceres_report;
};
AlphaGammaSummary search_alpha_gamma(MaskObjective& objective, const AlphaSearchOptions& options = {});

}  // namespace coons
