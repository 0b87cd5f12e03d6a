// Fixtures of the CAD-exchange tests and of the bundled sample files (data/cad/, made by
// scripts/make_step.sh through coons_make_step): a B-spline boundary with non-uniform knots.
#pragma once

#include "coons/surfaces/bspline_surface.h"

namespace coons::test {

//! Compatible sides over [0, 1]: bottom/top degree 3 on knots 0⁴ 0.3 0.45 1⁴ (6 points),
//! left/right degree 2 on knots 0³ 0.6 1³ (4 points), corners shared exactly.
BSplineBoundary cad_sample_boundary();

//! The time stamp written into the sample STEP files (reproducible bytes).
inline constexpr const char* kCadSampleTimeStamp = "2026-11-22T00:00:00";

}  // namespace coons::test
