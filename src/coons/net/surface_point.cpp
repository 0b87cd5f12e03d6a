#include "surface_point.h"

#include <Eigen/Geometry>
#include <algorithm>
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

Eigen::RowVector3d unit_cross(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b) {
  // Divided by their norms first: the cross product then neither underflows (a surface of size
  // 1e-150: the squared norm of du × dv would be 1e-600) nor overflows.
  const double la = a.stableNorm(), lb = b.stableNorm();
  if (!(la > 0) || !(lb > 0)) return Eigen::RowVector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const Eigen::RowVector3d n = (a / la).cross(b / lb);
  const double len = n.norm();
  if (!(len > 1e-14)) return Eigen::RowVector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return n / len;
}

Eigen::RowVector3d unit_normal(const SurfacePoint& s) { return unit_cross(s.du, s.dv); }

Curvatures curvatures(const SurfacePoint& s) {
  const Eigen::RowVector3d n = unit_normal(s);
  // In units of the larger first partial σ, so that no product underflows or overflows at any
  // size of the surface: E, F, G are then of order one, and H scales back by 1/σ, K by 1/σ².
  const double sigma = std::max(s.du.stableNorm(), s.dv.stableNorm());
  const Eigen::RowVector3d du = s.du / sigma, dv = s.dv / sigma;
  const double E = du.dot(du), F = du.dot(dv), G = dv.dot(dv);
  const double L = s.duu.dot(n) / sigma, M = s.duv.dot(n) / sigma, N = s.dvv.dot(n) / sigma;
  const double det = E * G - F * F;
  Curvatures c;
  c.gaussian = (L * N - M * M) / det / sigma / sigma;
  c.mean = (E * N - 2 * F * M + G * L) / (2 * det) / sigma;
  return c;
}

}  // namespace coons
