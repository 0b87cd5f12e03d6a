#include "curve.h"

namespace coons {

namespace {
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;
}  // namespace

Curve Curve::constant(const Eigen::RowVector3d& p) { return BezierCurve(Eigen::MatrixX3d(p)); }

Curve Curve::segment(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  Eigen::MatrixX3d P(2, 3);
  P << a, b;
  return BezierCurve(P);
}

Curve Curve::hermite_cubic(const Eigen::RowVector3d& p0, const Eigen::RowVector3d& p1, const Eigen::RowVector3d& d0,
                           const Eigen::RowVector3d& d1) {
  Eigen::MatrixX3d P(4, 3);
  P << p0, p0 + d0 / 3, p1 - d1 / 3, p1;
  return BezierCurve(P);
}

Eigen::RowVector3d Curve::at(double s) const { return derivative(0, s); }

Eigen::RowVector3d Curve::derivative(int r, double s) const {
  return std::visit(Overloaded{[&](const BezierCurve& c) { return evaluate_derivative(c, r, s); },
                               [&](const AnalyticCurve& c) { return c.derivative(r, s); },
                               [&](const FunctionCurve& c) { return c.f(r, s); }},
                    v_);
}

double Curve::derivative_error(int r, double s) const {
  const AnalyticCurve* c = analytic();
  return c ? c->derivative_error(r, s) : 0.0;
}

const char* Curve::kind() const {
  return std::visit(Overloaded{[](const BezierCurve&) { return "bezier"; }, [](const AnalyticCurve&) { return "expr"; },
                               [](const FunctionCurve&) { return "function"; }},
                    v_);
}

}  // namespace coons
