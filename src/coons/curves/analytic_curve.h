// Curves written as three expressions in the parameter t on an interval [t₁, t₂], reparametrised
// linearly to s ∈ [0, 1]: c(s) = f(t₁ + s(t₂ − t₁)) (LN1). Expressions are compiled by
// muparser: `pi`, `e`, + − * / ^, sin cos tan asin acos atan sinh cosh tanh exp ln log sqrt abs
// sign rint min max sum avg, and the ternary `?:`. The parameter may be written t, or u, v, s
// (all four name the curve's own parameter, so a curve in u can be written in u).
// Derivatives (with respect to s) come from numerical_derivative.h: Richardson-extrapolated
// central differences, relative accuracy ≈ 1e-13 (order 1), 1e-12 (order 2), 1e-10 (order 3).
// Based on: LN0 (Slovak lecture notes), the analytic boundary curves of its examples;
// LN1, linear reparametrisation; muparser (I. Berg, https://beltoforion.de/en/muparser).
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <stdexcept>
#include <string>

namespace coons {

//! An expression that does not compile or has no single value.
class ExpressionError : public std::invalid_argument {
 public:
  ExpressionError(int component, const std::string& message) : std::invalid_argument(message), component_(component) {}
  //! 0, 1, 2 for x, y, z.
  [[nodiscard]] int component() const { return component_; }

 private:
  int component_;
};

//! Evaluation mutates the compiled parser's variable: one object must not be evaluated from two
//! threads at once (copies are independent: copying recompiles).
class AnalyticCurve {
 public:
  //! Throws ExpressionError when an expression does not compile, or when it evaluates to a list.
  //! Precondition: t1 ≠ t2, both finite (t1 > t2 runs the curve backwards).
  AnalyticCurve(std::array<std::string, 3> expressions, double t1 = 0, double t2 = 1);
  AnalyticCurve(const AnalyticCurve& other);
  AnalyticCurve& operator=(const AnalyticCurve& other);
  AnalyticCurve(AnalyticCurve&&) noexcept;
  AnalyticCurve& operator=(AnalyticCurve&&) noexcept;
  ~AnalyticCurve();

  //! c(s), s ∈ [0, 1] (values outside extrapolate the expressions). May be non-finite.
  [[nodiscard]] Eigen::RowVector3d at(double s) const;
  //! d^r c / ds^r (r = 0..3), numerically for r ≥ 1; NaN where it cannot be computed (the
  //! extrapolation does not settle to 1e-5 relative, e.g. an infinite derivative).
  [[nodiscard]] Eigen::RowVector3d derivative(int r, double s) const;
  //! The error bound of derivative(r, s) (max-norm): the extrapolation's disagreement, at least
  //! the rounding of the curve's values (numerical_derivative.h); NaN where derivative() is NaN.
  [[nodiscard]] double derivative_error(int r, double s) const;

  [[nodiscard]] const std::array<std::string, 3>& expressions() const { return expressions_; }
  [[nodiscard]] double t1() const { return t1_; }
  [[nodiscard]] double t2() const { return t2_; }

 private:
  struct Compiled;
  std::array<std::string, 3> expressions_;
  double t1_, t2_;
  std::unique_ptr<Compiled> compiled_;
};

}  // namespace coons
