// A tensor B-spline surface (coons' BSplineSurface: a net and two clamped knot vectors) written to
// STEP (AP214) and IGES through OpenCASCADE as one face bounded by its natural edges, and read
// back from such files. Reals are written with 17 significant digits, so a written surface reads
// back with the same poles and knots, bit for bit (tests/cad/cad_surface_test.cpp).
// A Bézier net of degree (m, n) is the B-spline with single-span clamped knots 0^(m+1) 1^(m+1).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "coons/net/control_net.h"
#include "coons/surfaces/bspline_surface.h"

namespace coons::cad {

//! The Bézier surface of `net` as a B-spline: degrees (m, n), knots {0 ×(m+1), 1 ×(m+1)} and
//! {0 ×(n+1), 1 ×(n+1)}.
BSplineSurface bezier_as_bspline(const ControlNet& net);

//! Throws InputError(target, field, reason) when the surface cannot be written exactly: invalid
//! knots, a non-finite value, or a non-zero magnitude outside [1e-99, 1e99] (17-digit reals with a
//! two-digit exponent: OpenCASCADE formats each real into 24 characters). `field` is what the
//! caller calls the target (the CLI: the option that named it), here and in the writers below.
void check_writable(const BSplineSurface& s, const std::string& target, const std::string& field);

//! One face (the whole surface) as STEP, after check_writable. The header's time stamp is the
//! current time when `time_stamp` is empty, else `time_stamp` (reproducible files).
void write_step_surface(std::ostream& out, const BSplineSurface& s, const std::string& target, const std::string& field,
                        const std::string& time_stamp = {});
//! The same face as IGES, after check_writable.
void write_iges_surface(std::ostream& out, const BSplineSurface& s, const std::string& target,
                        const std::string& field);

//! Curves as free STEP edges (one compound, in the given order; a wireframe model) with a fixed
//! header time stamp when `time_stamp` is not empty: sample files for import-step.
void write_step_edges(std::ostream& out, const std::vector<BSplineCurve>& curves, const std::string& target,
                      const std::string& field, const std::string& time_stamp = {});

//! The surfaces of every face of a STEP or IGES file, in the order OpenCASCADE lists the faces.
//! Throws InputError(path, "face K", reason) for a face whose surface is not a non-rational
//! B-spline (after conversion of a Bézier surface), and the errors of read_step_shape.
std::vector<BSplineSurface> read_step_surfaces(const std::string& path);
std::vector<BSplineSurface> read_iges_surfaces(const std::string& path);

}  // namespace coons::cad
