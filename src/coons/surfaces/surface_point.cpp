#include "surface_point.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace coons {

Eigen::RowVector3d SurfacePoint::derivative(int a, int b) const {
  if (a == 0 && b == 0) return p;
  if (a == 1 && b == 0) return du;
  if (a == 0 && b == 1) return dv;
  if (a == 2 && b == 0) return duu;
  if (a == 1 && b == 1) return duv;
  if (a == 0 && b == 2) return dvv;
  return Eigen::RowVector3d::Zero();
}

Eigen::RowVector3d unit_normal(const SurfacePoint& s) {
  const Eigen::RowVector3d n = s.du.cross(s.dv);
  const double len = n.norm();
  const double scale = s.du.norm() * s.dv.norm();
  if (!(len > 1e-14 * scale) || !(len > 0))
    return Eigen::RowVector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return n / len;
}

Curvatures curvatures(const SurfacePoint& s) {
  const Eigen::RowVector3d n = unit_normal(s);
  const double E = s.du.dot(s.du), F = s.du.dot(s.dv), G = s.dv.dot(s.dv);
  const double L = s.duu.dot(n), M = s.duv.dot(n), N = s.dvv.dot(n);
  const double det = E * G - F * F;
  Curvatures c;
  c.gaussian = (L * N - M * M) / det;
  c.mean = (E * N - 2 * F * M + G * L) / (2 * det);
  return c;
}

}  // namespace coons
