// The bicubic Hermite patches of corner data: the Ferguson (12-vector) patch — corner points,
// u- and v-tangents, zero twists — and the 16-vector patch, which adds the four corner twists:
//   r(u, v) = [H₀₃(u) H₃₃(u) H₁₃(u) H₂₃(u)] · G · [H₀₃(v) H₃₃(v) H₁₃(v) H₂₃(v)]ᵀ,
//   G = [ r₀₀ r₀₁ r^v₀₀ r^v₀₁ ; r₁₀ r₁₁ r^v₁₀ r^v₁₁ ; r^u₀₀ r^u₀₁ r^uv₀₀ r^uv₀₁ ; r^u₁₀ r^u₁₁ r^uv₁₀ r^uv₁₁ ].
// Its boundary curves are Ferguson cubics, and the Ferguson patch equals the partially bicubic
// Coons patch of those cubics (LN1). The Bézier net (bicubic) is exact: at each corner the
// point, p ± r_u/3, p ± r_v/3 and p ± r_u/3 ± r_v/3 + s·r_uv/9 (docs/math.md §6).
// LN0's example: unit-square corners, r_u = (1,0,0), r_v = (0,1,0), twist (0,0,T) at (0,0)
// only, gives r = (u, v, T·H₁₃(u)·H₁₃(v)).
// Based on: LN0 (Slovak lecture notes), bikubická Hermitova záplata, 12- a 16-vektorová
// záplata; LN1 (Czech), dvanácti- a šestnáctivektorový plát; J. C. Ferguson, Multivariable
// curve interpolation, J. ACM 11 (1964) 221–228.
#pragma once

#include <Eigen/Core>
#include <array>

#include "coons/surfaces/boolean_sum.h"

namespace coons {

//! Every array in the corner order (0,0), (1,0), (0,1), (1,1) (docs/formats.md).
struct HermitePatch {
  std::array<Eigen::RowVector3d, 4> corners;
  std::array<Eigen::RowVector3d, 4> du;     //!< r_u at the corners
  std::array<Eigen::RowVector3d, 4> dv;     //!< r_v at the corners
  std::array<Eigen::RowVector3d, 4> twist;  //!< r_uv at the corners (zero: Ferguson)
};

//! The 12-vector patch: twists zero.
HermitePatch ferguson_patch(const std::array<Eigen::RowVector3d, 4>& corners,
                            const std::array<Eigen::RowVector3d, 4>& du, const std::array<Eigen::RowVector3d, 4>& dv);

BooleanSum to_boolean_sum(const HermitePatch& h);

}  // namespace coons
