#include "coons/cad/occt_convert.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <APIHeaderSection_MakeHeader.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESControl_Writer.hxx>
#include <IGESData_IGESModel.hxx>
#include <IGESData_IGESWriter.hxx>
#include <IGESSelect_WorkLibrary.hxx>
#include <Interface_Check.hxx>
#include <Interface_CheckIterator.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <Standard_Failure.hxx>
#include <StepData_Protocol.hxx>
#include <StepData_StepModel.hxx>
#include <StepData_StepWriter.hxx>
#include <StepGeom_Curve.hxx>
#include <StepGeom_Surface.hxx>
#include <StepShape_TopologicalRepresentationItem.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TCollection_HAsciiString.hxx>
#include <Transfer_TransientProcess.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons::cad {

namespace {

// Distinct knots and their multiplicities as OpenCASCADE arrays (1-based).
std::pair<TColStd_Array1OfReal, TColStd_Array1OfInteger> occt_knots(const Eigen::VectorXd& knots) {
  const auto distinct = knot_multiplicities(knots);
  TColStd_Array1OfReal values(1, int(distinct.size()));
  TColStd_Array1OfInteger mults(1, int(distinct.size()));
  for (std::size_t k = 0; k < distinct.size(); ++k) {
    values(int(k) + 1) = distinct[k].first;
    mults(int(k) + 1) = distinct[k].second;
  }
  return {values, mults};
}

Eigen::VectorXd full_knots(const TColStd_Array1OfReal& sequence) {
  Eigen::VectorXd knots(sequence.Length());
  for (int k = sequence.Lower(); k <= sequence.Upper(); ++k) knots(k - sequence.Lower()) = sequence(k);
  return knots;
}

// Every real as %.16E: 17 significant digits, so that strtod on reading gives the same double.
// Zero suppression stays off: OpenCASCADE's suppression cuts the exponent of long mantissas.
void exact_reals(Interface_FloatWriter& writer) {
  writer.SetFormat("%.16E");
  writer.SetZeroSuppress(Standard_False);
}

}  // namespace

Handle(Geom_BSplineCurve) to_occt(const BSplineCurve& c) {
  TColgp_Array1OfPnt poles(1, c.count());
  for (int i = 0; i < c.count(); ++i) poles(i + 1) = gp_Pnt(c.points(i, 0), c.points(i, 1), c.points(i, 2));
  const auto [knots, mults] = occt_knots(c.knots);
  return new Geom_BSplineCurve(poles, knots, mults, c.degree);
}

Handle(Geom_BSplineSurface) to_occt(const BSplineSurface& s) {
  TColgp_Array2OfPnt poles(1, s.net.m + 1, 1, s.net.n + 1);
  for (int i = 0; i <= s.net.m; ++i)
    for (int j = 0; j <= s.net.n; ++j) {
      const auto p = s.net.at(i, j);
      poles(i + 1, j + 1) = gp_Pnt(p(0), p(1), p(2));
    }
  const auto [ku, mu] = occt_knots(s.knots_u);
  const auto [kv, mv] = occt_knots(s.knots_v);
  return new Geom_BSplineSurface(poles, ku, kv, mu, mv, s.degree_u, s.degree_v);
}

BSplineCurve from_occt(const Geom_BSplineCurve& c) {
  BSplineCurve out;
  out.degree = c.Degree();
  TColStd_Array1OfReal sequence(1, c.NbPoles() + c.Degree() + 1);
  c.KnotSequence(sequence);
  out.knots = full_knots(sequence);
  out.points.resize(c.NbPoles(), 3);
  for (int i = 1; i <= c.NbPoles(); ++i) {
    const gp_Pnt& p = c.Pole(i);
    out.points.row(i - 1) << p.X(), p.Y(), p.Z();
  }
  return out;
}

BSplineSurface from_occt(const Geom_BSplineSurface& s) {
  BSplineSurface out;
  out.degree_u = s.UDegree();
  out.degree_v = s.VDegree();
  TColStd_Array1OfReal su(1, s.NbUPoles() + s.UDegree() + 1), sv(1, s.NbVPoles() + s.VDegree() + 1);
  s.UKnotSequence(su);
  s.VKnotSequence(sv);
  out.knots_u = full_knots(su);
  out.knots_v = full_knots(sv);
  out.net = ControlNet(s.NbUPoles() - 1, s.NbVPoles() - 1);
  for (int i = 1; i <= s.NbUPoles(); ++i)
    for (int j = 1; j <= s.NbVPoles(); ++j) {
      const gp_Pnt& p = s.Pole(i, j);
      out.net.at(i - 1, j - 1) << p.X(), p.Y(), p.Z();
    }
  return out;
}

void silence_occt_messages() {
  static std::once_flag once;
  std::call_once(once, [] { Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream)); });
}

void write_step_shape(std::ostream& out, const TopoDS_Shape& shape, const std::string& time_stamp,
                      const std::string& target, const std::string& field) {
  silence_occt_messages();
  STEPControl_Writer writer;
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    throw InputError(target, field, "OpenCASCADE could not translate the surface to STEP");
  const Handle(StepData_StepModel) model = writer.Model();
  if (!time_stamp.empty()) {
    APIHeaderSection_MakeHeader header(model);
    header.SetTimeStamp(new TCollection_HAsciiString(time_stamp.c_str()));
    header.Apply(model);
  }
  StepData_StepWriter step(model);
  exact_reals(step.FloatWriter());
  step.SendModel(Handle(StepData_Protocol)::DownCast(writer.WS()->Protocol()));
  if (!step.Print(out)) throw InputError(target, field, "OpenCASCADE could not print the STEP file");
}

void write_iges_shape(std::ostream& out, const TopoDS_Shape& shape, const std::string& target,
                      const std::string& field) {
  silence_occt_messages();
  IGESControl_Writer writer("MM", 0);
  if (!writer.AddShape(shape)) throw InputError(target, field, "OpenCASCADE could not translate the surface to IGES");
  writer.ComputeModel();
  IGESData_IGESWriter iges(writer.Model());
  exact_reals(iges.FloatWriter());
  iges.SendModel(IGESSelect_WorkLibrary::DefineProtocol());
  if (!iges.Print(out)) throw InputError(target, field, "OpenCASCADE could not print the IGES file");
}

namespace {

void require_readable(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path, kDocumentField, "cannot be read (not an existing regular file)");
  std::ifstream probe(path);
  if (!probe) throw InputError(path, kDocumentField, "cannot be read");
}

// The field of a check's error: "entity #47" (the file's label of the entity), or "model".
std::string check_field(XSControl_Reader& reader, const Handle(Standard_Transient) & entity) {
  if (!entity.IsNull() && !reader.Model().IsNull()) {
    const Handle(TCollection_HAsciiString) label = reader.Model()->StringLabel(entity);
    if (!label.IsNull()) return std::string("entity ") + label->ToCString();
  }
  return "model";
}

// The first failure OpenCASCADE's reader noted while loading the file (an unresolved reference
// "#999", an entity of the wrong type, a parameter it could not read), named by its entity:
// transferring such a model dereferences the missing entity (a segfault in StepToGeom for a
// B-spline curve whose control point is #999). Warnings are let through.
void require_no_load_failure(const std::string& path, XSControl_Reader& reader) {
  Interface_CheckIterator checks = reader.WS()->ModelCheckList(Standard_False);
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& check = checks.Value();
    if (check.IsNull() || !check->HasFailed()) continue;
    const std::string what = check->NbFails() > 0 ? check->CFail(1, Standard_True) : "unreadable entity";
    throw InputError(path, check_field(reader, check->Entity()), "OpenCASCADE cannot load it: " + what);
  }
}

// The first entity OpenCASCADE's transfer failed on: a fail in its check list, or a curve, surface
// or topological item the transfer left "not mapped to TopoDS" (a B-spline curve whose
// multiplicities do not add up to its poles and degree: the exception is only printed, and the
// check keeps a warning). The reader leaves such an entity out of the shape, so that the faces and
// edges after it would be numbered one lower than in the file: refused, named.
void require_no_transfer_failure(const std::string& path, XSControl_Reader& reader) {
  const Handle(XSControl_TransferReader) transfer = reader.WS()->TransferReader();
  if (transfer.IsNull() || transfer->TransientProcess().IsNull()) return;
  Interface_CheckIterator checks = transfer->TransientProcess()->CheckList(Standard_False);
  for (checks.Start(); checks.More(); checks.Next()) {
    const Handle(Interface_Check)& check = checks.Value();
    if (check.IsNull()) continue;
    const Handle(Standard_Transient)& entity = check->Entity();
    const bool geometry = !entity.IsNull() && (entity->IsKind(STANDARD_TYPE(StepGeom_Curve)) ||
                                               entity->IsKind(STANDARD_TYPE(StepGeom_Surface)) ||
                                               entity->IsKind(STANDARD_TYPE(StepShape_TopologicalRepresentationItem)));
    std::string what;
    if (check->HasFailed())
      what = check->NbFails() > 0 ? check->CFail(1, Standard_True) : "no reason given";
    else if (geometry)
      for (int k = 1; k <= check->NbWarnings() && what.empty(); ++k)
        if (std::string(check->CWarning(k, Standard_False)).find("Entity not mapped to TopoDS") != std::string::npos)
          what = "left out of the shape: a B-spline whose poles, degree and multiplicities disagree, for one";
    if (what.empty()) continue;
    throw InputError(path, check_field(reader, entity),
                     "OpenCASCADE cannot translate it (" + what +
                         "); the faces and edges after it would be numbered one lower than in the file");
  }
}

}  // namespace

namespace {

std::string lower_case(std::string name) {
  for (char& c : name) c = char(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

// OpenCASCADE's name of a STEP length unit (STEPControl_Reader::FileUnits: SI units as
// "millimetre", conversion-based ones as the file spells them, "INCH") as a value of its
// "xstep.cascade.unit" parameter, the unit the transfer converts to; empty when it has none.
std::string cascade_unit(const std::string& name) {
  static const std::map<std::string, std::string> units = {
      {"millimetre", "MM"}, {"millimeter", "MM"}, {"metre", "M"},      {"meter", "M"},       {"centimetre", "CM"},
      {"centimeter", "CM"}, {"kilometre", "KM"},  {"kilometer", "KM"}, {"micrometre", "UM"}, {"micrometer", "UM"},
      {"inch", "INCH"},     {"foot", "FT"},       {"mile", "MI"},      {"mil", "MIL"},       {"microinch", "UIN"}};
  const auto it = units.find(lower_case(name));
  return it == units.end() ? std::string() : it->second;
}

}  // namespace

TopoDS_Shape read_step_shape(const std::string& path, std::string* unit) {
  silence_occt_messages();
  require_readable(path);
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    throw InputError(path, kDocumentField, "OpenCASCADE cannot read it as a STEP file");
  require_no_load_failure(path, reader);
  TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
  reader.FileUnits(lengths, angles, solid_angles);
  std::set<std::string> names;  // lower case; a context without a length unit gives an empty name
  for (int k = 1; k <= lengths.Length(); ++k)
    if (const std::string name = lower_case(lengths(k).ToCString()); !name.empty()) names.insert(name);
  const std::string file_unit = names.size() == 1 ? *names.begin() : std::string();
  const std::string keep = cascade_unit(file_unit);
  // A process-wide parameter of OpenCASCADE: set for this transfer only, and put back.
  const std::string previous = Interface_Static::CVal("xstep.cascade.unit");
  Interface_Static::SetCVal("xstep.cascade.unit", keep.empty() ? "MM" : keep.c_str());
  const int transferred = reader.TransferRoots();
  Interface_Static::SetCVal("xstep.cascade.unit", previous.c_str());
  require_no_transfer_failure(path, reader);
  if (unit) {
    if (!keep.empty())
      *unit = file_unit;
    else
      *unit = names.empty() ? std::string("millimetre")
                            : "millimetre (converted from " + fmt::format("{}", fmt::join(names, ", ")) + ")";
  }
  if (transferred == 0) throw InputError(path, kDocumentField, "the STEP file holds no shape");
  TopoDS_Shape shape = reader.OneShape();
  if (shape.IsNull()) throw InputError(path, kDocumentField, "the STEP file holds no shape");
  return shape;
}

TopoDS_Shape read_iges_shape(const std::string& path) {
  silence_occt_messages();
  require_readable(path);
  IGESControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone)
    throw InputError(path, kDocumentField, "OpenCASCADE cannot read it as an IGES file");
  require_no_load_failure(path, reader);
  const int transferred = reader.TransferRoots();
  require_no_transfer_failure(path, reader);
  if (transferred == 0) throw InputError(path, kDocumentField, "the IGES file holds no shape");
  TopoDS_Shape shape = reader.OneShape();
  if (shape.IsNull()) throw InputError(path, kDocumentField, "the IGES file holds no shape");
  return shape;
}

}  // namespace coons::cad
