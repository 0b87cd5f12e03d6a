#include "conoid.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "coons/net/control_net.h"

namespace coons {

std::string conoid_problem(const Conoid& c) {
  if (!(c.line_direction.cwiseAbs().maxCoeff() > 0)) return "the line's direction is the zero vector";
  if (!(c.plane_normal.cwiseAbs().maxCoeff() > 0)) return "the plane's normal is the zero vector";
  // the conoid depends on the direction and the normal only through ratios, which a power of two
  // leaves bit for bit, while norm() and n·d of a vector like [1e-200, 0, 0] underflow to 0
  const Eigen::RowVector3d direction = unit_scaled(c.line_direction), normal = unit_scaled(c.plane_normal);
  const double cosine = std::abs(normal.dot(direction)) / (direction.norm() * normal.norm());
  if (!(cosine > 1e-9))
    return fmt::format("the line is parallel to the directing plane (|cos| between direction and normal = {:.3g})",
                       cosine);
  return {};
}

Curve conoid_line_curve(const Conoid& c) {
  const Eigen::RowVector3d L0 = c.line_point, d = unit_scaled(c.line_direction), n = unit_scaled(c.plane_normal);
  const double nd = n.dot(d);
  if (const BezierCurve* b = c.directrix.bezier()) {
    Eigen::MatrixX3d Q(b->points.rows(), 3);
    for (Eigen::Index i = 0; i < Q.rows(); ++i) Q.row(i) = L0 + d * (n.dot(b->points.row(i) - L0) / nd);
    return BezierCurve(Q);
  }
  auto directrix = std::make_shared<const Curve>(c.directrix);
  return FunctionCurve{[directrix, L0, d, n, nd](int r, double s) -> Eigen::RowVector3d {
                         if (r == 0) return L0 + d * (n.dot(directrix->at(s) - L0) / nd);
                         return d * (n.dot(directrix->derivative(r, s)) / nd);
                       },
                       "the directing line's points"};
}

BooleanSum to_boolean_sum(const Conoid& c) {
  BooleanSum sum;
  sum.v_blended.push_back({linear_blend(0), conoid_line_curve(c)});
  sum.v_blended.push_back({linear_blend(1), c.directrix});
  return sum;
}

Conoid right_conoid(Curve profile, double y_p, double z_p) {
  return Conoid{std::move(profile), Eigen::RowVector3d(0, y_p, z_p), Eigen::RowVector3d(1, 0, 0),
                Eigen::RowVector3d(1, 0, 0)};
}

Conoid right_helicoidal_conoid(double radius, double theta1, double theta2, double rise) {
  const double span = theta2 - theta1;
  FunctionCurve helix{[=](int r, double s) -> Eigen::RowVector3d {
                        const double th = theta1 + s * span, k = std::pow(span, r);
                        // d^r/dθ^r of (R cos θ, R sin θ): cos(θ + rπ/2), sin(θ + rπ/2).
                        const double phase = th + r * 1.57079632679489661923;  // rπ/2
                        const double z = r == 0 ? rise * th : (r == 1 ? rise * span : 0.0);
                        return {k * radius * std::cos(phase), k * radius * std::sin(phase), z};
                      },
                      "helix"};
  return Conoid{Curve(std::move(helix)), Eigen::RowVector3d(0, 0, 0), Eigen::RowVector3d(0, 0, 1),
                Eigen::RowVector3d(0, 0, 1)};
}

}  // namespace coons
