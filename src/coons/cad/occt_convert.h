// Conversions between coons' B-spline value types and OpenCASCADE's Geom_BSplineCurve /
// Geom_BSplineSurface (non-rational only), and the STEP/IGES writing and reading they share.
// OpenCASCADE keeps distinct knots with multiplicities and 1-based poles; coons keeps the full
// clamped knot vector (#count + p + 1) and 0-based points. Both directions copy doubles, so a round
// trip is exact. Only coons_cad and its tests include this header (it names OCCT types).
#pragma once

#include <Geom_BSplineCurve.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Standard_Handle.hxx>
#include <TopoDS_Shape.hxx>
#include <ostream>
#include <string>

#include "coons/curves/bspline_curve.h"
#include "coons/surfaces/bspline_surface.h"

namespace coons::cad {

//! The same curve as an OpenCASCADE B-spline (c must be valid).
Handle(Geom_BSplineCurve) to_occt(const BSplineCurve& c);
//! The same surface as an OpenCASCADE B-spline (s must be valid): pole (i+1, j+1) = net.at(i, j).
Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s);

//! The same curve in coons' form; c must be non-rational and non-periodic (the full knot sequence
//! of OpenCASCADE is then clamped).
BSplineCurve from_occt(const Geom_BSplineCurve& c);
BSplineSurface from_occt(const Geom_BSplineSurface& s);

//! Silences OpenCASCADE's messages on standard output (coons prints its reports there); once.
void silence_occt_messages();

//! Writes a shape as an AP214 STEP file: reals as %.16E (17 significant digits, exact on reading),
//! the header time stamp fixed to `time_stamp` when it is not empty. Throws InputError(`target`,
//! `field`, reason) when OpenCASCADE cannot translate the shape; `field` is what the caller calls
//! the target (the CLI: the option that named it).
void write_step_shape(std::ostream& out, const TopoDS_Shape& shape, const std::string& time_stamp,
                      const std::string& target, const std::string& field);
//! The same for IGES 5.3 (entities 128/126 and the face's topology, reals as %.16E).
void write_iges_shape(std::ostream& out, const TopoDS_Shape& shape, const std::string& target,
                      const std::string& field);

//! Reads every root of a STEP or an IGES file into one shape. Throws InputError(path, "(document)",
//! reason) when the file cannot be read or holds no shape.
//! STEP: the coordinates are the file's own numbers, in its length unit, which `unit` receives
//! ("metre", "inch", …): OpenCASCADE would convert them to millimetres, and a file in metres came
//! in 1000 times larger. A unit it cannot keep (several units in one file, or one without an
//! OpenCASCADE name) is converted to millimetres as before, and `unit` says so ("millimetre
//! (converted from X)"). IGES: converted to millimetres.
TopoDS_Shape read_step_shape(const std::string& path, std::string* unit = nullptr);
TopoDS_Shape read_iges_shape(const std::string& path);

}  // namespace coons::cad
