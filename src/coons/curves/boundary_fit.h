// Boundaries from curves: the four sides of a boundary given as curves (Bézier or analytic), fitted
// at any degree (m, n) by Bézier curves through the end points (fit_bezier), with the shared
// corners made bit-identical. This is how a shape given analytically is studied at degrees 3 … 16
// and more; Bézier sides of lower degree are elevated exactly.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), §6.1, §9; docs/math.md §4.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/net/control_net.h"

namespace coons {

struct FittedBoundary {
  Boundary boundary;
  double max_deviation = 0;  //!< largest deviation of a fitted side from its curve
};

//! sides = {bottom, top, left, right} (bottom/top in u, left/right in v). m, n ≥ 1. Throws
//! InputError (naming `source` and the corner) when the curves do not meet at the corners to
//! 1e-9 of the boundary's size.
FittedBoundary fit_boundary(const std::vector<Curve>& sides, int m, int n, const std::string& name,
                            const std::string& source = "curves");

//! The "curves" object of a boundary file ({"bottom": curve, "top": …, "left": …, "right": …},
//! curves as in docs/formats.md), or nullopt when the file has none. Bad curves throw InputError.
std::optional<std::vector<Curve>> read_boundary_curves(const std::string& path);

}  // namespace coons
