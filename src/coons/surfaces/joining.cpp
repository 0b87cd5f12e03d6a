#include "joining.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace coons {

namespace {
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
    const Eigen::RowVector3d na = unit_normal(pa), nb = unit_normal(pb);
    if (!na.allFinite() || !nb.allFinite()) continue;
    ++r.normals_compared;
    // The angle between unoriented normals, robustly: atan2(|na × nb|, |na · nb|).
    const double angle = std::atan2(na.cross(nb).norm(), std::abs(na.dot(nb)));
    if (angle > r.max_normal_angle) {
      r.max_normal_angle = angle;
      r.at = t;
    }
  }
  return r;
}

}  // namespace coons
