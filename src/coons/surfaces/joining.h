// Two patches along a common boundary: the C⁰ gap (largest distance between corresponding seam
// points) and the G¹ defect (largest angle between the tangent planes along the seam, oriented
// alike across it: 0 for a smooth continuation, up to 180° for the second patch folded back onto
// the first). Bilinear Coons patches meet C⁰ only; partially bicubic Coons patches over
// transversal boundary curves that join C¹ — or G¹ with the same ratio of tangent lengths at both
// ends of the seam — meet with a common tangent plane (LN1, LN2). With different ratios at the
// two ends the cross-boundary derivatives are not parallel in between, and the join is only C⁰.
// Based on: LN1 (Czech lecture notes), napojení plátů (C⁰, G¹); LN2 (Czech), plátování
// bikubických Coonsových plátů.
#pragma once

#include "coons/surfaces/surface.h"

namespace coons {

//! bottom: v = 0, top: v = 1 (seam parameter u); left: u = 0, right: u = 1 (seam parameter v).
enum class Side { kBottom, kTop, kLeft, kRight };

struct SeamReport {
  double c0_gap = 0;            //!< max ‖a(t) − b(t)‖
  double max_normal_angle = 0;  //!< radians, angle between the oriented tangent planes, in [0, π]
  double at = 0;                //!< seam parameter of the largest angle
  int samples = 0;
  int normals_compared = 0;  //!< samples where both normals exist (max_normal_angle is over these)
  int not_finite = 0;        //!< 1 (a) or 2 (b): the surface whose seam point is first not finite; 0: none
  double not_finite_at = 0;  //!< that point's parameter on its own side (b's is 1 − t when reversed)
};

//! Compares side_a of a with side_b of b at `samples` ≥ 2 seam parameters t (b at 1 − t when
//! reversed). The normals are T × (a's outward cross-boundary derivative) and T × (b's inward one),
//! T the seam tangent of a, so that they agree where b continues a smoothly. Where one is singular
//! (NaN: a vanishing or parallel derivative) the sample is skipped and not counted in
//! normals_compared; a seam point
//! that is not finite (a pole of an expression curve) is reported in not_finite and compared with
//! nothing, so that c0_gap is the largest finite gap.
SeamReport compare_seam(const Surface& a, Side side_a, const Surface& b, Side side_b, bool reversed = false,
                        int samples = 101);

}  // namespace coons
