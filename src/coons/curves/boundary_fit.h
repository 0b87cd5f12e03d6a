// Boundaries from curves: the four sides of a boundary given as curves (Bézier or analytic), fitted
// at any degree (m, n) by Bézier curves through the end points (fit_bezier), with the shared
// corners made bit-identical. This is how a shape given analytically is studied at degrees 3 … 16
// and more; Bézier sides of lower degree are elevated exactly.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), §6.1, §9; docs/math.md §4.
#pragma once

#include <string>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/net/control_net.h"

namespace coons {

struct FittedBoundary {
  Boundary boundary;
  double max_deviation = 0;  //!< largest deviation of a fitted side from its curve
  CornerGap corner_gap;      //!< the largest gap between fitted sides at a corner (before closing it)
  bool corners_meet = true;  //!< corner_gap ≤ 1e-9 of the boundary's size (else the boundary is unusable)
};

//! sides = {bottom, top, left, right} (bottom/top in u, left/right in v). m, n ≥ 1. When the curves
//! meet at the corners (corners_meet), the shared corners are made bit-identical. Reading the curves
//! from a file and refusing a gap is io's job (coons/io/boundary_curves.h).
FittedBoundary fit_boundary(const std::vector<Curve>& sides, int m, int n, const std::string& name);

}  // namespace coons
