// Fixtures for the B-spline tests, made in code with fixed seeds: clamped knot vectors with
// non-uniform spacing and repeated interior knots, random curves and boundaries on them.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "coons/curves/bspline_curve.h"
#include "coons/surfaces/bspline_surface.h"

namespace coons::test {

//! A clamped knot vector on [a, b] for degree p and `count` points: the interior knots are drawn
//! from a grid of 4·count + 8 steps (so some repeat), none more than p times.
Eigen::VectorXd make_random_knots(int degree, int count, std::uint32_t seed, double a = 0.0, double b = 1.0);

//! A curve on make_random_knots with random control points in [−1, 1]³.
BSplineCurve make_random_bspline(int degree, int count, std::uint32_t seed, double a = 0.0, double b = 1.0);

//! A surface of degree (p, q) on make_random_knots over [u0, u1] × [v0, v1] (seeds `seed`, `seed` + 1)
//! with count_u × count_v random points in [−1, 1]³ (make_random_net, seed + 2).
BSplineSurface make_random_bspline_surface(int p, int count_u, int q, int count_v, std::uint32_t seed, double u0 = 0.0,
                                           double u1 = 1.0, double v0 = 0.0, double v1 = 1.0);

//! The Bézier knot vector of degree p on [a, b]: p + 1 copies of a, then p + 1 copies of b.
Eigen::VectorXd bezier_knots(int degree, double a = 0.0, double b = 1.0);

//! Four curves with shared corners whose opposite sides differ in degree, knots, point count and
//! domain: bottom (p, count_u), top (p + 1, count_u + 2), left (q, count_v), right (q, count_v + 1).
BSplineBoundary make_random_bspline_boundary(int p, int count_u, int q, int count_v, std::uint32_t seed);

}  // namespace coons::test
