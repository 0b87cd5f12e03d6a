// Bézier curves of any degree on [0, 1]: evaluation, derivatives of any order, degree elevation,
// subdivision, and the linear reparametrisation of a piece [t₁, t₂] to [0, 1].
// Based on: LN1 (Czech lecture notes), reparametrisation t = t₁ + (s − s₁)(t₂ − t₁)/(s₂ − s₁);
// G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), ch. 4 (de Casteljau, blossoms), 5, 6.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "coons/net/bernstein.h"

namespace coons {

//! c(t) = Σ_i P_i B_i^k(t), t ∈ [0, 1]. Degree 0 (one point) is a constant curve: the "point"
//! of a sectorial surface.
struct BezierCurve {
  Eigen::MatrixX3d points;  //!< #k+1 by 3 control points, k = degree() ≥ 0

  BezierCurve() = default;
  explicit BezierCurve(Eigen::MatrixX3d P) : points(std::move(P)) {}
  [[nodiscard]] int degree() const { return int(points.rows()) - 1; }
};

//! c(t) by de Casteljau up to kDeCasteljauMaxDegree (net/bernstein.h; stable for t ∈ [0, 1], an
//! extrapolation outside), by bernstein_sum() above it for t ∈ [0, 1]: a surface of a degree-5000
//! curve sampled 65 × 65 times with its derivatives took over two minutes with de Casteljau alone.
Eigen::RowVector3d evaluate(const BezierCurve& c, double t);

//! Σ_i P_i B_i^k(t) for t ∈ [0, 1] in O(k) for k > kDeCasteljauMaxDegree: bernstein_basis(k, t)
//! (net/bernstein.h) applied to P. Within about 1e−13 of de Casteljau's value at degree 1000,
//! relative to max|P_i| (test `bernstein_sum: agrees with de Casteljau in long double to 1e-13 up
//! to degree 5000`).
Eigen::RowVector3d bernstein_sum(const Eigen::MatrixX3d& P, double t);

//! The control points of the r-th derivative (the r-th hodograph): #k−r+1 by 3,
//! k!/(k−r)!·Δ^r P. A single zero point when r > k.
Eigen::MatrixX3d hodograph(const Eigen::MatrixX3d& P, int r);

//! d^r c / dt^r at t (r ≥ 0).
Eigen::RowVector3d evaluate_derivative(const BezierCurve& c, int r, double t);

//! The same curve at degree ≥ c.degree() (reuses elevate_curve).
BezierCurve elevated(const BezierCurve& c, int degree);

//! The blossom (polar form) f(t₁, …, t_k) of a degree-k curve; args has k entries.
Eigen::RowVector3d blossom(const BezierCurve& c, const std::vector<double>& args);

//! The two halves of c at t, each reparametrised to [0, 1]: first(s) = c(s·t),
//! second(s) = c(t + s(1 − t)).
std::pair<BezierCurve, BezierCurve> subdivide(const BezierCurve& c, double t);

//! The piece of c over [t₁, t₂] as a curve on [0, 1]: result(s) = c(t₁ + s(t₂ − t₁)) (LN1),
//! exactly, by blossoming; t₁ > t₂ reverses, values outside [0, 1] extrapolate.
BezierCurve reparametrised(const BezierCurve& c, double t1, double t2);

}  // namespace coons
