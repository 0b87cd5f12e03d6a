// Sampled fields (curvatures, twist, distance to a reference) and the mesh files built from them.
#include "coons/surfaces/sampling.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <sstream>

#include "coons/io/mesh_export.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using V = Eigen::RowVector3d;

namespace {

// A cylinder of radius R as the ruled surface of two circles (exact derivatives).
Surface cylinder(double R) {
  auto circle = [R](double z) {
    return closed_form_curve(
        [=](double s) { return V(R * std::cos(M_PI * s), R * std::sin(M_PI * s), z); },
        [=](double s) { return V(-M_PI * R * std::sin(M_PI * s), M_PI * R * std::cos(M_PI * s), 0); },
        [=](double s) { return V(-M_PI * M_PI * R * std::cos(M_PI * s), -M_PI * M_PI * R * std::sin(M_PI * s), 0); });
  };
  return make_ruled(circle(0), circle(1));
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}
}  // namespace

TEST_CASE("sample_grid: curvatures of a cylinder, a saddle and a plane", "[surfaces]") {
  const SurfaceSamples c = sample_grid(cylinder(2), 9);
  for (int r = 0; r < 81; ++r) {
    CHECK(std::abs(std::abs(c.mean_curvature(r)) - 0.25) < 1e-12);  // H = ±1/(2R)
    CHECK(std::abs(c.gaussian_curvature(r)) < 1e-12);
  }
  // z = 2uv: K = −4/(1 + 4u² + 4v²)² at (u, v).
  const Surface saddle = make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 2)});
  const SurfaceSamples s = sample_grid(saddle, 5);
  for (int a = 0; a < 5; ++a)
    for (int b = 0; b < 5; ++b) {
      const double u = a / 4.0, v = b / 4.0;
      CHECK(s.gaussian_curvature(a * 5 + b) == Approx(-4 / std::pow(1 + 4 * u * u + 4 * v * v, 2)).epsilon(1e-12));
      CHECK(s.twist(a * 5 + b) == Approx(2));
      CHECK((s.points.row(a * 5 + b) - V(u, v, 2 * u * v)).norm() < 1e-15);
    }
}

TEST_CASE("sample_grid: normals and curvatures follow a scaling of the surface by 1e-150 and 1e150", "[surfaces]") {
  // z = 2uv scaled by s: the same normals, H and K divided by s and s², the twist times s. At
  // 1e-150 the cross product of the partials (1e-300) has a squared norm below the smallest double,
  // so every normal and curvature was NaN and `coons surface` printed maxima of 0.
  auto saddle = [](double s) { return make_bilinear({V(0, 0, 0), V(s, 0, 0), V(0, s, 0), V(s, s, 2 * s)}); };
  const SurfaceSamples one = sample_grid(saddle(1), 5);
  for (const double s : {1e-150, 1e150}) {
    INFO("scale " << s);
    const SurfaceSamples scaled = sample_grid(saddle(s), 5);
    for (int r = 0; r < 25; ++r) {
      CHECK((scaled.normals.row(r) - one.normals.row(r)).norm() < 1e-15);
      CHECK(scaled.mean_curvature(r) * s == Approx(one.mean_curvature(r)).epsilon(1e-14));
      CHECK(scaled.gaussian_curvature(r) * s * s == Approx(one.gaussian_curvature(r)).epsilon(1e-14));
      CHECK(scaled.twist(r) / s == Approx(one.twist(r)).epsilon(1e-14));
    }
  }
}

TEST_CASE("add_reference_distance: the distance of the 16-vector bump to its plane is |z|", "[surfaces]") {
  const std::array<V, 4> corners = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)};
  const std::array<V, 4> du = {V(1, 0, 0), V(1, 0, 0), V(1, 0, 0), V(1, 0, 0)};
  const std::array<V, 4> dv = {V(0, 1, 0), V(0, 1, 0), V(0, 1, 0), V(0, 1, 0)};
  const Surface bump = make_hermite16(HermitePatch{corners, du, dv, {V(0, 0, 10), V(0, 0, 0), V(0, 0, 0), V(0, 0, 0)}});
  const Surface plane = make_bilinear({V(-1, -1, 0), V(2, -1, 0), V(-1, 2, 0), V(2, 2, 0)});
  SurfaceSamples s = sample_grid(bump, 7);
  add_reference_distance(s, plane);
  REQUIRE(s.distance);
  for (int r = 0; r < 49; ++r) CHECK(std::abs((*s.distance)(r)-std::abs(s.points(r, 2))) < 1e-12);
  // The closest point of a point above the saddle z = 2uv.
  const Surface saddle = make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 2)});
  const SurfacePoint q = saddle.evaluate(0.4, 0.7);
  const ClosestPoint cp = closest_point(saddle, q.p + 0.05 * unit_normal(q));
  CHECK(cp.u == Approx(0.4).epsilon(1e-9));
  CHECK(cp.v == Approx(0.7).epsilon(1e-9));
  CHECK(cp.distance == Approx(0.05).epsilon(1e-9));
}

TEST_CASE("closest_point: on a side of the square the search goes on along it to the nearest point", "[surfaces]") {
  // z = 2u(1 - u) + 2v(1 - v) over [0, 1]^2 (a quadratic Bezier net). From q = (0, 1/2, 0) the
  // nearest points are on the side u = 0 at v = 1/2 +- 1/sqrt(8): with w = v - 1/2 the squared
  // distance is w^2 + (1/2 - 2w^2)^2, least at w^2 = 1/8, where it is 3/16. The search stopped at
  // (0, 0.34375), 0.433228: the full Newton step, clamped to u = 0, hardly moved v.
  ControlNet net(2, 2);
  const double z[3] = {0, 1, 0};
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; j <= 2; ++j) net.at(i, j) = V(i / 2.0, j / 2.0, z[i] + z[j]);
  const Surface paraboloid = make_bezier_surface(net);
  const ClosestPoint cp = closest_point(paraboloid, V(0, 0.5, 0));
  CHECK(cp.distance == Approx(std::sqrt(3.0) / 4).epsilon(1e-12));
  CHECK(cp.u == Approx(0).margin(1e-12));
  CHECK(std::abs(cp.v - 0.5) == Approx(1 / std::sqrt(8.0)).epsilon(1e-6));
}

TEST_CASE("write_grid_obj, write_grid_ply, write_grid_vts: sizes, fields and structure", "[surfaces]") {
  SurfaceSamples s = sample_grid(make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 2)}), 4);
  add_reference_distance(s, make_bilinear({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1, 0)}));
  std::stringstream obj, ply, vts;
  write_grid_obj(obj, s, "saddle");
  write_grid_ply(ply, s);
  write_grid_vts(vts, s);
  CHECK(count(obj.str(), "\nv ") == 16);
  CHECK(count(obj.str(), "\nvn ") == 16);
  CHECK(count(obj.str(), "\nf ") == 2 * 9);
  CHECK(ply.str().rfind("ply\nformat ascii 1.0\n", 0) == 0);
  CHECK(ply.str().find("element vertex 16\n") != std::string::npos);
  CHECK(ply.str().find("element face 9\n") != std::string::npos);
  for (const char* field :
       {"mean_curvature", "gaussian_curvature", "twist", "distance", "parametric_distance", "singular"}) {
    CHECK(ply.str().find(std::string("property double ") + field + "\n") != std::string::npos);
    CHECK(vts.str().find(std::string("Name=\"") + field + "\"") != std::string::npos);
  }
  CHECK(vts.str().find("WholeExtent=\"0 3 0 3 0 0\"") != std::string::npos);
  CHECK(count(vts.str(), "<DataArray") == count(vts.str(), "</DataArray>"));
  CHECK(vts.str().find("</VTKFile>") != std::string::npos);
  // PLY body: 16 vertex lines of 3 + 3 + 6 numbers, then 9 quads.
  std::string line;
  std::stringstream body(ply.str().substr(ply.str().find("end_header\n") + 11));
  int vertices = 0, faces = 0;
  while (std::getline(body, line)) {
    std::stringstream words(line);
    int n = 0;
    for (std::string w; words >> w;) ++n;
    if (n == 12) ++vertices;
    if (n == 5) ++faces;
  }
  CHECK(vertices == 16);
  CHECK(faces == 9);
}

TEST_CASE("sample_grid: the apex of a sectorial surface is singular, and marked so in the meshes", "[surfaces]") {
  const Surface cone = make_sectorial(Curve::segment(V(1, 0, 0), V(0, 1, 0)), V(0, 0, 1));
  const SurfaceSamples s = sample_grid(cone, 3);
  for (int a = 0; a < 3; ++a) {
    CHECK(s.normals.row(a * 3 + 2).hasNaN());  // v = 1: the apex
    CHECK(s.normals.row(a * 3 + 0).allFinite());
  }
  std::stringstream vts;
  write_grid_vts(vts, s);
  const std::string text = vts.str();
  const size_t start = text.find("Name=\"singular\"");
  REQUIRE(start != std::string::npos);
  const std::string values =
      text.substr(text.find('>', start) + 1, text.find("</DataArray>", start) - text.find('>', start) - 1);
  std::stringstream in(values);
  std::vector<double> flags;
  for (double x; in >> x;) flags.push_back(x);
  CHECK(flags == std::vector<double>{0, 0, 1, 0, 0, 1, 0, 0, 1});
  CHECK(text.find("nan") == std::string::npos);
  CHECK(text.find("NaN") == std::string::npos);
}

TEST_CASE("write_grid_obj: a sample on a side collapsed to a point gets its neighbour's normal, not (0, 0, 1)",
          "[surfaces]") {
  // A planar fan in the tilted plane z = x with the side v = 0 collapsed to one point: every
  // normal is the same +-(-1, 0, 1)/sqrt(2), and the apex's samples have none of their own.
  ControlNet net(3, 3);
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 3; ++j) {
      const double r = j / 3.0, x = r * (i / 3.0 - 0.5);
      net.at(i, j) = V(x, r, x);
    }
  const SurfaceSamples s = sample_grid(make_bezier_surface(net), 5);
  REQUIRE_FALSE(s.normals.row(0).allFinite());  // the apex: a singular sample
  std::stringstream obj;
  write_grid_obj(obj, s, "fan");
  std::vector<V> normals;
  for (std::string line; std::getline(obj, line);)
    if (line.rfind("vn ", 0) == 0) {
      std::istringstream fields(line.substr(3));
      double x = 0, y = 0, z = 0;
      fields >> x >> y >> z;
      normals.emplace_back(x, y, z);
    }
  REQUIRE(normals.size() == 25);
  const V expected = s.normals.row(2 * 5 + 2);  // the centre's
  CHECK(std::abs(expected(0)) == Approx(1 / std::sqrt(2.0)).epsilon(1e-12));
  for (const V& n : normals) CHECK((n - expected).norm() < 1e-12);
}
