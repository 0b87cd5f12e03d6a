// The OBJ files of a net: vertex normals are unit vectors at every scale.
#include "coons/io/obj_export.h"

#include <catch2/catch.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The "vn" lines of an OBJ text.
std::vector<std::string> normal_lines(const std::string& obj) {
  std::vector<std::string> out;
  std::istringstream in(obj);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("vn ", 0) == 0) out.push_back(line);
  return out;
}

}  // namespace

TEST_CASE("write_surface_obj: the normals of a net scaled by 2^-300 are those at scale 1", "[io]") {
  // 2^-300 ≈ 5e-91: the tangents' cross product (≈ 1e-181) underflows in norm(), which made every
  // normal (0, 0, 1)
  const ControlNet net = make_random_net(3, 4, 11);
  const ControlNet tiny = transformed(net, std::ldexp(1.0, -300) * Eigen::Matrix3d::Identity(), {0, 0, 0});
  std::ostringstream one, small;
  write_surface_obj(one, net, 5);
  write_surface_obj(small, tiny, 5);
  const std::vector<std::string> expected = normal_lines(one.str());
  REQUIRE(expected.size() == 25);
  CHECK(normal_lines(small.str()) == expected);  // exact: scaling by a power of two
  CHECK(expected[0] != "vn 0 0 1");
}

TEST_CASE("write_surface_obj: at a side collapsed to a point the normal is the limit from inside", "[io]") {
  // A planar net in the tilted plane z = x whose side v = 0 is one point: every normal of the
  // surface is +-(-1, 0, 1)/sqrt(2), the apex's too. It was written as the placeholder (0, 0, 1).
  ControlNet net(3, 3);
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; j <= 3; ++j) {
      const double r = j / 3.0, x = r * (i / 3.0 - 0.5), y = r;  // a triangle fanned from (0, 0)
      net.at(i, j) = Eigen::RowVector3d(x, y, x);
    }
  std::ostringstream obj;
  write_surface_obj(obj, net, 5);
  const std::vector<std::string> normals = normal_lines(obj.str());
  REQUIRE(normals.size() == 25);
  const std::string& interior = normals[2 * 5 + 2];  // (u, v) = (1/2, 1/2)
  std::istringstream fields(interior.substr(3));
  double nx = 0, ny = 0, nz = 0;
  fields >> nx >> ny >> nz;
  CHECK(std::abs(nx) == Approx(1 / std::sqrt(2.0)).epsilon(1e-12));
  CHECK(ny == Approx(0).margin(1e-12));
  CHECK(nz == Approx(-nx).epsilon(1e-12));
  for (int s = 0; s < 5; ++s) {  // v = 0: the apex, sample s * 5
    INFO("u = " << s / 4.0 << ": " << normals[s * 5]);
    std::istringstream apex(normals[std::size_t(s) * 5].substr(3));
    double ax = 0, ay = 0, az = 0;
    apex >> ax >> ay >> az;
    CHECK(ax == Approx(nx).epsilon(1e-6));
    CHECK(ay == Approx(ny).margin(1e-6));
    CHECK(az == Approx(nz).epsilon(1e-6));
  }
}
