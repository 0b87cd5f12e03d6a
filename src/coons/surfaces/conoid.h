// Conoids: the lines that meet a directing curve c and a directing line ℓ and are parallel to a
// directing plane ω (normal n). With q(u) the point of ℓ in the plane through c(u) with normal n,
//   r(u, v) = (1 − v)·q(u) + v·c(u),   q(u) = L₀ + d·(n·(c(u) − L₀))/(n·d)   (docs/formats.md `conoid`)
// — a ruled surface whose second curve is an affine image of the first, so a Bézier directrix
// gives an exact Bézier net of degree (deg c, 1) (polynomial conoids, e.g. the parabolic one).
// Right conoid (LN0): directrix (x(u), 0, z(u)) in the plane y = 0, line parallel to x at
// height z_P in the plane y = y_P, plane x = const:
//   x = x(u), y = y_P (1 − v), z = z_P + v (z(u) − z_P);
// circular, elliptic, parabolic by the directrix. Right helicoidal conoid (LN2): directrix the
// helix (R cos θ, R sin θ, hθ), line the z-axis, plane z = const: r = (vR cos θ, vR sin θ, hθ).
// An oblique conoid is any other choice (line not perpendicular to the plane).
// Based on: LN0 (Slovak lecture notes), conoids (kolmý/šikmý konoid); LN2 (Czech
// lecture notes), přímý kruhový a přímý šroubový konoid.
#pragma once

#include <Eigen/Core>
#include <string>

#include "coons/curves/curve.h"
#include "coons/surfaces/boolean_sum.h"

namespace coons {

struct Conoid {
  Curve directrix;                    //!< c(u) = r(u, 1)
  Eigen::RowVector3d line_point;      //!< L₀ on the directing line
  Eigen::RowVector3d line_direction;  //!< d
  Eigen::RowVector3d plane_normal;    //!< n of the directing plane; n·d ≠ 0
};

//! Empty when valid, else why not (a zero vector, or the line parallel to the plane).
std::string conoid_problem(const Conoid& c);

//! q(u), the directing line's curve r(u, 0); Bézier when the directrix is.
Curve conoid_line_curve(const Conoid& c);

BooleanSum to_boolean_sum(const Conoid& c);

//! LN0's right conoid over `profile` (in the plane y = 0) with the line y = y_P, z = z_P.
Conoid right_conoid(Curve profile, double y_p, double z_p);

//! The right helicoidal conoid: helix of radius R over θ ∈ [θ₁, θ₂] rising h per radian (exact
//! derivatives). With R = 1, h = 1, θ ∈ [0, 2π]: r(s, v) = (v cos θ, v sin θ, θ), θ = 2πs — LN2's
//! (u cos v, u sin v, v) with the roles of the parameters exchanged.
Conoid right_helicoidal_conoid(double radius, double theta1, double theta2, double rise_per_radian = 1);

}  // namespace coons
