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
