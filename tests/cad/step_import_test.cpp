// import_step_boundary: four edges of a STEP file (a face's outer wire or edges by index) as a
// compatible B-spline boundary; the bundled samples of data/cad/; the input errors.
#include "coons/cad/step_import.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRep_Builder.hxx>
#include <GC_MakeArcOfCircle.hxx>
#include <Geom_BSplineSurface.hxx>
#include <Interface_Static.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <sstream>
#include <tuple>

#include "cad_fixtures.h"
#include "coons/cad/cad_surface.h"
#include "coons/cad/occt_convert.h"
#include "coons/io/input_error.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;

namespace {

BSplineCurve reversed(BSplineCurve c) {
  c.points = c.points.colwise().reverse().eval();
  const double a = c.start(), e = c.end();
  c.knots = (a + e - c.knots.reverse().array()).matrix().eval();  // eval: no aliasing
  return c;
}

void require_same_curve(const BSplineCurve& a, const BSplineCurve& b, double knot_tolerance) {
  REQUIRE(a.degree == b.degree);
  REQUIRE(a.count() == b.count());
  CHECK(a.points == b.points);
  CHECK((a.knots - b.knots).cwiseAbs().maxCoeff() <= knot_tolerance);
}

void require_same_boundary(const BSplineBoundary& a, const BSplineBoundary& b, double knot_tolerance) {
  require_same_curve(a.bottom, b.bottom, knot_tolerance);
  require_same_curve(a.top, b.top, knot_tolerance);
  require_same_curve(a.left, b.left, knot_tolerance);
  require_same_curve(a.right, b.right, knot_tolerance);
}

std::string write_edges(const test::TempDir& dir, const std::string& name, const std::vector<BSplineCurve>& curves) {
  std::string path = dir.file(name);
  std::ofstream out(path);
  cad::write_step_edges(out, curves, path, "edges");
  return path;
}

std::string write_shape(const test::TempDir& dir, const std::string& name, const TopoDS_Shape& shape) {
  std::string path = dir.file(name);
  std::ofstream out(path);
  cad::write_step_shape(out, shape, "", path, "shape");
  return path;
}

cad::StepImportOptions face(int k) {
  cad::StepImportOptions o;
  o.face = k;
  return o;
}

cad::StepImportOptions edges(std::vector<int> e) {
  cad::StepImportOptions o;
  o.edges = std::move(e);
  return o;
}

}  // namespace

TEST_CASE("import_step_boundary: a face written from a Greville net gives back its boundary", "[cad]") {
  const test::TempDir dir;
  for (std::uint32_t seed : {1U, 2U, 3U}) {
    // compatible sides over [0, 1] (the form import returns)
    const BSplineBoundary b = compatible_boundary(test::make_random_bspline_boundary(2 + int(seed % 2), 5, 3, 4, seed));
    const std::string path = dir.file("face.step");
    {
      std::ofstream out(path);
      cad::write_step_surface(out, greville_coons_surface(b), path, "surface");
    }
    const cad::StepImport import = cad::import_step_boundary(path, face(0));
    INFO("seed " << seed);
    // exact, poles and knots: the surface's boundary rows and columns (its corners come from bottom
    // and top, while b.left and b.right may differ there by rounding after degree elevation)
    require_same_boundary(import.boundary, boundary_of(greville_coons_surface(b)), 0.0);
    CHECK(import.max_gap == 0);
    CHECK(import.file_faces == 1);
    CHECK(import.notes.empty());
    CHECK_FALSE(import.is_bezier());
  }
}

TEST_CASE("import_step_boundary: four edges in any order and orientation give one boundary", "[cad]") {
  const test::TempDir dir;
  const BSplineBoundary b = test::cad_sample_boundary();
  // the sides as a loop: bottom, right, top reversed, left reversed
  const std::vector<BSplineCurve> loop = {b.bottom, b.right, reversed(b.top), reversed(b.left)};
  const std::vector<std::vector<int>> orders = {{0, 1, 2, 3}, {0, 3, 2, 1}, {0, 2, 1, 3}, {0, 2, 3, 1}};
  int imported = 0;
  for (const auto& order : orders)
    for (int flips = 0; flips < 16; flips += 5) {  // which edges are stored reversed
      std::vector<BSplineCurve> stored;
      stored.reserve(4);
      for (int k = 0; k < 4; ++k) stored.push_back(((flips >> k) & 1) ? reversed(loop[order[k]]) : loop[order[k]]);
      const std::string path = write_edges(dir, "edges.step", stored);
      const cad::StepImport import = cad::import_step_boundary(path, edges({0, 1, 2, 3}));
      // bottom is edge 0 in its stored direction: the loop itself when edge 0 is not flipped,
      // else the same loop walked the other way (bottom and left swap roles, reversed).
      const BSplineBoundary expected =
          (flips & 1) ? BSplineBoundary{reversed(b.bottom), reversed(b.top), b.right, b.left} : b;
      // Knots of a reversed side are a + b − u: the identity up to rounding (1 − (1 − 0.3) ≠ 0.3).
      INFO("order " << order[0] << order[1] << order[2] << order[3] << " flips " << flips);
      require_same_boundary(import.boundary, expected, 4e-16);
      CHECK(import.max_gap == 0);
      CHECK(import.edge_indices[0] == 0);
      ++imported;
    }
  CHECK(imported == 16);
}

TEST_CASE("import_step_boundary: incompatible sides are made compatible exactly", "[cad]") {
  const test::TempDir dir;
  const BSplineBoundary raw = test::make_random_bspline_boundary(2, 5, 3, 4, 11);
  const std::string path = write_edges(dir, "raw.step", {raw.bottom, raw.right, reversed(raw.top), reversed(raw.left)});
  const cad::StepImport import = cad::import_step_boundary(path, edges({0, 1, 2, 3}));
  std::vector<CompatibilityNote> notes;
  const BSplineBoundary expected = compatible_boundary(raw, &notes);
  CHECK(import.notes.size() == notes.size());
  CHECK_FALSE(import.notes.empty());
  REQUIRE(import.boundary.bottom.count() == expected.bottom.count());
  REQUIRE(import.boundary.left.count() == expected.left.count());
  CHECK(import.boundary.bottom.knots == import.boundary.top.knots);
  CHECK(import.boundary.left.knots == import.boundary.right.knots);
  for (double t : {0.0, 0.17, 0.5, 0.93, 1.0}) {
    CHECK((evaluate(import.boundary.top, t) - evaluate(expected.top, t)).norm() < 1e-12);
    CHECK((evaluate(import.boundary.left, t) - evaluate(expected.left, t)).norm() < 1e-12);
  }
}

TEST_CASE("import_step_boundary: small corner gaps are reported and closed, large ones refused", "[cad]") {
  const test::TempDir dir;
  const BSplineBoundary b = test::cad_sample_boundary();
  BSplineCurve right = b.right;
  right.points.row(0) += Eigen::RowVector3d(0, 0, 3e-7);  // the bottom-right corner opens by 3e-7
  const std::string path = write_edges(dir, "gap.step", {b.bottom, right, reversed(b.top), reversed(b.left)});
  const cad::StepImport import = cad::import_step_boundary(path, edges({0, 1, 2, 3}));
  CHECK(import.max_gap == Approx(3e-7).epsilon(1e-6));
  REQUIRE(import.gaps.size() == 4);
  CHECK(import.gaps[0].corner == "bottom-right");
  CHECK(import.gaps[0].gap == Approx(3e-7).epsilon(1e-6));
  CHECK(import.gaps[1].gap == 0);
  // closed at the midpoint: bottom's end and right's start coincide
  CHECK(import.boundary.bottom.points.row(5) == import.boundary.right.points.row(0));
  CHECK(import.boundary.right.points(0, 2) == Approx(1.5e-7).margin(1e-15));

  cad::StepImportOptions strict = edges({0, 1, 2, 3});
  strict.gap_tolerance = 1e-8;  // 1e-8 × diagonal (≈ 4.1) < 3e-7
  CHECK_THROWS_WITH(cad::import_step_boundary(path, strict),
                    Catch::StartsWith(path + ": corner bottom-right: gap 3e-07 between edge 0 and edge 1 exceeds"));
}

TEST_CASE("import_step_boundary: the bundled samples of data/cad give the sample boundary", "[cad]") {
  const std::string dir = std::string(COONS_DATA_DIR) + "/cad/";
  const BSplineBoundary b = test::cad_sample_boundary();
  const cad::StepImport patch = cad::import_step_boundary(dir + "bspline_patch.step", face(0));
  require_same_boundary(patch.boundary, b, 0.0);
  // four_edges.step: edge 0 = right, 1 = bottom reversed, 2 = left, 3 = top reversed
  const cad::StepImport free_edges = cad::import_step_boundary(dir + "four_edges.step", edges({1, 0, 3, 2}));
  CHECK(free_edges.file_faces == 0);
  CHECK(free_edges.file_edges == 4);
  require_same_boundary(free_edges.boundary, {reversed(b.bottom), reversed(b.top), b.right, b.left}, 4e-16);
  CHECK(free_edges.edge_indices == std::vector<int>{1, 2, 3, 0});
  // every side is its edge's curve as stored (the file holds bottom and top already reversed), so
  // none is reversed (it used to report top and left as reversed: against the loop, not the curve)
  CHECK(free_edges.edge_reversed == std::vector<bool>{false, false, false, false});
}

TEST_CASE("import_step_boundary: bad files and choices are input errors naming the field", "[cad]") {
  const test::TempDir dir;
  const std::string garbage = dir.write("garbage.step", "this is not STEP\n");
  CHECK_THROWS_WITH(cad::import_step_boundary(dir.file("missing.step"), face(0)),
                    Catch::Contains("missing.step: (document): cannot be read"));
  CHECK_THROWS_WITH(cad::import_step_boundary(garbage, face(0)), Catch::StartsWith(garbage + ": (document):"));

  const BSplineBoundary b = test::cad_sample_boundary();
  const std::string patch = dir.file("patch.step");
  {
    std::ofstream out(patch);
    cad::write_step_surface(out, greville_coons_surface(b), patch, "surface");
  }
  CHECK_THROWS_WITH(cad::import_step_boundary(patch, face(1)),
                    Catch::Equals(patch + ": face 1: out of range: the file has 1 face(s), 0 to 0"));
  CHECK_THROWS_WITH(cad::import_step_boundary(patch, edges({0, 1, 2, 7})),
                    Catch::StartsWith(patch + ": edge 7: out of range"));
  // invalid options are the caller's to check (options_problem names the member at fault)
  CHECK_THROWS_AS(cad::import_step_boundary(patch, edges({0, 1, 2})), std::invalid_argument);
  cad::StepImportOptions negative = face(0);
  negative.gap_tolerance = -1;
  CHECK(cad::options_problem(negative).field == cad::StepImportOptionsField::kGapTolerance);
  CHECK(cad::options_problem(negative).reason == "must be finite and >= 0");
  CHECK_THROWS_AS(cad::import_step_boundary(patch, negative), std::invalid_argument);

  // a triangle: 3 edges
  BRepBuilderAPI_MakePolygon triangle(gp_Pnt(0, 0, 0), gp_Pnt(1, 0, 0), gp_Pnt(0, 1, 0), Standard_True);
  const std::string tri = write_shape(dir, "triangle.step", BRepBuilderAPI_MakeFace(triangle.Wire()).Face());
  CHECK_THROWS_WITH(cad::import_step_boundary(tri, face(0)),
                    Catch::Equals(tri + ": face 0: has 3 edges in its outer wire; a Coons boundary needs 4"));

  // a circular arc is a rational B-spline
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  const std::vector<BSplineCurve> sides = {b.bottom, b.right, reversed(b.top)};
  for (const auto& c : sides) builder.Add(compound, BRepBuilderAPI_MakeEdge(cad::to_occt(c)).Edge());
  builder.Add(compound, BRepBuilderAPI_MakeEdge(
                            GC_MakeArcOfCircle(gp_Pnt(0, 2, 0.5), gp_Pnt(-0.5, 1, 0.25), gp_Pnt(0, 0, 0)).Value())
                            .Edge());
  const std::string arc = write_shape(dir, "arc.step", compound);
  CHECK_THROWS_WITH(
      cad::import_step_boundary(arc, edges({0, 1, 2, 3})),
      Catch::StartsWith(arc + ": edge 3: is rational") && Catch::Contains("rational boundaries are not supported"));
}

namespace {

// A tube: a B-spline surface periodic in u (`along_u`) or in v, degree 3 × 2, one face whose outer
// wire is two closed circles and the seam twice. `reverse`: the face reversed.
Handle(Geom_BSplineSurface) tube(bool along_u) {
  const int around = 6;
  TColgp_Array2OfPnt poles(1, along_u ? around : 3, 1, along_u ? 3 : around);
  for (int a = 1; a <= around; ++a)
    for (int h = 1; h <= 3; ++h) {
      const double angle = 2 * M_PI * (a - 1) / around;
      const gp_Pnt p((1 + 0.2 * h) * std::cos(angle), (1 + 0.2 * h) * std::sin(angle), 0.7 * h);
      if (along_u)
        poles(a, h) = p;
      else
        poles(h, a) = p;
    }
  TColStd_Array1OfReal periodic(1, around + 1), clamped(1, 2);
  TColStd_Array1OfInteger periodic_mult(1, around + 1), clamped_mult(1, 2);
  for (int k = 1; k <= around + 1; ++k) periodic(k) = k - 1, periodic_mult(k) = 1;
  clamped(1) = 0, clamped(2) = 1, clamped_mult(1) = clamped_mult(2) = 3;
  if (along_u) return new Geom_BSplineSurface(poles, periodic, clamped, periodic_mult, clamped_mult, 3, 2, true, false);
  return new Geom_BSplineSurface(poles, clamped, periodic, clamped_mult, periodic_mult, 2, 3, false, true);
}

// max over t of |side(t) − S(iso-curve)|, each side over [0, 1] against the surface on its line of
// the parameter rectangle, in the direction the contract gives (bottom, top: u increasing; left,
// right: v increasing).
double side_error(const BSplineBoundary& b, const Handle(Geom_BSplineSurface) & s) {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
  s->Bounds(u0, u1, v0, v1);
  double worst = 0;
  for (int k = 0; k <= 40; ++k) {
    const double t = k / 40.0, u = u0 + t * (u1 - u0), v = v0 + t * (v1 - v0);
    auto distance = [](const Eigen::RowVector3d& p, const gp_Pnt& q) {
      return (p - Eigen::RowVector3d(q.X(), q.Y(), q.Z())).norm();
    };
    worst = std::max({worst, distance(evaluate(b.bottom, t), s->Value(u, v0)),
                      distance(evaluate(b.top, t), s->Value(u, v1)), distance(evaluate(b.left, t), s->Value(u0, v)),
                      distance(evaluate(b.right, t), s->Value(u1, v))});
  }
  return worst;
}

}  // namespace

TEST_CASE("import_step_boundary: a closed face's sides run as its parameters do, the seam on both sides", "[cad]") {
  // The chain of a tube's wire (circle, seam, circle, seam) cannot orient a closed circle: until
  // 2026-11-30 the top of a tube periodic in u came out backwards, 2.19 off, with exit 0.
  const test::TempDir dir;
  for (const bool along_u : {true, false})
    for (const bool reverse : {false, true}) {
      const Handle(Geom_BSplineSurface) s = tube(along_u);
      TopoDS_Face f = BRepBuilderAPI_MakeFace(s, 1e-7).Face();
      if (reverse) f = TopoDS::Face(f.Reversed());
      const std::string path = write_shape(dir, "tube.step", f);
      const cad::StepImport import = cad::import_step_boundary(path, face(0));
      INFO("periodic in " << (along_u ? "u" : "v") << (reverse ? ", face reversed" : ""));
      CHECK(side_error(import.boundary, s) < 1e-12);
      CHECK(import.max_gap < 1e-12);
      // the seam is both sides of its direction
      CHECK(import.edge_indices[along_u ? 1 : 0] == import.edge_indices[along_u ? 3 : 2]);
    }
}

TEST_CASE("import_step_boundary: a closed edge given by --edges is refused, the chain cannot orient it", "[cad]") {
  const test::TempDir dir;
  const std::string path = write_shape(dir, "tube.step", BRepBuilderAPI_MakeFace(tube(true), 1e-7).Face());
  TopTools_IndexedMapOfShape all;
  TopExp::MapShapes(cad::read_step_shape(path), TopAbs_EDGE, all);
  REQUIRE(all.Extent() == 3);  // two circles and the seam
  // the tube's edges and a fourth: a closed circle is named before any chaining
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  for (int k = 1; k <= all.Extent(); ++k) builder.Add(compound, all(k));
  builder.Add(compound, BRepBuilderAPI_MakeEdge(gp_Pnt(5, 5, 5), gp_Pnt(6, 5, 5)).Edge());
  const std::string loose = write_shape(dir, "edges.step", compound);
  CHECK_THROWS_WITH(cad::import_step_boundary(loose, edges({0, 1, 2, 3})),
                    Catch::Contains(": edge ") && Catch::Contains("is closed (its ends meet)"));
  // a straight edge of length 1e-6 is short, not closed: its ends are its whole extent apart (a
  // closed edge was one with ends within the gap tolerance, 1e-6 of the diagonal, at first)
  const gp_Pnt p0(0, 0, 0), p1(1, 0, 0), p2(1, 1e-6, 0), p3(0, 1, 0.5);
  BRep_Builder quad_builder;
  TopoDS_Compound quad;
  quad_builder.MakeCompound(quad);
  for (const auto& [from, to] : {std::pair{p0, p1}, {p1, p2}, {p2, p3}, {p3, p0}})
    quad_builder.Add(quad, BRepBuilderAPI_MakeEdge(from, to).Edge());
  const std::string short_side = write_shape(dir, "short.step", quad);
  CHECK(cad::import_step_boundary(short_side, edges({0, 1, 2, 3})).max_gap == 0);
}

TEST_CASE("import_step_boundary: a file in metres or centimetres gives its own numbers and names its unit", "[cad]") {
  // OpenCASCADE converts to millimetres by default: a file in metres came in 1000 times larger
  const test::TempDir dir;
  const BSplineBoundary b = test::cad_sample_boundary();
  const std::string mm = write_edges(dir, "mm.step", {b.bottom, b.right, reversed(b.top), reversed(b.left)});
  std::stringstream text;
  text << std::ifstream(mm).rdbuf();
  const std::string original = text.str();
  const std::string millimetre = "SI_UNIT(.MILLI.,.METRE.)";
  REQUIRE(original.find(millimetre) != std::string::npos);
  const cad::StepImport in_mm = cad::import_step_boundary(mm, edges({0, 1, 2, 3}));
  CHECK(in_mm.unit == "millimetre");
  for (const auto& [unit, entity] : {std::pair<std::string, std::string>{"metre", "SI_UNIT($,.METRE.)"},
                                     {"centimetre", "SI_UNIT(.CENTI.,.METRE.)"}}) {
    std::string changed = original;
    for (std::size_t at = changed.find(millimetre); at != std::string::npos; at = changed.find(millimetre, at))
      changed.replace(at, millimetre.size(), entity);
    const std::string path = dir.write(unit + ".step", changed);
    const cad::StepImport import = cad::import_step_boundary(path, edges({0, 1, 2, 3}));
    INFO(unit);
    CHECK(import.unit == unit);
    require_same_boundary(import.boundary, in_mm.boundary, 0.0);
    CHECK(cad::import_note(import)["unit"] == unit);
  }
  // conversion-based units, written by OpenCASCADE (which converts the millimetres it is given):
  // the import keeps the file's numbers, 1/25.4 and 1/0.0254 of the millimetres, in lower case
  const std::string previous = Interface_Static::CVal("write.step.unit");
  for (const auto& [unit, name, per_mm] : {std::tuple{"INCH", "inch", 1 / 25.4}, {"MIL", "mil", 1 / 0.0254}}) {
    Interface_Static::SetCVal("write.step.unit", unit);
    const std::string path =
        write_edges(dir, std::string(name) + ".step", {b.bottom, b.right, reversed(b.top), reversed(b.left)});
    Interface_Static::SetCVal("write.step.unit", previous.c_str());
    const cad::StepImport import = cad::import_step_boundary(path, edges({0, 1, 2, 3}));
    INFO(name);
    CHECK(import.unit == name);
    const Eigen::MatrixX3d expected = per_mm * in_mm.boundary.bottom.points;
    CHECK((import.boundary.bottom.points - expected).cwiseAbs().maxCoeff() <= 1e-12 * expected.cwiseAbs().maxCoeff());
  }
}
