// The limit of a sequence μ*(n) as the degree n grows: least-squares fits of candidate forms
// (μ∞ + a/n, μ∞ + a/n², μ∞ + a/n + b/n², μ∞ + a·n^−p with p free), a Richardson-type
// extrapolation of μ∞ from the last three points with its error estimate, the observed rate p of
// μ* − μ∞ ≈ a·n^−p (from each triple of successive points), and the degree from which μ* stays
// within 5 % and 1 % of μ∞. Pure functions of the (n, μ) pairs; the caller leaves out degrees
// without an interior optimum (flat or on a bound).
// Based on: L. F. Richardson, The deferred approach to the limit, Phil. Trans. A 226 (1927);
// A. C. Aitken's Δ² process for an unknown rate (here with unequal steps in n).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace coons {

struct DegreeLimitOptions {
  int fit_from_degree = 8;                        //!< the fits use the points with n ≥ this (the asymptotic range)
  double min_rate = 0.05, max_rate = 8;           //!< range of the exponent p searched and accepted
  std::vector<double> tolerances = {0.05, 0.01};  //!< relative distances to μ∞ for within_from

  bool is_valid(std::string* why) const;
};

//! One candidate form, fitted by least squares over the points with n ≥ fit_from_degree.
struct LimitFit {
  std::string form;                                        //!< "mu_inf + a/n", ...
  std::vector<std::pair<std::string, double>> parameters;  //!< ("mu_inf", .), ("a", .), ("b" or "p", .)
  double residual = 0;  //!< root-mean-square relative residual |μ − fit|/|μ| over the points used
  int points = 0;
  //! `mu_inf + a*n^-p` only: p stopped at an end of the range searched, [min_rate, max_rate], so
  //! the residual may fall further beyond it (an oscillating sequence stopped at p = 8).
  bool at_bound = false;
};

//! kSuccess: an extrapolated limit (claimed only with an error estimate small enough:
//! limit_claimed); kTooFewPoints: fewer than three points (no extrapolation; fits that have enough
//! points are still given); kNotMonotone: the differences of the last three points change sign (or
//! one vanishes); kRateOutOfRange: they keep their sign but do not shrink as n^−p with p in
//! [min_rate, max_rate] would make them (μ* = 595, 21.3, 14.2 at n = 3, 4, 5 falls strictly). No
//! rate and no limit without kSuccess.
enum class DegreeLimitStatus { kSuccess, kTooFewPoints, kNotMonotone, kRateOutOfRange };
//! "success", "too_few_points", "not_monotone", "rate_out_of_range"
const char* to_string(DegreeLimitStatus status);

struct DegreeLimitResult {
  DegreeLimitStatus status = DegreeLimitStatus::kSuccess;
  std::string message;
  std::vector<LimitFit> fits;
  std::optional<double> limit;  //!< μ∞ from the last triple of points
  //! max |μ∞ − other| over the free-rate fit's μ∞, the μ∞ + a/n + b/n² fit's and μ∞(the triple
  //! before): an estimate, not a bound; nullopt (and `message` says why) with fewer than four
  //! points at n ≥ fit_from_degree, where those fits have no check of their own
  std::optional<double> limit_error;
  std::optional<double> rate;  //!< p from the last triple
  //! (the largest n of the triple, p) for every triple of successive points that has a rate
  std::vector<std::pair<int, double>> rates;
  //! per tolerance: the smallest n from which every point is within it of μ∞ (nullopt: not yet
  //! within at the largest n, or no limit)
  std::vector<std::optional<int>> within_from;
  std::vector<double> tolerances;  //!< the relative tolerance of each within_from (DegreeLimitOptions)
};

//! The relative error estimate up to which a limit is claimed (the report's ClaimThresholds).
inline constexpr double kLimitClaimError = 0.05;

//! Whether the extrapolated limit is claimed: it exists and has an error estimate ≤
//! relative_error·|μ∞|. A kSuccess limit without one (too few degrees, or degrees spanning too
//! little: `message` says which) is reported but not claimed.
bool limit_claimed(const DegreeLimitResult& r, double relative_error = kLimitClaimError);

//! The exponent p with (y3 − y2)/(y2 − y1) = (n3^−p − n2^−p)/(n2^−p − n1^−p) for n1 < n2 < n3, and
//! the limit y∞ of the curve y∞ + a·n^−p through the three points; nullopt when the differences
//! change sign, do not shrink fast enough for a p in [min_rate, max_rate], or vanish.
struct TripleLimit {
  double rate = 0, limit = 0;
};
std::optional<TripleLimit> triple_limit(int n1, double y1, int n2, double y2, int n3, double y3, double min_rate,
                                        double max_rate);

//! Least-squares fit of y ≈ Σ c_k·n^−e_k (e_0 = 0 gives the constant μ∞), relative residual.
LimitFit fit_inverse_powers(const std::vector<std::pair<int, double>>& points, const std::vector<double>& exponents,
                            const std::string& form);

//! Points (n, μ*(n)) with increasing n, each n once.
DegreeLimitResult fit_degree_limit(const std::vector<std::pair<int, double>>& points,
                                   const DegreeLimitOptions& options = {});

}  // namespace coons
