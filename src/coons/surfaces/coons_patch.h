// The bilinearly blended and the partially bicubic (Hermite-blended) Coons patches of four
// boundary curves: with F₀ = 1 − t, F₁ = t (bilinear) or F₀ = H₀₃, F₁ = H₃₃ (Hermite),
//   r(u, v) = F₀(v) r(u,0) + F₁(v) r(u,1) + F₀(u) r(0,v) + F₁(u) r(1,v)
//             − Σ_ij F_i(u) F_j(v) r(i, j)
// i.e. (F₀(u), −1, F₁(u))·M·(F₀(v), −1, F₁(v))ᵀ = 0 with LN1's mapping matrix M. Both
// interpolate the four curves; the bilinear patch has the twist
//   r_uv(0,0) = r_u(0,1) − r_u(0,0) + r_v(1,0) − r_v(0,0) − (p₀₀ − p₁₀ − p₀₁ + p₁₁)
// at the corner (0, 0) (similarly elsewhere), the Hermite patch zero twists at all four corners and
// cross-boundary derivatives r_u(1, v) = F₀(v) r_u(1,0) + F₁(v) r_u(1,1) (blends of the corner
// tangents), which is why two such patches over C¹ (or equally scaled G¹) transversal boundaries
// join with a common tangent plane. On Bézier curves the nets are exact: the closed form of
// docs/math.md §2 (bilinear) and its η-weighted variant (Hermite).
// Based on: LN0 (Slovak lecture notes), bilineárne a čiastkovo bikubické Coonsove záplaty;
// LN1 (Czech), bilinear and bicubic Coons patches; LN4 (Russian), linear Coons surfaces;
// S. A. Coons, MIT MAC-TR-41 (1967).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/surfaces/boolean_sum.h"

namespace coons {

//! bottom = r(u, 0), top = r(u, 1), left = r(0, v), right = r(1, v); corners shared
//! (bottom(0) = left(0), bottom(1) = right(0), top(0) = left(1), top(1) = right(1)).
struct BoundaryCurves {
  Curve bottom, top, left, right;
};

enum class CoonsBlending { kLinear, kHermite };

//! Corners r(i, j) are taken from bottom and top.
BooleanSum to_boolean_sum(const BoundaryCurves& b, CoonsBlending blending);

//! The corners in the order (0,0), (1,0), (0,1), (1,1) and their names.
extern const std::array<const char*, 4> kCornerNames;  // "bottom-left (u = 0, v = 0)", …

//! One condition that compatible data satisfy, with how far the data are from it.
struct CompatibilityCondition {
  std::string field;      //!< the datum blamed: "left", "du_left", "twist[2]", …
  std::string corner;     //!< one of kCornerNames
  std::string condition;  //!< e.g. "left(0) = bottom(0)"
  double gap = 0;         //!< ‖lhs − rhs‖
  double scale = 0;       //!< max(‖lhs‖, ‖rhs‖): the tolerance is relative to max(scale, data size)
  int order = 0;          //!< 0: positions, 1: tangents, 2: twists
  //! The error bound of a numerical derivative on either side (0 where both are exact): the
  //! tolerance grows by it (a curve at x = 1e8 has tangents good to about 1e−5 only).
  double uncertainty = 0;
};

//! The four corner conditions of a boundary (blaming the v-curves left/right).
std::vector<CompatibilityCondition> corner_conditions(const BoundaryCurves& b);

//! Diagonal of the bounding box of the four curves sampled at 33 points each: the size the
//! tolerances are relative to.
double boundary_size(const BoundaryCurves& b);

}  // namespace coons
