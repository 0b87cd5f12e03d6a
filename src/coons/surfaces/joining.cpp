#include "joining.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "coons/net/surface_point.h"

namespace coons {

namespace {
// The derivative along the side (its own parameter) and the cross-boundary derivative pointing
// away from the patch's interior (bottom: −r_v, top: r_v, left: −r_u, right: r_u).
Eigen::RowVector3d along(const SurfacePoint& s, Side side) {
  return side == Side::kBottom || side == Side::kTop ? s.du : s.dv;
}
Eigen::RowVector3d outward(const SurfacePoint& s, Side side) {
  switch (side) {
    case Side::kBottom:
      return -s.dv;
    case Side::kTop:
      return s.dv;
    case Side::kLeft:
      return -s.du;
    default:
      return s.du;
  }
}

SurfacePoint on_side(const Surface& s, Side side, double t) {
  switch (side) {
    case Side::kBottom:
      return s.evaluate(t, 0);
    case Side::kTop:
      return s.evaluate(t, 1);
    case Side::kLeft:
      return s.evaluate(0, t);
    default:
      return s.evaluate(1, t);
  }
}
}  // namespace

SeamReport compare_seam(const Surface& a, Side side_a, const Surface& b, Side side_b, bool reversed, int samples) {
  SeamReport r;
  r.samples = samples;
  for (int k = 0; k < samples; ++k) {
    const double t = double(k) / (samples - 1);
    const double tb = reversed ? 1 - t : t;
    const SurfacePoint pa = on_side(a, side_a, t), pb = on_side(b, side_b, tb);
    if (!pa.p.allFinite() || !pb.p.allFinite()) {
      if (r.not_finite == 0) {
        r.not_finite = pa.p.allFinite() ? 2 : 1;
        r.not_finite_at = pa.p.allFinite() ? tb : t;
      }
      continue;
    }
    r.c0_gap = std::max(r.c0_gap, (pa.p - pb.p).norm());
    // Normals oriented alike across the seam: Ta × (a's outward derivative) and Tb × (b's inward
    // one), each T the seam's tangent on its own surface, running as t does on a. A smooth
    // continuation gives the same normal, a crease of 120° the angle 120°, b folded back onto a
    // 180°. (The angle between unoriented normals, used before, never exceeds 90°: it called a
    // 120° crease 60° and a fold G1. Until 2026-11-30 both took a's tangent, and Ta × b's
    // derivative is no normal of b where the sides do not coincide: two planes at 45° whose sides
    // cross at one point read 0°.)
    const Eigen::RowVector3d tangent_a = along(pa, side_a), tangent_b = (reversed ? -1.0 : 1.0) * along(pb, side_b);
    const Eigen::RowVector3d na = unit_cross(tangent_a, outward(pa, side_a));
    const Eigen::RowVector3d nb = unit_cross(tangent_b, -outward(pb, side_b));
    if (!na.allFinite() || !nb.allFinite()) continue;
    ++r.normals_compared;
    const double angle = std::atan2(na.cross(nb).norm(), na.dot(nb));
    if (angle > r.max_normal_angle) {
      r.max_normal_angle = angle;
      r.at = t;
    }
  }
  return r;
}

}  // namespace coons
