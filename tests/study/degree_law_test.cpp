// The degree law α* + 1/4 ≈ c/n² (coons/study/degree_law.h).
#include "coons/study/degree_law.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace coons;

TEST_CASE("fit_degree_law: recovers c from an exact c/n^2 sequence with no misfit", "[study]") {
  for (double c : {0.5, 2.25, 11.0}) {
    std::vector<std::pair<int, double>> optima;
    for (int n : {3, 4, 6, 8, 12, 16}) optima.emplace_back(n, -0.25 + c / (double(n) * n));
    const auto fit = fit_degree_law(optima);
    REQUIRE(fit);
    CHECK(fit->c == Approx(c).epsilon(1e-12));
    CHECK(fit->misfit < 1e-12);
  }
}

TEST_CASE("fit_degree_law: the misfit is the largest relative deviation from the fitted law", "[study]") {
  // α + 1/4 = 1/n² at n = 2 and 2·(1/n²) at n = 4: c minimises (1/4 − c/4)² + (1/8 − c/16)²
  const auto fit = fit_degree_law({{2, -0.25 + 0.25}, {4, -0.25 + 0.125}});
  REQUIRE(fit);
  const double c = (0.25 / 4 + 0.125 / 16) / (1.0 / 16 + 1.0 / 256);
  CHECK(fit->c == Approx(c).epsilon(1e-14));
  const double misfit = std::max(std::abs(0.25 - c / 4) / 0.25, std::abs(0.125 - c / 16) / 0.125);
  CHECK(fit->misfit == Approx(misfit).epsilon(1e-14));
  CHECK(fit->misfit > 0.1);
}

TEST_CASE("fit_degree_law: fewer than two optima give no fit", "[study]") {
  CHECK(!fit_degree_law({}));
  CHECK(!fit_degree_law({{4, -0.2}}));
}
