// Tensor-product B-spline surfaces from a control net and two clamped knot vectors, and the
// Greville-weighted discrete Coons net of four B-spline boundary curves: the control net of the
// continuous bilinearly blended Coons patch of those curves (docs/math.md §10).
// Sizes: the net has #count_u × #count_v points (ControlNet with m = count_u − 1, n = count_v − 1;
// m and n count points here, they are not the degrees), knots_u #count_u + p + 1,
// knots_v #count_v + q + 1.
// Based on: L. Piegl, W. Tiller, The NURBS Book, 2nd ed. (1997), A3.5 (surface point);
// G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) (the discrete Coons net);
// linear precision of the Greville abscissae, e.g. C. de Boor, A Practical Guide to Splines (1978).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "coons/curves/bspline_curve.h"
#include "coons/net/control_net.h"

namespace coons {

//! s(u, v) = Σ_i Σ_j b[i][j] N_{i,p}(u) N_{j,q}(v).
struct BSplineSurface {
  int degree_u = 1, degree_v = 1;  //!< p, q ≥ 1
  Eigen::VectorXd knots_u, knots_v;
  ControlNet net;  //!< b[i][j] = net.at(i, j), i < count_u, j < count_v

  //! True when both knot vectors are valid for the degrees and the net; else the first problem.
  bool is_valid(std::string* why) const;
};

//! s(u, v) (outside the domain the end pieces extrapolate).
Eigen::RowVector3d evaluate(const BSplineSurface& s, double u, double v);

//! ∂^a_u ∂^b_v s(u, v) (from the right at knots).
Eigen::RowVector3d evaluate_derivative(const BSplineSurface& s, int a, int b, double u, double v);

//! Four B-spline boundary curves: bottom = s(u, v₀), top = s(u, v₁), left = s(u₀, v),
//! right = s(u₁, v); corners shared as in docs/math.md §1.
struct BSplineBoundary {
  BSplineCurve bottom, top, left, right;
};
//! The four boundary curves of a surface (rows and columns of the net on the frame).
BSplineBoundary boundary_of(const BSplineSurface& s);

//! What making the four sides compatible did, for a report: per side the degree it was raised by
//! and the number of knots inserted, after mapping every side's domain onto [0, 1].
struct CompatibilityNote {
  std::string side;  //!< "bottom", "top", "left" or "right"
  int degree_raised_by = 0;
  int knots_inserted = 0;
};

//! Knot values of opposite sides over [0, 1] closer than this are one knot split by rounding (the
//! reparametrised 0.1 of [0, 0.3] is 0.33333333333333337, 1/3 is 0.3333333333333333).
inline constexpr double kSameKnot = 1e-12;

//! Four sides over [0, 1] with equal degree and knots on opposite sides (bottom/top share p and
//! the u knots, left/right q and the v knots), by exact degree elevation and knot insertion.
//! Each side is first reparametrised onto [0, 1] (the Coons patch of the curves uses their
//! normalised parameters); a knot of top (right) within kSameKnot of one of bottom's (left's)
//! takes its value, instead of being inserted as a second knot a rounding error away. `notes`
//! (when not null) receives one entry per side that changed.
BSplineBoundary compatible_boundary(const BSplineBoundary& b, std::vector<CompatibilityNote>* notes = nullptr);

//! The first span of a compatible boundary's u knots (direction 0: bottom and top) or v knots
//! (direction 1: left and right) shorter than kMinKnotSpan, as a reason naming the two sides;
//! std::nullopt when there is none. Two valid sides whose knots are closer than kMinKnotSpan but
//! more than kSameKnot apart merge into such a span.
std::optional<std::string> merged_span_problem(const BSplineBoundary& compatible, int direction);

//! The Greville-weighted discrete Coons net of a compatible boundary (as compatible_boundary
//! returns): with ξ_i, η_j the Greville abscissae of the u and v knots on [0, 1],
//!   b_ij = (1−ξ_i) L_j + ξ_i R_j + (1−η_j) B_i + η_j T_i
//!          − [(1−ξ_i)(1−η_j) B_0 + ξ_i(1−η_j) B_last + (1−ξ_i)η_j T_0 + ξ_i η_j T_last].
//! Its surface is the bilinearly blended Coons patch of the four curves (docs/math.md §10).
//! Corners are taken from bottom and top. Sides that are not compatible: call compatible_boundary.
BSplineSurface greville_coons_surface(const BSplineBoundary& compatible);

//! The continuous bilinearly blended Coons patch of four B-spline curves at (u, v) ∈ [0, 1]²,
//! each curve taken at its normalised parameter (the reference for greville_coons_surface).
Eigen::RowVector3d coons_patch_point(const BSplineBoundary& b, double u, double v);

}  // namespace coons
