#include "analytic_curve.h"

#include <fmt/format.h>
#include <muParser.h>

#include <algorithm>
#include <cmath>

#include "coons/curves/numerical_derivative.h"

namespace coons {

namespace {

// muparser's assignments ("t=0.5", "t+=1") change the variable they name: the '=' of one, which
// is not part of a comparison (==, <=, >=, !=). Returns its position, or npos.
size_t assignment_at(const std::string& expression) {
  for (size_t k = 0; k < expression.size(); ++k) {
    if (expression[k] != '=') continue;
    const char before = k > 0 ? expression[k - 1] : ' ', after = k + 1 < expression.size() ? expression[k + 1] : ' ';
    if (after == '=') {  // "==": skip both
      ++k;
      continue;
    }
    if (before != '<' && before != '>' && before != '!') return k;
  }
  return std::string::npos;
}

}  // namespace

struct AnalyticCurve::Compiled {
  // One variable per component, set before each evaluation: an expression cannot reach another's.
  double t[3] = {0, 0, 0};
  mu::Parser parser[3];

  explicit Compiled(const std::array<std::string, 3>& expressions) {
    for (int c = 0; c < 3; ++c) {
      mu::Parser& p = parser[c];
      // "t=0.5" in y was accepted and set the t that z then read: r(1, 0) came out (1, 0.5, 0.5)
      if (assignment_at(expressions[c]) != std::string::npos)
        throw ExpressionError(c, fmt::format("'{}' assigns to a variable ('=' at character {}); an expression in t "
                                             "computes a value (compare with ==)",
                                             expressions[c], assignment_at(expressions[c]) + 1));
      try {
        for (const char* name : {"t", "u", "v", "s"}) p.DefineVar(name, &t[c]);
        p.DefineConst("pi", 3.14159265358979323846);
        p.DefineConst("e", 2.71828182845904523536);
        p.SetExpr(expressions[c]);
        int results = 0;
        p.Eval(results);  // compiles; reports syntax errors and unknown names
        if (results != 1)
          throw ExpressionError(
              c, fmt::format("'{}' gives {} values (a ',' in the expression?), need one", expressions[c], results));
      } catch (const mu::Parser::exception_type& e) {
        std::string message = e.GetMsg();
        if (!message.empty() && message.back() == '.') message.pop_back();
        throw ExpressionError(c, fmt::format("'{}' does not parse: {}", expressions[c], message));
      }
    }
  }

  Eigen::RowVector3d at(double value) {
    Eigen::RowVector3d r;
    for (int c = 0; c < 3; ++c) {
      t[c] = value;
      r[c] = parser[c].Eval();
    }
    return r;
  }
};

AnalyticCurve::AnalyticCurve(std::array<std::string, 3> expressions, double t1, double t2)
    : expressions_(std::move(expressions)), t1_(t1), t2_(t2), compiled_(std::make_unique<Compiled>(expressions_)) {}

AnalyticCurve::AnalyticCurve(const AnalyticCurve& other)
    : expressions_(other.expressions_),
      t1_(other.t1_),
      t2_(other.t2_),
      compiled_(std::make_unique<Compiled>(expressions_)) {}

AnalyticCurve& AnalyticCurve::operator=(const AnalyticCurve& other) {
  if (this != &other) *this = AnalyticCurve(other);
  return *this;
}

AnalyticCurve::AnalyticCurve(AnalyticCurve&&) noexcept = default;
AnalyticCurve& AnalyticCurve::operator=(AnalyticCurve&&) noexcept = default;
AnalyticCurve::~AnalyticCurve() = default;

Eigen::RowVector3d AnalyticCurve::at(double s) const { return compiled_->at(t1_ + s * (t2_ - t1_)); }

namespace {

// derivative()'s test: an estimate that settled, or one whose disagreement is the rounding of the
// curve's values and within 2 % of the derivative.
bool usable(const NumericalDerivative& d) {
  const double size = d.value.cwiseAbs().maxCoeff();
  const bool settled = d.error_estimate <= 1e-5 * std::max(1.0, size);
  const bool rounding_only = d.error_estimate <= 10 * d.rounding && d.error_estimate <= 2e-2 * size;
  return settled || rounding_only;
}

}  // namespace

double AnalyticCurve::derivative_error(int r, double s) const {
  if (r == 0) return 0;
  if (r > 3) return std::nan("");
  const NumericalDerivative d = numerical_derivative([this](double x) { return at(x); }, r, s);
  return usable(d) ? std::max(d.error_estimate, d.rounding) : std::nan("");
}

Eigen::RowVector3d AnalyticCurve::derivative(int r, double s) const {
  if (r == 0) return at(s);
  if (r > 3) return Eigen::RowVector3d::Constant(std::nan(""));
  const NumericalDerivative d = numerical_derivative([this](double x) { return at(x); }, r, s);
  // An estimate that does not settle (a singular derivative, e.g. sqrt at the end of its domain)
  // is no derivative: say so rather than return a number. An estimate whose disagreement is the
  // rounding of the curve's values has settled as far as doubles let it: a curve at x = 1e8 has
  // second derivatives good to about 1 % (it was NaN, and the surface's curvature printed 0).
  // Beyond 2 % it is no derivative either.
  if (!usable(d)) return Eigen::RowVector3d::Constant(std::nan(""));
  return d.value;
}

}  // namespace coons
