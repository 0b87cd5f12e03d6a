#include "coons/cad/step_import.h"

#include <fmt/format.h>

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomConvert.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <ShapeAnalysis_WireOrder.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "coons/cad/occt_convert.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons::cad {

namespace {
// Corner k joins side k of the loop (bottom, right, top, left) to side k + 1.
constexpr std::array<const char*, 4> kCorner{"bottom-right", "top-right", "top-left", "bottom-left"};
constexpr std::array<const char*, 4> kSide{"bottom", "right", "top", "left"};
}  // namespace

StepImportOptionsProblem options_problem(const StepImportOptions& options) {
  using F = StepImportOptionsField;
  const std::vector<int>& edges = options.edges;
  if (options.face < -1) return {F::kFace, "must be >= 0 (faces count from 0)"};  // (−1: not given)
  if ((options.face >= 0) == !edges.empty()) return {F::kFaceOrEdges, "give exactly one of a face and four edges"};
  if (!edges.empty()) {
    if (edges.size() != 4) return {F::kEdges, fmt::format("needs 4 edge indices ({} given)", edges.size())};
    if (std::set<int>(edges.begin(), edges.end()).size() != 4) return {F::kEdges, "the 4 indices must differ"};
    for (int e : edges)
      if (e < 0) return {F::kEdges, "indices are >= 0 (edges count from 0)"};
  }
  if (!std::isfinite(options.gap_tolerance) || options.gap_tolerance < 0)
    return {F::kGapTolerance, "must be finite and >= 0"};
  return {};
}

bool StepImportOptions::is_valid(std::string* why) const {
  using F = StepImportOptionsField;
  const StepImportOptionsProblem problem = options_problem(*this);
  if (why) {
    const char* member = problem.field == F::kFace           ? "face: "
                         : problem.field == F::kEdges        ? "edges: "
                         : problem.field == F::kGapTolerance ? "gap_tolerance: "
                                                             : "";
    *why = member + problem.reason;
  }
  return problem.field == F::kNone;
}

bool StepImport::is_bezier() const {
  auto single = [](const BSplineCurve& c) { return c.count() == c.degree + 1; };
  return single(boundary.bottom) && single(boundary.top) && single(boundary.left) && single(boundary.right);
}

namespace {

BSplineCurve reversed(const BSplineCurve& c) {
  BSplineCurve r = c;
  const double a = c.start(), b = c.end();
  for (Eigen::Index k = 0; k < c.knots.size(); ++k) r.knots(k) = a + b - c.knots(c.knots.size() - 1 - k);
  r.points = c.points.colwise().reverse();
  return r;
}

// The edge's 3D curve over its parameter range as a non-rational, non-periodic B-spline.
BSplineCurve edge_curve(const TopoDS_Edge& edge, int index, const std::string& path) {
  const std::string field = fmt::format("edge {}", index);
  if (BRep_Tool::Degenerated(edge))
    throw InputError(path, field, "is degenerated (a point): a Coons side needs a curve");
  double first = 0, last = 0;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, first, last);
  if (curve.IsNull()) throw InputError(path, field, "has no 3D curve");
  Handle(Geom_BSplineCurve) bspline;
  try {
    bspline = GeomConvert::CurveToBSplineCurve(new Geom_TrimmedCurve(curve, first, last));
  } catch (const Standard_Failure& e) {
    throw InputError(path, field,
                     std::string("OpenCASCADE cannot convert its ") + curve->DynamicType()->Name() +
                         " to a B-spline: " + e.GetMessageString());
  }
  if (bspline.IsNull())
    throw InputError(path, field, std::string("its ") + curve->DynamicType()->Name() + " has no B-spline form");
  if (bspline->IsRational())
    throw InputError(path, field,
                     std::string("is rational (") + curve->DynamicType()->Name() +
                         " as a rational B-spline): rational boundaries are not supported");
  if (bspline->IsPeriodic()) bspline->SetNotPeriodic();
  BSplineCurve c = from_occt(*bspline);
  // the bounds a boundary file's points and knots are held to (json_coordinate): a pole NAN or
  // 1e400 in the STEP file was written out as null, a file coons itself then refused
  for (Eigen::Index k = 0; k < c.points.rows(); ++k)
    for (Eigen::Index d = 0; d < c.points.cols(); ++d)
      if (const std::string why = coordinate_problem(c.points(k, d)); !why.empty())
        throw InputError(path, field, fmt::format("control point {}: coordinate {} {}", k, d, why));
  for (Eigen::Index k = 0; k < c.knots.size(); ++k)
    if (!std::isfinite(c.knots(k))) throw InputError(path, field, fmt::format("knot {} is not finite", k));
  std::string why;
  if (!c.is_valid(&why)) throw InputError(path, field, "its B-spline form cannot be used: " + why);
  return c;
}

// For a face: which position in its wire holds each side (bottom, right, top, left: v = v_min,
// u = u_max, v = v_max, u = u_min of the face's parameter rectangle) and whether the side runs
// against the edge's curve (bottom and top run towards increasing u, left and right towards
// increasing v). The direction comes from the edge's curve on the face, whose parameter is its 3D
// curve's, so a closed edge (the circle of a tube, start = end) is oriented as surely as any
// other, and a seam that is both left and right (its two curves on the face) is found twice.
struct FaceSide {
  int side = -1;      //!< 0 bottom, 1 right, 2 top, 3 left; -1: on no side line
  int position = -1;  //!< in the wire
  bool reversed = false;
};

// Every edge of the wire classified, in wire order (an edge without a curve on the face: side -1).
std::vector<FaceSide> classify_face_edges(const TopoDS_Face& face, const TopoDS_Wire& wire) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  const double tol_u = 1e-9 * std::max(1.0, std::abs(u1 - u0)) + Precision::PConfusion();
  const double tol_v = 1e-9 * std::max(1.0, std::abs(v1 - v0)) + Precision::PConfusion();
  auto on = [](double line, double tol, std::initializer_list<double> values) {
    return std::all_of(values.begin(), values.end(), [&](double x) { return std::abs(x - line) <= tol; });
  };
  std::vector<FaceSide> out;
  int position = 0;
  for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next(), ++position) {
    FaceSide f;
    f.position = position;
    double first = 0, last = 0;
    const Handle(Geom2d_Curve) uv = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Current()), face, first, last);
    if (!uv.IsNull()) {
      const gp_Pnt2d a = uv->Value(first), b = uv->Value(last), m = uv->Value(0.5 * (first + last));
      if (std::abs(b.X() - a.X()) > tol_u) {  // along u: bottom or top
        if (on(v0, tol_v, {a.Y(), b.Y(), m.Y()})) f.side = 0;
        if (on(v1, tol_v, {a.Y(), b.Y(), m.Y()})) f.side = 2;
        f.reversed = b.X() < a.X();
      } else if (std::abs(b.Y() - a.Y()) > tol_v) {  // along v: left or right
        if (on(u1, tol_u, {a.X(), b.X(), m.X()})) f.side = 1;
        if (on(u0, tol_u, {a.X(), b.X(), m.X()})) f.side = 3;
        f.reversed = b.Y() < a.Y();
      }
    }
    out.push_back(f);
  }
  return out;
}

// Each side exactly one edge of four on its line, indexed by side; else nullopt.
std::optional<std::array<FaceSide, 4>> sides_of_face(const std::vector<FaceSide>& edges) {
  if (edges.size() != 4) return std::nullopt;
  std::array<FaceSide, 4> sides;
  for (const FaceSide& f : edges) {
    if (f.side < 0 || sides[std::size_t(f.side)].position >= 0) return std::nullopt;
    sides[std::size_t(f.side)] = f;
  }
  return sides;
}

gp_XYZ xyz(const Eigen::RowVector3d& p) { return {p(0), p(1), p(2)}; }

// The sides of four edges from their chain, as OpenCASCADE orders a wire's edges (3D mode),
// starting at the bottom (`start_edge`, a position in `chosen`, in the direction `start_reversed`
// says). A closed edge has no direction in a chain: refused. Closed means ends within 1e-9 of the
// edge's own extent (the diagonal of its poles' box), so that a straight edge of length 1e-9 is not
// closed while a circle is.
void chain_sides(const std::string& path, const std::vector<int>& chosen, const std::array<BSplineCurve, 4>& curves,
                 int start_edge, bool start_reversed, std::array<BSplineCurve, 4>& walk,
                 std::array<BSplineCurve, 4>& sides, StepImport& out) {
  for (int k = 0; k < 4; ++k) {
    const BSplineCurve& c = curves[k];
    const double extent = (c.points.colwise().maxCoeff() - c.points.colwise().minCoeff()).norm();
    if (extent > 0 && (c.points.row(0) - c.points.row(c.count() - 1)).norm() <= 1e-9 * extent)
      throw InputError(path, fmt::format("edge {}", chosen[k]),
                       "is closed (its ends meet), so the chain of edges cannot tell which way it runs; import the "
                       "face it bounds with --face, whose parameters orient it");
  }
  // The chain, as OpenCASCADE orders a wire's edges (3D mode).
  ShapeAnalysis_WireOrder order(Standard_True, Precision::Confusion());
  for (const auto& c : curves) order.Add(xyz(c.points.row(0)), xyz(c.points.row(c.count() - 1)));
  order.Perform(Standard_True);
  if (!order.IsDone()) throw InputError(path, "edges", "OpenCASCADE could not chain the four edges into a loop");
  std::array<int, 4> signed_order{};
  for (int k = 0; k < 4; ++k) signed_order[k] = order.Ordered(k + 1);  // 1-based, negative: reversed
  // Start at the bottom edge (the first given, or the face's v = v_min edge) in its direction.
  int start = 0;
  while (std::abs(signed_order[start]) != start_edge + 1) ++start;
  std::array<int, 4> chain{};
  for (int k = 0; k < 4; ++k) chain[k] = signed_order[(start + k) % 4];
  if ((chain[0] < 0) != start_reversed) {  // walk the loop the other way round
    const std::array<int, 4> other{-chain[0], -chain[3], -chain[2], -chain[1]};
    chain = other;
  }
  // The loop's sides head to tail. Each curve is reversed at most once (bottom and right run with
  // the loop, top and left against it), so a curve stored in the side's direction is copied exactly.
  for (int k = 0; k < 4; ++k) {
    const int e = std::abs(chain[k]) - 1;
    walk[k] = chain[k] > 0 ? curves[e] : reversed(curves[e]);
    out.edge_indices.push_back(chosen[e]);
  }
  for (int k = 0; k < 4; ++k) {
    const int e = std::abs(chain[k]) - 1;
    const bool against_loop = k >= 2;
    const bool side_reversed = (chain[k] < 0) != against_loop;  // the side runs against the edge's curve
    sides[k] = side_reversed ? reversed(curves[e]) : curves[e];
    out.edge_reversed.push_back(side_reversed);
  }
}

double diagonal_of(const std::array<BSplineCurve, 4>& curves) {
  Eigen::RowVector3d lo = curves[0].points.row(0), hi = lo;
  for (const auto& c : curves) {
    lo = lo.cwiseMin(c.points.colwise().minCoeff());
    hi = hi.cwiseMax(c.points.colwise().maxCoeff());
  }
  return (hi - lo).norm();
}

}  // namespace

namespace {

StepImport import_boundary(const std::string& path, const StepImportOptions& options) {
  if (std::string why; !options.is_valid(&why)) throw std::invalid_argument("import_step_boundary: options: " + why);
  StepImport out;
  const TopoDS_Shape shape = read_step_shape(path, &out.unit);
  TopTools_IndexedMapOfShape faces, edges;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  out.file_faces = faces.Extent();
  out.file_edges = edges.Extent();

  std::vector<int> chosen;  // the file's edge indices, 0-based
  int start_edge = 0;       // position in `chosen` of the bottom side
  bool start_reversed = false;
  std::optional<std::array<FaceSide, 4>> face_sides;  // each side from the face's own parameters
  if (options.face >= 0) {
    if (options.face >= faces.Extent())
      throw InputError(path, fmt::format("face {}", options.face),
                       faces.Extent() == 0 ? std::string("out of range: the file has no faces")
                                           : fmt::format("out of range: the file has {} face(s), 0 to {}",
                                                         faces.Extent(), faces.Extent() - 1));
    const TopoDS_Face face = TopoDS::Face(faces(options.face + 1));
    const TopoDS_Wire wire = BRepTools::OuterWire(face);
    if (wire.IsNull()) throw InputError(path, fmt::format("face {}", options.face), "has no outer wire");
    for (TopExp_Explorer e(wire, TopAbs_EDGE); e.More(); e.Next()) chosen.push_back(edges.FindIndex(e.Current()) - 1);
    if (chosen.size() != 4)
      throw InputError(path, fmt::format("face {}", options.face),
                       fmt::format("has {} edges in its outer wire; a Coons boundary needs 4", chosen.size()));
    const std::vector<FaceSide> classified = classify_face_edges(face, wire);
    face_sides = sides_of_face(classified);
    // otherwise the chain starts at the first edge along v = v_min, in +u
    for (const FaceSide& f : classified)
      if (f.side == 0) {
        start_edge = f.position;
        start_reversed = f.reversed;
        break;
      }
  } else {
    for (int e : options.edges)
      if (e >= edges.Extent())
        throw InputError(path, fmt::format("edge {}", e),
                         fmt::format("out of range: the file has {} edge(s){}", edges.Extent(),
                                     edges.Extent() ? fmt::format(", 0 to {}", edges.Extent() - 1) : ""));
    chosen = options.edges;
  }

  std::array<BSplineCurve, 4> curves;
  for (int k = 0; k < 4; ++k) curves[k] = edge_curve(TopoDS::Edge(edges(chosen[k] + 1)), chosen[k], path);
  out.diagonal = diagonal_of(curves);

  std::array<BSplineCurve, 4> walk;   // the loop's sides head to tail
  std::array<BSplineCurve, 4> sides;  // bottom, right, top, left in their own directions
  if (face_sides) {
    for (int k = 0; k < 4; ++k) {
      const int e = (*face_sides)[std::size_t(k)].position;
      const bool side_reversed = (*face_sides)[std::size_t(k)].reversed;
      sides[k] = side_reversed ? reversed(curves[e]) : curves[e];
      walk[k] = k < 2 ? sides[k] : reversed(sides[k]);
      out.edge_indices.push_back(chosen[e]);
      out.edge_reversed.push_back(side_reversed);
    }
  } else {
    chain_sides(path, chosen, curves, start_edge, start_reversed, walk, sides, out);
  }

  // Corner k joins the end of walk[k] to the start of walk[k + 1].
  const double limit = options.gap_tolerance * out.diagonal;
  for (int k = 0; k < 4; ++k) {
    const BSplineCurve& a = walk[k];
    const BSplineCurve& b = walk[(k + 1) % 4];
    const double gap = (a.points.row(a.count() - 1) - b.points.row(0)).norm();
    out.gaps.push_back(
        {kCorner[k], fmt::format("edge {} -> edge {}", out.edge_indices[k], out.edge_indices[(k + 1) % 4]), gap});
    out.max_gap = std::max(out.max_gap, gap);
    if (!(gap <= limit))
      throw InputError(path, std::string("corner ") + kCorner[k],
                       fmt::format("gap {:.6g} between edge {} and edge {} exceeds the tolerance {:.3g} x diagonal "
                                   "{:.6g} = {:.6g} (--gap-tolerance)",
                                   gap, out.edge_indices[k], out.edge_indices[(k + 1) % 4], options.gap_tolerance,
                                   out.diagonal, limit));
  }
  // Close the gaps at their midpoints (the clamped ends are the curves' end points).
  BSplineBoundary raw{sides[0], sides[2], sides[3], sides[1]};
  auto close = [](auto a, auto b) {  // two rows (block views) of the sides' points
    if (a == b) return;
    const Eigen::RowVector3d mid = 0.5 * (a + b);
    a = mid;
    b = mid;
  };
  close(raw.bottom.points.row(0), raw.left.points.row(0));
  close(raw.bottom.points.row(raw.bottom.count() - 1), raw.right.points.row(0));
  close(raw.top.points.row(0), raw.left.points.row(raw.left.count() - 1));
  close(raw.top.points.row(raw.top.count() - 1), raw.right.points.row(raw.right.count() - 1));
  // Opposite knots that differ by rounding only (a reversed curve's knots are a + b − u) become
  // one knot in compatible_boundary (kSameKnot), so none is inserted twice a rounding error apart.
  out.boundary = compatible_boundary(raw, &out.notes);
  for (const int direction : {0, 1})
    if (const auto why = merged_span_problem(out.boundary, direction)) {
      const int first = direction == 0 ? 0 : 3;  // bottom and top, left and right in `sides`
      const int second = direction == 0 ? 2 : 1;
      throw InputError(path, fmt::format("edges {} and {}", out.edge_indices[first], out.edge_indices[second]), *why);
    }
  return out;
}

}  // namespace

StepImport import_step_boundary(const std::string& path, const StepImportOptions& options) {
  try {
    return import_boundary(path, options);
  } catch (const Standard_Failure& e) {
    throw InputError(path, kDocumentField, std::string("OpenCASCADE failed: ") + e.GetMessageString());
  }
}

namespace {

nlohmann::json points_json(const Eigen::MatrixX3d& P) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index i = 0; i < P.rows(); ++i) rows.push_back({P(i, 0), P(i, 1), P(i, 2)});
  return rows;
}

nlohmann::json knots_json(const Eigen::VectorXd& U) {
  nlohmann::json knots = nlohmann::json::array();
  for (Eigen::Index k = 0; k < U.size(); ++k) knots.push_back(U(k));
  return knots;
}

}  // namespace

nlohmann::json import_note(const StepImport& import) {
  nlohmann::json chain = nlohmann::json::array();
  for (std::size_t k = 0; k < import.edge_indices.size(); ++k)
    chain.push_back(
        {{"side", kSide[k]}, {"edge", import.edge_indices[k]}, {"reversed", bool(import.edge_reversed[k])}});
  nlohmann::json gaps = nlohmann::json::array();
  for (const auto& g : import.gaps) gaps.push_back({{"corner", g.corner}, {"edges", g.edges}, {"gap", g.gap}});
  nlohmann::json notes = nlohmann::json::array();
  for (const auto& n : import.notes)
    notes.push_back({{"side", n.side}, {"degree_raised_by", n.degree_raised_by}, {"knots_inserted", n.knots_inserted}});
  return {{"file_faces", import.file_faces},
          {"file_edges", import.file_edges},
          {"chain", chain},
          {"corner_gaps", gaps},
          {"max_gap", import.max_gap},
          {"diagonal", import.diagonal},
          {"unit", import.unit},
          {"compatibility", notes},
          {"form", import.is_bezier() ? "bezier" : "bspline"}};
}

nlohmann::json boundary_document(const StepImport& import, const std::string& name, const std::string& source) {
  const BSplineBoundary& b = import.boundary;
  nlohmann::json doc = {{"name", name}, {"source", source}};
  doc["degree"] = {b.bottom.count() - 1, b.left.count() - 1};
  if (!import.is_bezier()) {
    doc["degree_spline"] = {b.bottom.degree, b.left.degree};
    doc["knots_u"] = knots_json(b.bottom.knots);
    doc["knots_v"] = knots_json(b.left.knots);
  }
  doc["bottom"] = points_json(b.bottom.points);
  doc["top"] = points_json(b.top.points);
  doc["left"] = points_json(b.left.points);
  doc["right"] = points_json(b.right.points);
  doc["import"] = import_note(import);
  return doc;
}

}  // namespace coons::cad
