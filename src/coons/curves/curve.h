// The curve value type of the surfaces: a Bézier curve, an analytic curve (expressions, derivatives
// numerically) or a function with exact derivatives (closed forms in tests and in code), all on
// s ∈ [0, 1]. A point is a Bézier curve of degree 0.
// Based on: LN0, LN1, LN4 — every surface of the Coons family is built from such curves.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <variant>

#include "coons/curves/analytic_curve.h"
#include "coons/curves/bezier_curve.h"

namespace coons {

//! c^(r)(s) = f(r, s) for r = 0, 1, 2 (at least); exact derivatives supplied by the caller.
struct FunctionCurve {
  std::function<Eigen::RowVector3d(int r, double s)> f;
  std::string description = "function";
};

class Curve {
 public:
  using Variant = std::variant<BezierCurve, AnalyticCurve, FunctionCurve>;

  Curve(BezierCurve c) : v_(std::move(c)) {}    // NOLINT: implicit on purpose (a curve is any of these)
  Curve(AnalyticCurve c) : v_(std::move(c)) {}  // NOLINT
  Curve(FunctionCurve c) : v_(std::move(c)) {}  // NOLINT

  //! The constant curve c(s) = p (degree-0 Bézier).
  static Curve constant(const Eigen::RowVector3d& p);
  //! The segment from a to b (degree-1 Bézier).
  static Curve segment(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b);
  //! The Ferguson (Hermite) cubic with c(0) = p0, c(1) = p1, c'(0) = d0, c'(1) = d1, as the
  //! Bézier cubic (p0, p0 + d0/3, p1 − d1/3, p1).
  static Curve hermite_cubic(const Eigen::RowVector3d& p0, const Eigen::RowVector3d& p1, const Eigen::RowVector3d& d0,
                             const Eigen::RowVector3d& d1);

  [[nodiscard]] Eigen::RowVector3d at(double s) const;
  //! d^r c / ds^r, r ≥ 0 (exact for Bézier and function curves, numerical for analytic ones).
  [[nodiscard]] Eigen::RowVector3d derivative(int r, double s) const;
  //! The error bound of derivative(r, s): 0 for Bézier and function curves (exact), the numerical
  //! estimate's bound for analytic ones (AnalyticCurve::derivative_error).
  [[nodiscard]] double derivative_error(int r, double s) const;

  //! The Bézier curve when this is one (the surface is then polynomial along it), else nullptr.
  [[nodiscard]] const BezierCurve* bezier() const { return std::get_if<BezierCurve>(&v_); }
  [[nodiscard]] const AnalyticCurve* analytic() const { return std::get_if<AnalyticCurve>(&v_); }
  [[nodiscard]] bool is_polynomial() const { return bezier() != nullptr; }
  //! "bezier", "expr" or "function".
  [[nodiscard]] const char* kind() const;
  [[nodiscard]] const Variant& variant() const { return v_; }

 private:
  Variant v_;
};

}  // namespace coons
