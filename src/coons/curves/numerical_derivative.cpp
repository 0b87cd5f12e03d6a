#include "numerical_derivative.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace coons {

namespace {

constexpr int kRows = 12;
constexpr double kShrink = 1.4;
constexpr double kSafe = 2.0;

bool finite(const Eigen::RowVector3d& x) { return x.allFinite(); }

// Central difference of order r with step h; NaN row when a sample is not finite.
Eigen::RowVector3d central(const std::function<Eigen::RowVector3d(double)>& f, int r, double s, double h) {
  Eigen::RowVector3d d;
  switch (r) {
    case 1:
      d = (f(s + h) - f(s - h)) / (2 * h);
      break;
    case 2:
      d = (f(s + h) - 2 * f(s) + f(s - h)) / (h * h);
      break;
    default:
      d = (f(s + 2 * h) - 2 * f(s + h) + 2 * f(s - h) - f(s - 2 * h)) / (2 * h * h * h);
      break;
  }
  return d;
}

// r-th forward (dir = +1) or backward (dir = −1) difference divided by h^r.
Eigen::RowVector3d one_sided(const std::function<Eigen::RowVector3d(double)>& f, int r, double s, double h, int dir) {
  static const double binomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
  for (int k = 0; k <= r; ++k) {
    const double sign = ((r - k) % 2 == 0) ? 1.0 : -1.0;
    d += sign * binomial[r][k] * f(s + dir * k * h);
  }
  return d / std::pow(dir * h, r);
}

// Ridders' tableau; `ratio` is the factor by which the leading error term shrinks per row
// (kShrink² for central differences, kShrink for one-sided ones).
template <class D>
NumericalDerivative tableau(D difference, double h0, double ratio, bool* broke_on_nonfinite) {
  Eigen::RowVector3d T[kRows][kRows];
  NumericalDerivative best;
  best.error_estimate = std::numeric_limits<double>::infinity();
  double h = h0;
  *broke_on_nonfinite = false;
  for (int i = 0; i < kRows; ++i, h /= kShrink) {
    T[i][0] = difference(h);
    if (!finite(T[i][0])) {
      *broke_on_nonfinite = true;
      return best;
    }
    double factor = ratio;
    for (int k = 1; k <= i; ++k, factor *= ratio) {
      T[i][k] = (factor * T[i][k - 1] - T[i - 1][k - 1]) / (factor - 1);
      const double err =
          std::max((T[i][k] - T[i][k - 1]).cwiseAbs().maxCoeff(), (T[i][k] - T[i - 1][k - 1]).cwiseAbs().maxCoeff());
      if (err <= best.error_estimate) {
        best.error_estimate = err;
        best.value = T[i][k];
        best.step = h;
        best.column = k;
      }
    }
    if (i > 0 && (T[i][i] - T[i - 1][i - 1]).cwiseAbs().maxCoeff() >= kSafe * best.error_estimate) break;
  }
  return best;
}

// Ridders' tableau from h0, h0/4, h0/16, …: a first step too large for the function's scale can
// give a confident but wrong value, so a result counts only when the tableau from the next
// smaller start agrees with it (to 1e-7 relative). Returns the better of the first agreeing pair
// (the disagreement folded into its error estimate). When none of the first four (down to h0/64)
// agree, the fourth with its disagreement folded in is the fallback, and starts go on to h0/4⁷: an
// agreeing pair there counts if it lies within the fallback's error estimate (times 10) of the
// fallback's value. With four starts sin(1000 t)/1000 had no agreeing pair and no derivative at
// all (its fallback's estimate is large); the values of a curve at 1e8, quantised in steps of
// 1.5e-8, give the smaller starts equal wrong second differences that agree, far from a fallback
// that rounding spoils by about 1 % (derivative()'s test may accept that as rounding).
template <class D>
NumericalDerivative consistent(D difference, double h0, double ratio, bool* nonfinite) {
  constexpr int kStarts = 8, kFallback = 4;
  NumericalDerivative previous = tableau(difference, h0, ratio, nonfinite);
  if (*nonfinite) return previous;
  NumericalDerivative fallback;
  for (int k = 1; k < kStarts; ++k) {
    h0 /= 4;
    NumericalDerivative current = tableau(difference, h0, ratio, nonfinite);
    if (*nonfinite) return k < kFallback ? current : fallback;
    const double disagreement = (current.value - previous.value).cwiseAbs().maxCoeff();
    const double scale = std::max(1.0, current.value.cwiseAbs().maxCoeff());
    if (disagreement <= 1e-7 * scale) {
      NumericalDerivative& best = current.error_estimate <= previous.error_estimate ? current : previous;
      best.error_estimate = std::max(best.error_estimate, disagreement);
      if (k >= kFallback && !((best.value - fallback.value).cwiseAbs().maxCoeff() <= 10 * fallback.error_estimate))
        return fallback;
      return best;
    }
    if (k == kFallback - 1) {
      fallback = current;
      fallback.error_estimate = std::max(fallback.error_estimate, disagreement);
    }
    previous = current;
  }
  return fallback;
}

}  // namespace

NumericalDerivative numerical_derivative(const std::function<Eigen::RowVector3d(double)>& function, int r, double s,
                                         double h0, double domain_lo, double domain_hi) {
  assert(r >= 1 && r <= 3);
  if (h0 <= 0) h0 = 0.1;
  double largest = 0;  // max |f| over the finite samples
  const std::function<Eigen::RowVector3d(double)> f = [&](double x) {
    Eigen::RowVector3d v = function(x);
    if (v.allFinite()) largest = std::max(largest, v.cwiseAbs().maxCoeff());
    return v;
  };
  // the sum of |weights| of the differences above: central 1/h, 4/h², 3/h³; one-sided 2^r/h^r
  auto with_rounding = [&](NumericalDerivative d, bool central_weights) {
    static const double central_sum[4] = {0, 1, 4, 3};
    const double weights = (central_weights ? central_sum[r] : std::pow(2.0, r)) / std::pow(d.step, r);
    d.rounding = std::numeric_limits<double>::epsilon() * largest * weights * std::pow(3.0, d.column);
    return d;
  };
  auto centred = [&](double h) { return central(f, r, s, h); };
  // Differences that stay in the domain: central ones from the room left inside it, else
  // one-sided ones pointing into it (towards its middle); NaN when those meet non-finite values too.
  auto inside = [&]() {
    bool nonfinite = false;
    const double room = 0.9 * std::min(s - domain_lo, domain_hi - s) / (r == 3 ? 2 : 1);
    if (room >= 1e-3 && room < h0) {
      const NumericalDerivative d = consistent(centred, room, kShrink * kShrink, &nonfinite);
      if (!nonfinite) return with_rounding(d, true);
    }
    const int dir = (s - domain_lo) <= (domain_hi - s) ? +1 : -1;
    NumericalDerivative d =
        consistent([&](double h) { return one_sided(f, r, s, h, dir); }, h0 / (r + 1), kShrink, &nonfinite);
    d.one_sided = true;
    if (nonfinite) d.value.setConstant(std::numeric_limits<double>::quiet_NaN());
    return with_rounding(d, false);
  };
  bool nonfinite = false;
  const NumericalDerivative d = consistent(centred, h0, kShrink * kShrink, &nonfinite);
  if (nonfinite) return inside();  // the function may be undefined outside the domain
  NumericalDerivative across = with_rounding(d, true);
  const double reach = (r == 3 ? 2 : 1) * h0;
  if (s - reach >= domain_lo && s + reach <= domain_hi) return across;
  // The first steps left the domain, where the function may be another one: abs(sin πt) is
  // sin πt on [0, 1] only, and its derivative at 0 came out 0, not π. The central estimate stands
  // when the one inside the domain agrees with it to that one's accuracy (it is the more accurate
  // of the two); else the inside one does.
  NumericalDerivative within = inside();
  if (!within.value.allFinite()) return across;
  const double disagreement = (across.value - within.value).cwiseAbs().maxCoeff();
  const double allowed = std::max(100 * (within.error_estimate + within.rounding),
                                  1e-6 * std::max(1.0, across.value.cwiseAbs().maxCoeff()));
  return disagreement <= allowed ? across : within;
}

}  // namespace coons
