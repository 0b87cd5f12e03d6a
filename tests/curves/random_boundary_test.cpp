#include "coons/curves/random_boundary.h"

#include <catch2/catch.hpp>

#include "coons/net/control_net.h"
#include "coons/net/degree_elevation.h"

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

TEST_CASE("perturbed_boundary: the seed and index determine it, corners stay shared, amplitude scales it") {
  // a base of degree (4, 2) with shared corners: the sides of a random-smooth boundary of its own
  RandomSmoothOptions base_options;
  base_options.side_degree = 4;
  Boundary base = random_smooth_boundary(11, 0, base_options);
  base.left = base.left.topRows(3).eval();  // a degree-2 side with the same two corners
  base.left.row(2) = base.top.row(0);
  base.right = base.right.topRows(3).eval();
  base.right.row(2) = base.top.row(4);
  base.n = 2;
  base.name = "base";
  REQUIRE(largest_corner_gap(base).gap == 0);
  const RandomSmoothOptions options;  // degree 3 displacements
  const Boundary a = perturbed_boundary(base, 0.1, 5, 2, options), b = perturbed_boundary(base, 0.1, 5, 2, options);
  const Boundary c = perturbed_boundary(base, 0.1, 5, 3, options), d = perturbed_boundary(base, 0.1, 6, 2, options);
  CHECK(a.m == 4);
  CHECK(a.n == 3);  // max(2, 3)
  CHECK(a.name == "base-perturbed-5-2");
  CHECK(a.bottom == b.bottom);
  CHECK(a.left == b.left);
  CHECK(a.bottom != c.bottom);
  CHECK(a.top != d.top);
  CHECK(largest_corner_gap(a).gap < 1e-15);
  CHECK(largest_corner_gap(c).gap < 1e-15);
  // amplitude 0 is the base (elevated); the displacement is linear in the amplitude
  const Boundary zero = perturbed_boundary(base, 0.0, 5, 2, options);
  const Boundary elevated = elevate_boundary(base, 4, 3);
  CHECK(zero.left == elevated.left);
  CHECK(zero.bottom == elevated.bottom);
  const Boundary half = perturbed_boundary(base, 0.05, 5, 2, options);
  const Eigen::MatrixX3d full_step = a.bottom - zero.bottom, half_step = half.bottom - zero.bottom;
  CHECK((full_step - 2 * half_step).cwiseAbs().maxCoeff() < 1e-14);
  CHECK(full_step.cwiseAbs().maxCoeff() > 0);
  // within amplitude × diagonal × the generator's height (z) and wiggle (x, y)
  const double scale = 0.1 * bounding_box_diagonal(base);
  CHECK(full_step.col(2).cwiseAbs().maxCoeff() <= 2 * scale * options.height + 1e-15);  // corner height + own
  CHECK(full_step.leftCols(2).cwiseAbs().maxCoeff() <= scale * options.wiggle + 1e-15);
}
