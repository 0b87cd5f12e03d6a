// Joining patches along a shared boundary (LN1, LN2): C⁰ always; a common tangent plane for
// partially bicubic Coons patches over C¹ (or equally scaled G¹) transversal boundaries.
#include "coons/surfaces/joining.h"

#include <catch2/catch.hpp>

#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using V = Eigen::RowVector3d;

namespace {

// Patch A over [0,1]² and patch B to its right: they share A.right = B.left. The transversal
// boundary curves (bottoms and tops) are cubic Bézier curves; B's start with tangent
// λ_bottom·A.bottom'(1) and λ_top·A.top'(1) (λ = 1: C¹, λ > 0: G¹).
std::pair<Surface, Surface> two_patches(CoonsBlending blending, double lambda_bottom, double lambda_top) {
  Eigen::MatrixX3d a_bottom(4, 3), a_top(4, 3), shared(4, 3), a_left(3, 3), b_bottom(4, 3), b_top(4, 3), b_right(3, 3);
  a_bottom << 0, 0, 0, 0.3, -0.1, 0.2, 0.7, 0.1, 0.4, 1, 0, 0.1;
  a_top << 0, 1, 0.2, 0.4, 1.1, 0.5, 0.6, 0.9, 0.3, 1, 1, 0.6;
  shared << 1, 0, 0.1, 1.1, 0.4, 0.5, 0.9, 0.7, 0.2, 1, 1, 0.6;
  a_left << 0, 0, 0, -0.2, 0.5, 0.4, 0, 1, 0.2;
  // B's bottom and top leave the shared corners along A's end tangents, scaled.
  const V tb = 3 * (a_bottom.row(3) - a_bottom.row(2)), tt = 3 * (a_top.row(3) - a_top.row(2));
  b_bottom << a_bottom.row(3), a_bottom.row(3) + lambda_bottom * tb / 3, V(1.6, 0.2, -0.1), V(2, 0.1, 0.3);
  b_top << a_top.row(3), a_top.row(3) + lambda_top * tt / 3, V(1.7, 1.2, 0.9), V(2, 1, 0.2);
  b_right << 2, 0.1, 0.3, 2.2, 0.5, 0.0, 2, 1, 0.2;
  const Surface a = make_coons(
      BoundaryCurves{BezierCurve(a_bottom), BezierCurve(a_top), BezierCurve(a_left), BezierCurve(shared)}, blending);
  const Surface b = make_coons(
      BoundaryCurves{BezierCurve(b_bottom), BezierCurve(b_top), BezierCurve(shared), BezierCurve(b_right)}, blending);
  return {a, b};
}

}  // namespace

TEST_CASE("compare_seam: bicubic Coons patches over C1 transversal boundaries join G1", "[surfaces]") {
  const auto [a, b] = two_patches(CoonsBlending::kHermite, 1, 1);
  const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
  CHECK(r.c0_gap < 1e-15);
  CHECK(r.max_normal_angle < 1e-12);
  // In fact C¹: the cross-boundary derivatives agree.
  for (double v : {0.2, 0.5, 0.9}) CHECK((a.evaluate(1, v).du - b.evaluate(0, v).du).norm() < 1e-13);
}

TEST_CASE("compare_seam: bicubic Coons patches over G1 boundaries with one ratio join G1", "[surfaces]") {
  for (double lambda : {0.5, 2.0, 3.7}) {
    const auto [a, b] = two_patches(CoonsBlending::kHermite, lambda, lambda);
    const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
    INFO("lambda = " << lambda);
    CHECK(r.c0_gap < 1e-15);
    CHECK(r.max_normal_angle < 1e-12);
  }
}

TEST_CASE("compare_seam: G1 boundaries with different ratios at the two ends give a kink (the limit of the claim)",
          "[surfaces]") {
  // r_u(1, v) = F0(v) b'(1) + F1(v) t'(1) on A and F0(v) λ_b b'(1) + F1(v) λ_t t'(1) on B: parallel
  // only at the ends when λ_b ≠ λ_t, so the tangent planes differ in between.
  const auto [a, b] = two_patches(CoonsBlending::kHermite, 0.5, 2.0);
  const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
  CHECK(r.c0_gap < 1e-15);
  CHECK(r.max_normal_angle > 1e-2);
  CHECK(r.at > 0.05);
  CHECK(r.at < 0.95);
}

TEST_CASE("compare_seam: bilinear Coons patches over the same data meet only C0", "[surfaces]") {
  const auto [a, b] = two_patches(CoonsBlending::kLinear, 1, 1);
  const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
  CHECK(r.c0_gap < 1e-15);
  CHECK(r.max_normal_angle > 1e-2);
}

TEST_CASE("compare_seam: Ferguson patches sharing their edge data join C1, a reversed seam is found", "[surfaces]") {
  const std::array<V, 4> ca = {V(0, 0, 0), V(1, 0, 0.2), V(0, 1, 0.1), V(1, 1, 0.5)};
  const std::array<V, 4> ua = {V(1, 0, 0.1), V(1, 0.2, -0.3), V(0.9, 0, 0.2), V(1.2, 0, 0.4)};
  const std::array<V, 4> va = {V(0, 1, 0), V(0.1, 1, 0.3), V(0, 1.1, -0.2), V(-0.1, 0.9, 0.2)};
  // B's left edge data = A's right edge data.
  const std::array<V, 4> cb = {ca[1], V(2, 0, 0), ca[3], V(2, 1, 0.3)};
  const std::array<V, 4> ub = {ua[1], V(1, 0, 0), ua[3], V(1, 0, 0)};
  const std::array<V, 4> vb = {va[1], V(0, 1, 0), va[3], V(0, 1, 0)};
  const Surface a = make_ferguson(ca, ua, va), b = make_ferguson(cb, ub, vb);
  const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
  CHECK(r.c0_gap < 1e-15);
  CHECK(r.max_normal_angle < 1e-12);
  const SeamReport wrong = compare_seam(a, Side::kRight, b, Side::kLeft, true);
  CHECK(wrong.c0_gap > 0.1);
}

TEST_CASE("compare_seam: the verdict does not depend on the size of the patches", "[surfaces]") {
  // Two pieces of z = xy (a bilinear surface), over [0,1]² and [1,2]×[0,1], scaled by s: one smooth
  // surface. At s = 1e-150 the normals used to underflow, none was compared and no G1 was claimed.
  for (const double s : {1.0, 1e-150, 1e150}) {
    INFO("scale " << s);
    const Surface a = make_bilinear({V(0, 0, 0) * s, V(1, 0, 0) * s, V(0, 1, 0) * s, V(1, 1, 1) * s});
    const Surface b = make_bilinear({V(1, 0, 0) * s, V(2, 0, 0) * s, V(1, 1, 1) * s, V(2, 1, 2) * s});
    const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
    CHECK(r.normals_compared == 101);
    CHECK(r.max_normal_angle < 1e-12);
    CHECK(r.c0_gap <= 1e-15 * s);
    CHECK(r.not_finite == 0);
  }
}

TEST_CASE("compare_seam: the angle is between oriented tangent planes, a 120 degree crease is 120 and a fold 180",
          "[surfaces]") {
  // The angle between unoriented normals never exceeds 90 degrees: it called this crease 60 and the
  // fold (b lying back over a) G1 with angle 0.
  const Surface a = make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)});
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);  // b leaves the seam at 120 degrees to a's plane
  const Surface crease = make_bilinear({V(1, 0, 0), V(1 - c, 0, s), V(1, 1, 0), V(1 - c, 1, s)});
  const Surface fold = make_bilinear({V(1, 0, 0), V(0, 0, 0), V(1, 1, 0), V(0, 1, 0)});
  const SeamReport r120 = compare_seam(a, Side::kRight, crease, Side::kLeft);
  CHECK(r120.c0_gap == 0);
  CHECK(r120.normals_compared == 101);
  CHECK(r120.max_normal_angle == Approx(2 * M_PI / 3).epsilon(1e-14));
  const SeamReport r180 = compare_seam(a, Side::kRight, fold, Side::kLeft);
  CHECK(r180.max_normal_angle == Approx(M_PI).epsilon(1e-14));
  // A smooth continuation whose own normal r_u x r_v points the other way (u runs backwards, the
  // seam is reversed) is still a smooth continuation: the orientation comes from the seam.
  const Surface flipped = make_bilinear({V(1, 1, 0), V(0, 1, 0), V(1, 2, 0), V(0, 2, 0)});
  const SeamReport smooth = compare_seam(a, Side::kTop, flipped, Side::kBottom, true);
  CHECK(smooth.c0_gap < 1e-15);
  CHECK(smooth.normals_compared == 101);
  CHECK(smooth.max_normal_angle == 0);
}

TEST_CASE("compare_seam: each normal takes its own surface's seam tangent, sides crossing at a point give 45 degrees",
          "[surfaces]") {
  // a: the plane z = 0; b: the plane z = y - 1/2, whose left side crosses a's right side only at
  // (1, 1/2, 0). With a's tangent for both normals the angle read 0 there.
  const Surface a = make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)});
  const Surface b = make_bilinear({V(1, 0, -0.5), V(2, 0, -0.5), V(1, 1, 0.5), V(2, 1, 0.5)});
  const SeamReport r = compare_seam(a, Side::kRight, b, Side::kLeft);
  CHECK(r.c0_gap == Approx(0.5).epsilon(1e-14));
  CHECK(r.normals_compared == 101);
  CHECK(r.max_normal_angle == Approx(M_PI / 4).epsilon(1e-14));
  // the same, b's side running the other way
  const Surface b_reversed = make_bilinear({V(1, 1, 0.5), V(2, 1, 0.5), V(1, 0, -0.5), V(2, 0, -0.5)});
  CHECK(compare_seam(a, Side::kRight, b_reversed, Side::kLeft, true).max_normal_angle ==
        Approx(M_PI / 4).epsilon(1e-14));
}
