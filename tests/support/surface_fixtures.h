// Fixtures for the curve and surface tests, made in code with fixed seeds.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>

#include "coons/curves/curve.h"
#include "coons/surfaces/coons_patch.h"
#include "coons/surfaces/surface.h"

namespace coons::test {

//! A Bézier curve of the given degree with random control points in [−1, 1]³.
BezierCurve make_random_bezier(int degree, std::uint32_t seed);

//! Four random Bézier curves (bottom/top of degree m, left/right of degree n) with shared corners.
BoundaryCurves make_random_boundary_curves(int m, int n, std::uint32_t seed);

//! A curve from a closed form and its first two derivatives (exact, for closed-form checks).
Curve closed_form_curve(std::function<Eigen::RowVector3d(double)> f, std::function<Eigen::RowVector3d(double)> df,
                        std::function<Eigen::RowVector3d(double)> d2f);

//! The Hermite cubics of LN0: H₀₃, H₃₃, H₁₃, H₂₃ (i = 0..3) and their derivatives.
double hermite(int i, double t, int r = 0);

//! max over an n × n grid of ‖a(u,v) − b(u,v)‖.
double max_distance(const std::function<Eigen::RowVector3d(double, double)>& a,
                    const std::function<Eigen::RowVector3d(double, double)>& b, int n = 11);

//! Path of a file in data/surfaces/.
std::string surface_data(const std::string& name);

}  // namespace coons::test
