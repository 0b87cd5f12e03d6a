// The general (bicubically blended, Hermite) Coons patch: four boundary curves, the
// cross-boundary derivatives along them and the four corner twists,
//   r = Σ_i α_i(u) r(i,v) + Σ_i β_i(u) r_u(i,v) + Σ_j α_j(v) r(u,j) + Σ_j β_j(v) r_v(u,j)
//       − [α₀ α₁ β₀ β₁](u) · M · [α₀ α₁ β₀ β₁](v)ᵀ,
// α₀ = H₀₃, α₁ = H₃₃, β₀ = H₁₃, β₁ = H₂₃, and M the 4×4 corner matrix (points, v-tangents,
// u-tangents, twists) of LN1 / LN4 (6.19). It reproduces the curves and the cross
// derivatives exactly when the data are compatible (LN1):
//   • the curves meet at the corners (4 conditions);
//   • the cross derivatives agree with the curves' tangents at the corners, e.g.
//     du_left(0) = bottom'(0), dv_bottom(0) = left'(0) (8 conditions);
//   • the twists agree with the derivatives of the cross derivatives, e.g.
//     twist(0,0) = du_left'(0) = dv_bottom'(0) (8 conditions).
// compatibility_conditions() lists all 20 with their gaps; the input layer rejects data whose gap
// exceeds the tolerance, naming the corner and the condition. M is built from the boundary curves
// (points, tangents) and the given twists. With Bézier curves and cross derivatives the patch is a
// polynomial and its Bézier net is exact, degree (max(3, deg bottom, top, dv_*), max(3, deg left,
// right, du_*)).
// Based on: LN1 (Czech lecture notes), obecný Coonsův plát and its compatibility conditions;
// LN4 (Russian), generalised Coons surfaces (6.16)–(6.19); S. A. Coons, MIT MAC-TR-41 (1967).
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "coons/surfaces/coons_patch.h"

namespace coons {

struct GeneralCoonsData {
  BoundaryCurves boundary;
  Curve du_left;                            //!< ∂r/∂u (0, v), a curve in v
  Curve du_right;                           //!< ∂r/∂u (1, v)
  Curve dv_bottom;                          //!< ∂r/∂v (u, 0), a curve in u
  Curve dv_top;                             //!< ∂r/∂v (u, 1)
  std::array<Eigen::RowVector3d, 4> twist;  //!< r_uv at (0,0), (1,0), (0,1), (1,1)
};

BooleanSum to_boolean_sum(const GeneralCoonsData& g);

//! All 20 conditions, corners first, then tangents, then twists.
std::vector<CompatibilityCondition> compatibility_conditions(const GeneralCoonsData& g);

}  // namespace coons
