// The analytic sides of a boundary file (its "curves" object) and their fit at any degree, with
// the checks that make a bad file an input error (docs/formats.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "coons/curves/boundary_fit.h"
#include "coons/curves/curve.h"

namespace coons {

//! The "curves" object of a boundary file ({"bottom": curve, "top": …, "left": …, "right": …},
//! curves as in docs/formats.md), or nullopt when the file has none. Bad curves throw InputError.
std::optional<std::vector<Curve>> read_boundary_curves(const std::string& path);

//! fit_boundary, and InputError (naming `source` and the curve) when a fit is not finite (a pole
//! between the reader's samples), or (naming the corner) when the curves do not meet at the corners
//! to 1e-9 of the boundary's size.
FittedBoundary fit_boundary_or_throw(const std::vector<Curve>& sides, int m, int n, const std::string& name,
                                     const std::string& source);

}  // namespace coons
