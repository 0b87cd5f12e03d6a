// A tensor B-spline surface as a SurfacePoint (value and derivatives up to order 2) and sampled on
// a k × k grid like any surface of sampling.h, so the OBJ/PLY/VTS writers of mesh_export.h take it.
// Parameters (s, t) ∈ [0, 1]² are mapped affinely onto the knot domain; derivatives are with
// respect to (s, t).
// Based on: L. Piegl, W. Tiller, The NURBS Book (1997), A3.6 (surface derivatives).
#pragma once

#include "coons/net/surface_point.h"
#include "coons/surfaces/bspline_surface.h"
#include "coons/surfaces/sampling.h"

namespace coons {

//! r, r_s, r_t, r_ss, r_st, r_tt at (s, t) ∈ [0, 1]².
SurfacePoint bspline_surface_point(const BSplineSurface& surface, double s, double t);

//! k ≥ 2: sample a·k + b at (a/(k−1), b/(k−1)), normals, curvatures and twist as sample_grid.
SurfaceSamples sample_bspline_grid(const BSplineSurface& surface, int k);

}  // namespace coons
