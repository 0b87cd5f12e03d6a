// STEP/IGES writing of B-spline surfaces through OpenCASCADE, read back by OpenCASCADE
// (STEPControl_Reader / IGESControl_Reader -> face -> BRep_Tool::Surface -> Geom_BSplineSurface).
#include "coons/cad/cad_surface.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Face.hxx>
#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "coons/cad/occt_convert.h"
#include "coons/io/input_error.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;

namespace {

// A surface with random non-uniform knots and random poles of mixed magnitudes.
BSplineSurface random_surface(int p, int count_u, int q, int count_v, std::uint32_t seed) {
  BSplineSurface s =
      test::make_random_bspline_surface(p, count_u, q, count_v, seed, -0.5, 2.0 / 3.0, 0.1, 1.0 / 7.0 + 1.0);
  const BSplineCurve rows = test::make_random_bspline(1, count_u * count_v, seed + 2);
  s.net.points = rows.points;
  s.net.points.col(1) *= 1e3 / 7.0;
  s.net.points.col(2) *= 1e-5 / 3.0;
  return s;
}

void write(const std::string& path, const BSplineSurface& s, bool step) {
  std::ofstream out(path);
  if (step)
    cad::write_step_surface(out, s, path, "step");
  else
    cad::write_iges_surface(out, s, path, "iges");
}

}  // namespace

TEST_CASE("write_step_surface: poles and knots read back exactly (STEP and IGES)", "[cad]") {
  const test::TempDir dir;
  int compared = 0;
  for (int p = 1; p <= 5; ++p)
    for (int q : {1, 2, 4}) {
      const int count_u = p + 1 + (p % 3) * 2, count_v = q + 2;
      const BSplineSurface s = random_surface(p, count_u, q, count_v, std::uint32_t(17 * p + q));
      REQUIRE(s.is_valid(nullptr));
      for (bool step : {true, false}) {
        const std::string path = dir.file(step ? "s.step" : "s.iges");
        write(path, s, step);
        const std::vector<BSplineSurface> back = step ? cad::read_step_surfaces(path) : cad::read_iges_surfaces(path);
        INFO("p=" << p << " q=" << q << (step ? " STEP" : " IGES"));
        REQUIRE(back.size() == 1);
        CHECK(back[0].degree_u == p);
        CHECK(back[0].degree_v == q);
        CHECK(back[0].knots_u == s.knots_u);  // bit for bit
        CHECK(back[0].knots_v == s.knots_v);
        REQUIRE(back[0].net.m == s.net.m);
        REQUIRE(back[0].net.n == s.net.n);
        CHECK(back[0].net.points == s.net.points);
        ++compared;
      }
    }
  CHECK(compared == 30);
}

TEST_CASE("bezier_as_bspline: a Bezier net is the single-span clamped B-spline", "[cad]") {
  ControlNet net(3, 2);
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 2; ++j) net.at(i, j) << i / 3.0, j / 2.0, (i * j) % 3 / 7.0;
  const BSplineSurface s = cad::bezier_as_bspline(net);
  REQUIRE(s.is_valid(nullptr));
  CHECK(s.knots_u.size() == 8);
  CHECK(s.knots_u.head(4).isZero());
  CHECK(s.knots_u.tail(4).isOnes());
  for (double u : {0.0, 0.3, 1.0})
    for (double v : {0.0, 0.7, 1.0}) {
      const Eigen::RowVector3d a = evaluate(s, u, v);
      const Handle(Geom_BSplineSurface) occt = cad::to_occt(s);
      const gp_Pnt b = occt->Value(u, v);
      CHECK((a - Eigen::RowVector3d(b.X(), b.Y(), b.Z())).norm() < 1e-14);
    }
  const test::TempDir dir;
  write(dir.file("b.step"), s, true);
  const auto back = cad::read_step_surfaces(dir.file("b.step"));
  REQUIRE(back.size() == 1);
  CHECK(back[0].net.points == net.points);
}

TEST_CASE("write_step_surface: OpenCASCADE's default real format is not exact", "[cad]") {
  // Why coons prints its own reals: STEPControl_Writer::Write keeps about 14 significant digits.
  const BSplineSurface s = random_surface(3, 6, 2, 4, 5);
  const test::TempDir dir;
  const std::string path = dir.file("default.step");
  cad::silence_occt_messages();
  STEPControl_Writer writer;
  REQUIRE(writer.Transfer(BRepBuilderAPI_MakeFace(cad::to_occt(s), Precision::Confusion()).Face(), STEPControl_AsIs) ==
          IFSelect_RetDone);
  REQUIRE(writer.Write(path.c_str()) == IFSelect_RetDone);
  const auto back = cad::read_step_surfaces(path);
  REQUIRE(back.size() == 1);
  const double pole_difference = (back[0].net.points - s.net.points).cwiseAbs().maxCoeff();
  const double relative = pole_difference / s.net.points.cwiseAbs().maxCoeff();
  WARN("OpenCASCADE's default STEP writer: max pole difference " << pole_difference << " (relative " << relative
                                                                 << ")");
  CHECK(pole_difference > 0);
  CHECK(relative < 1e-10);
}

TEST_CASE("check_writable: refuses what cannot be written exactly", "[cad]") {
  BSplineSurface s = cad::bezier_as_bspline(ControlNet(2, 2));
  CHECK_NOTHROW(cad::check_writable(s, "out.step", "--step"));
  s.net.at(1, 1)(2) = 1e-120;
  CHECK_THROWS_AS(cad::check_writable(s, "out.step", "--step"), InputError);
  s.net.at(1, 1)(2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(cad::check_writable(s, "out.step", "--step"), Catch::Contains("out.step: --step:"));
  s.net.at(1, 1)(2) = 0;
  s.knots_u(2) = -1;  // not clamped any more
  CHECK_THROWS_WITH(cad::check_writable(s, "out.iges", "--iges"), Catch::Contains("not a valid B-spline"));
}
