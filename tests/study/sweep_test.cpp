#include "coons/study/sweep.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <tuple>

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

TEST_CASE("linspace: the last value is the end itself and every value lies between the ends", "[study]") {
  // from + (to − from)·k/(count − 1) rounded the last value of −0.15 .. 0.25 in 7 steps to
  // 0.2500000000000001 (an α beyond 1/4, β < 0), of 1e300 .. 1e301 in 3 to 1.0000000000000002e301,
  // and of a triangle sweep to 1/3 in 401 to 0.33333333333333326
  const std::tuple<double, double, int> cases[] = {
      {-0.15, 0.25, 7}, {1e300, 1e301, 3}, {-1.0 / 6, 1.0 / 3, 401}, {0.25, -0.15, 7}, {-0.25, 0.25, 101}};
  for (const auto& [from, to, count] : cases) {
    const std::vector<double> v = linspace(from, to, count);
    INFO(from << " .. " << to << " in " << count);
    REQUIRE(v.size() == std::size_t(count));
    CHECK(v.front() == from);
    CHECK(v.back() == to);
    for (double x : v) {
      CHECK(x >= std::min(from, to));
      CHECK(x <= std::max(from, to));
    }
  }
}
