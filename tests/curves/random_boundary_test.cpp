#include "coons/curves/random_boundary.h"

#include <catch2/catch.hpp>

#include "coons/net/control_net.h"

using namespace coons;

TEST_CASE("random_smooth_boundary: corners are shared, the seed and index determine it") {
  RandomSmoothOptions options;
  options.side_degree = 4;
  const Boundary a = random_smooth_boundary(7, 3, options), b = random_smooth_boundary(7, 3, options);
  const Boundary c = random_smooth_boundary(7, 4, options), d = random_smooth_boundary(8, 3, options);
  CHECK(a.m == 4);
  CHECK(a.n == 4);
  CHECK(largest_corner_gap(a).gap == 0);
  CHECK(a.bottom == b.bottom);
  CHECK(a.right == b.right);
  CHECK(a.bottom != c.bottom);
  CHECK(a.bottom != d.bottom);
  const auto family = random_smooth_family(7, 3, options, 2);
  REQUIRE(family.size() == 3);
  CHECK(family[1].top == a.top);  // boundary 3 made alone or in a shard starting at 2
}

TEST_CASE("random_smooth_boundary: displacements stay within the amplitudes") {
  RandomSmoothOptions options;
  options.height = 0.2;
  options.wiggle = 0.05;
  for (int k = 0; k < 20; ++k) {
    const Boundary b = random_smooth_boundary(1, k, options);
    for (const Eigen::MatrixX3d* side : {&b.bottom, &b.top, &b.left, &b.right}) {
      CHECK(side->col(2).cwiseAbs().maxCoeff() <= 2 * options.height);
      CHECK(side->col(0).minCoeff() >= -options.wiggle);
      CHECK(side->col(1).maxCoeff() <= 1 + options.wiggle);
    }
  }
  RandomSmoothOptions bad;
  bad.wiggle = 0.7;
  std::string why;
  CHECK_FALSE(bad.is_valid(&why));
  CHECK(why.find("wiggle") != std::string::npos);
}
