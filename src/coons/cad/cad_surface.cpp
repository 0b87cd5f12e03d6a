#include "coons/cad/cad_surface.h"

#include <fmt/format.h>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GeomConvert.hxx>
#include <Geom_BezierSurface.hxx>
#include <Geom_Surface.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <cmath>

#include "coons/cad/occt_convert.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons::cad {

BSplineSurface bezier_as_bspline(const ControlNet& net) {
  BSplineSurface s;
  s.degree_u = net.m;
  s.degree_v = net.n;
  s.knots_u.resize(2 * (net.m + 1));
  s.knots_u << Eigen::VectorXd::Zero(net.m + 1), Eigen::VectorXd::Ones(net.m + 1);
  s.knots_v.resize(2 * (net.n + 1));
  s.knots_v << Eigen::VectorXd::Zero(net.n + 1), Eigen::VectorXd::Ones(net.n + 1);
  s.net = net;
  return s;
}

namespace {

bool exactly_printable(double x) {
  const double a = std::abs(x);
  return a == 0 || (a >= 1e-99 && a < 1e99);
}

}  // namespace

void check_writable(const BSplineSurface& s, const std::string& target, const std::string& field) {
  std::string why;
  if (!s.is_valid(&why)) throw InputError(target, field, "the surface is not a valid B-spline: " + why);
  if (const int limit = Geom_BSplineSurface::MaxDegree(); s.degree_u > limit || s.degree_v > limit)
    throw InputError(target, field,
                     fmt::format("the surface's degree ({}, {}) exceeds OpenCASCADE's B-spline limit {}, so it "
                                 "cannot be written as STEP or IGES",
                                 s.degree_u, s.degree_v, limit));
  for (Eigen::Index k = 0; k < s.net.points.size(); ++k) {
    const double x = s.net.points.data()[k];
    if (!std::isfinite(x) || !exactly_printable(x))
      throw InputError(target, field,
                       fmt::format("a coordinate of the net is {:g}: only 0 and magnitudes in [1e-99, 1e99) are "
                                   "written exactly (17 digits, two-digit exponent)",
                                   x));
  }
  for (const Eigen::VectorXd* knots : {&s.knots_u, &s.knots_v})
    for (Eigen::Index k = 0; k < knots->size(); ++k)
      if (!exactly_printable((*knots)(k)))
        throw InputError(
            target, field,
            fmt::format("knot {:g}: only 0 and magnitudes in [1e-99, 1e99) are written exactly", (*knots)(k)));
}

namespace {

TopoDS_Face face_of(const BSplineSurface& s) {
  BRepBuilderAPI_MakeFace make(to_occt(s), Precision::Confusion());
  return make.Face();
}

std::vector<BSplineSurface> surfaces_of(const TopoDS_Shape& shape, const std::string& path) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  std::vector<BSplineSurface> out;
  for (int k = 1; k <= faces.Extent(); ++k) {
    const Handle(Geom_Surface) surface = BRep_Tool::Surface(TopoDS::Face(faces(k)));
    Handle(Geom_BSplineSurface) bspline = Handle(Geom_BSplineSurface)::DownCast(surface);
    if (bspline.IsNull() && !Handle(Geom_BezierSurface)::DownCast(surface).IsNull())
      bspline = GeomConvert::SurfaceToBSplineSurface(surface);
    const std::string field = fmt::format("face {}", k - 1);
    if (bspline.IsNull())
      throw InputError(path, field, std::string("is a ") + surface->DynamicType()->Name() + ", not a B-spline surface");
    if (bspline->IsURational() || bspline->IsVRational())
      throw InputError(path, field, "is a rational B-spline surface (not supported)");
    if (bspline->IsUPeriodic() || bspline->IsVPeriodic()) {
      bspline = Handle(Geom_BSplineSurface)::DownCast(bspline->Copy());
      bspline->SetUNotPeriodic();
      bspline->SetVNotPeriodic();
    }
    out.push_back(from_occt(*bspline));
  }
  return out;
}

}  // namespace

void write_step_surface(std::ostream& out, const BSplineSurface& s, const std::string& target, const std::string& field,
                        const std::string& time_stamp) {
  check_writable(s, target, field);
  try {
    write_step_shape(out, face_of(s), time_stamp, target, field);
  } catch (const Standard_Failure& e) {
    throw InputError(target, field, std::string("OpenCASCADE refuses the surface: ") + e.GetMessageString());
  }
}

void write_iges_surface(std::ostream& out, const BSplineSurface& s, const std::string& target,
                        const std::string& field) {
  check_writable(s, target, field);
  try {
    write_iges_shape(out, face_of(s), target, field);
  } catch (const Standard_Failure& e) {
    throw InputError(target, field, std::string("OpenCASCADE refuses the surface: ") + e.GetMessageString());
  }
}

void write_step_edges(std::ostream& out, const std::vector<BSplineCurve>& curves, const std::string& target,
                      const std::string& field, const std::string& time_stamp) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  try {
    for (const auto& c : curves) builder.Add(compound, BRepBuilderAPI_MakeEdge(to_occt(c)).Edge());
    write_step_shape(out, compound, time_stamp, target, field);
  } catch (const Standard_Failure& e) {
    throw InputError(target, field, std::string("OpenCASCADE refuses the curves: ") + e.GetMessageString());
  }
}

std::vector<BSplineSurface> read_step_surfaces(const std::string& path) {
  try {
    return surfaces_of(read_step_shape(path), path);
  } catch (const Standard_Failure& e) {
    throw InputError(path, kDocumentField, std::string("OpenCASCADE failed: ") + e.GetMessageString());
  }
}

std::vector<BSplineSurface> read_iges_surfaces(const std::string& path) {
  try {
    return surfaces_of(read_iges_shape(path), path);
  } catch (const Standard_Failure& e) {
    throw InputError(path, kDocumentField, std::string("OpenCASCADE failed: ") + e.GetMessageString());
  }
}

}  // namespace coons::cad
