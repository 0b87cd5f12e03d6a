// The B-spline fields of a boundary file (docs/formats.md, "B-spline boundaries"):
// "degree_spline": [p, q], "knots_u" (bottom/top, #m+1 + p + 1 knots) and "knots_v" (left/right,
// #n+1 + q + 1 knots), where m + 1 and n + 1 are the point counts of the sides. A knot field may
// also be an object with one vector per side ({"bottom": [...], "top": [...]} for knots_u,
// {"left": [...], "right": [...]} for knots_v): opposite sides on different knots, made compatible
// exactly (compatible_boundary) before anything is solved. Parsed and validated here;
// parse_boundary (boundary_io.h) calls it for the sides form.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/net/control_net.h"
#include "coons/surfaces/bspline_surface.h"

namespace coons {

struct BSplineKnots {
  int degree_u = 1, degree_v = 1;    //!< p (bottom/top), q (left/right)
  Eigen::VectorXd knots_u, knots_v;  //!< bottom and left: #count_u + p + 1, #count_v + q + 1
  //! top and right when the file gave them per side; empty: the same as knots_u / knots_v.
  Eigen::VectorXd knots_top, knots_right;
};

//! The sides of a B-spline boundary file as given, and made compatible over [0, 1]² (opposite
//! sides on the same degree and knots), with what that changed.
struct BSplineInput {
  BSplineBoundary given;
  BSplineBoundary compatible;
  std::vector<CompatibilityNote> notes;  //!< empty when the sides were compatible already
};

//! The three fields when the document has any of them, std::nullopt when it has none. Throws
//! InputError("source", field, reason) when one is missing while another is present, when
//! degree_spline is not two integers in [1, 64], and for every rule of knot_vector_problems, with
//! the field naming the knot ("knots_u[4]", "knots_u.top[2]") or the whole vector ("knots_u").
std::optional<BSplineKnots> parse_bspline_knots(const nlohmann::json& doc, const std::string& source, int count_u,
                                                int count_v);

//! The four sides of a boundary as B-spline curves on those knots (bottom/top on knots_u,
//! left/right on knots_v).
BSplineBoundary bspline_boundary(const Boundary& boundary, const BSplineKnots& knots);

//! bspline_boundary, then compatible_boundary with its notes. Throws InputError(source,
//! "knots_u" or "knots_v", reason) when the per-side knots merge into a span shorter than
//! kMinKnotSpan (merged_span_problem).
BSplineInput bspline_input(const Boundary& boundary, const BSplineKnots& knots, const std::string& source);

}  // namespace coons
