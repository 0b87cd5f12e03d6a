// The Bézier curve of a chosen degree that interpolates a curve's end points and fits its inner
// points by least squares, at the same parameter: minimise Σ_k ‖b(s_k) − c(s_k)‖² over the inner
// control points, s_k uniform in [0, 1]. The report gives the largest parametric deviation
// max_s ‖b(s) − c(s)‖ on a finer grid (an upper bound of the geometric distance), so that every
// analytic example of the lecture notes (LN0–LN4) can be studied as a net with a known error.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), §9 (least-squares
// approximation with fixed end points); LN0's analytic boundaries.
#pragma once

#include "coons/curves/curve.h"

namespace coons {

struct BezierFit {
  BezierCurve curve;         //!< #degree+1 control points; first = c(0), last = c(1)
  double max_deviation = 0;  //!< max ‖b(s) − c(s)‖ over the check grid
  double at = 0;             //!< the s where it is reached
  int samples = 0;           //!< least-squares samples used
  int fitted_degree = 0;     //!< the degree of the least-squares fit before its exact elevation
};

//! Up to this degree the fit is made at the degree asked for.
constexpr int kDirectFitDegree = 24;
//! Above kDirectFitDegree the fit is made at 8, 12, …, up to this degree (and the degree asked for,
//! if lower): the first at rounding level, else the one at kDirectFitDegree, elevated exactly.
constexpr int kLargestFitDegree = 64;

//! degree ≥ 1 (degree 1: the chord). samples ≤ 0 picks max(10·(degree + 1), 101) at the degree
//! fitted; the deviation is checked on 10·samples + 1 points. A Bézier input of degree ≤ `degree`
//! is elevated exactly, and so is the fit when `degree` exceeds kDirectFitDegree.
BezierFit fit_bezier(const Curve& c, int degree, int samples = 0);

}  // namespace coons
