#include "coons/study/sweep.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

using coons::linspace;

TEST_CASE("linspace: both ends included and evenly spaced", "[study]") {
  const std::vector<double> v = linspace(-0.25, 0.25, 5);
  REQUIRE(v.size() == 5);
  CHECK(v.front() == -0.25);
  CHECK(v.back() == 0.25);
  CHECK(v[2] == 0.0);
  CHECK(linspace(3.0, 7.0, 1) == std::vector<double>{3.0});
}

TEST_CASE("linspace: a range near the largest double stays finite and ordered", "[study]") {
  // sweep --parameter mu --from 0 --to 1e308 --count 3 evaluated its last value at mu = inf:
  // (to - from) * k overflowed before the division.
  const double big = std::numeric_limits<double>::max();
  for (const auto& [from, to] : {std::pair{0.0, 1e308}, std::pair{-big, big}, std::pair{-1e308, 1e308}}) {
    const std::vector<double> v = linspace(from, to, 3);
    INFO(from << " .. " << to);
    REQUIRE(v.size() == 3);
    CHECK(v.front() == from);
    CHECK(v.back() == to);
    for (double x : v) CHECK(std::isfinite(x));
    CHECK(v[0] < v[1]);
    CHECK(v[1] < v[2]);
  }
}
