// Poles and non-finite values of an analytic curve between the samples a reader checks. A reader
// that evaluates an expression at 65 parameters misses 0.001 t(1 − t)/(t − 0.50390625): the pole
// lies between two samples, and the curve was accepted, fitted and solved. Each coordinate is
// sampled densely; where it changes sign between neighbouring samples, bisection keeps the change
// and ends on a root (small values) or a pole (values without bound); where its magnitude peaks,
// a golden-section search climbs the peak, which a pole of even order makes unbounded. A value
// `growth` times the curve's size, or one that is not finite, is a singularity; the size is the
// largest sampled magnitude, each sample capped at its larger neighbour's (so that a pole that
// falls on a sample, tan(πt) at t = 1/2, does not set it).
// Costs: samples evaluations, plus 60 (bisection) or 80 (golden section) per candidate interval;
// only intervals whose values reach a tenth of the coordinate's largest sampled magnitude are
// searched, which is where a pole's neighbours are.
// Based on: bisection and golden-section search (J. Kiefer, Sequential minimax search for a
// maximum, Proc. AMS 4, 1953).
#pragma once

#include <optional>

#include "coons/curves/analytic_curve.h"

namespace coons {

struct Singularity {
  int component = 0;  //!< 0, 1, 2 for x, y, z
  double s = 0;       //!< the curve's own parameter in [0, 1]
  double value = 0;   //!< the coordinate found there (may be ±inf or NaN)
};

//! The first singularity found (component by component), or nullopt. samples ≥ 2.
std::optional<Singularity> find_singularity(const AnalyticCurve& c, int samples = 1025, double growth = 1e8);

}  // namespace coons
