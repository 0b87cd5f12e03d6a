// Ruled (lofted) surfaces of two curves, sectorial surfaces (one curve a point) and the bilinear
// surface (hyperbolic paraboloid) of four corners:
//   ruled:      r(u, v) = (1 − v)·c₀(u) + v·c₁(u)
//   sectorial:  r(u, v) = (1 − v)·c(u) + v·p
//   bilinear:   r(u, v) = (1−u)(1−v) p₀₀ + u(1−v) p₁₀ + (1−u)v p₀₁ + uv p₁₁
// Exact Bézier nets: degree (max deg c₀, c₁; 1) when both curves are Bézier; (1, 1) for bilinear.
// Based on: LN0 (Slovak lecture notes), ruled surfaces; LN1, the transition surface
// (přechodová plocha); LN4 (Russian lecture notes), ruled, sectorial and bilinear surfaces.
#pragma once

#include <Eigen/Core>
#include <array>

#include "coons/curves/curve.h"
#include "coons/surfaces/boolean_sum.h"

namespace coons {

struct RuledSurface {
  Curve c0;  //!< r(u, 0)
  Curve c1;  //!< r(u, 1)
};

//! The sectorial surface of curve c and apex p: a ruled surface whose c₁ is the constant p.
RuledSurface sectorial_surface(Curve c, const Eigen::RowVector3d& apex);

//! Corners in the order p₀₀ = r(0,0), p₁₀ = r(1,0), p₀₁ = r(0,1), p₁₁ = r(1,1) (docs/formats.md).
struct BilinearSurface {
  std::array<Eigen::RowVector3d, 4> corners;
};

BooleanSum to_boolean_sum(const RuledSurface& s);
BooleanSum to_boolean_sum(const BilinearSurface& s);

}  // namespace coons
