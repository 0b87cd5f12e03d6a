// The JSON of `coons degree-limit` (coons/study/degree_limit_study.h), on entries made in code.
#include "coons/study/degree_limit_study.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/study/study.h"

using namespace coons;

TEST_CASE("degree_limit_json: p_at_bound is the fit's own, and only the n^-p form carries it", "[study]") {
  // μ = 4 + a·n^−p with p = 10 (beyond the range searched, p stops at 8) and p = 6 (inside it): the
  // field must follow the fit, not a constant (a CLI run on the bundled shapes only ever met false)
  for (const double p : {10.0, 6.0}) {
    DegreeLimitEntry e;
    e.boundary = "synthetic";
    e.objective = "thin_plate";
    std::vector<std::pair<int, double>> mus;
    for (int n : {4, 6, 8, 10, 12, 16, 20, 24, 32}) mus.emplace_back(n, 4 + 1e6 * std::pow(n, -p));
    e.limit = fit_degree_limit(mus);
    const nlohmann::json j = degree_limit_json(e);
    INFO("p = " << p << ": " << j["fits"].dump());
    int with_p = 0;
    for (std::size_t k = 0; k < e.limit.fits.size(); ++k) {
      const LimitFit& f = e.limit.fits[k];
      const nlohmann::json& fit = j["fits"][k];
      CHECK(fit["form"] == f.form);
      const bool power = f.form == "mu_inf + a*n^-p";
      CHECK(fit.contains("p_at_bound") == power);
      if (!power) continue;
      ++with_p;
      CHECK(fit["p_at_bound"].get<bool>() == (p > DegreeLimitOptions{}.max_rate));
    }
    CHECK(with_p == 1);
  }
}

TEST_CASE("unreachable_degrees: below the boundary's degree in u or v without curves, none with curves", "[study]") {
  StudyInput input;
  input.boundary.m = 3;
  input.boundary.n = 5;
  CHECK(unreachable_degrees(input, {2, 3, 4, 5, 6}) == std::vector<int>{2, 3, 4});
  CHECK(unreachable_degrees(input, {}).empty());
  CHECK(unreachable_reason(input).rfind("below the boundary's degree 3x5", 0) == 0);
  input.curves = std::vector<Curve>{};  // analytic sides: refitted at any degree
  CHECK(unreachable_degrees(input, {2, 3, 4}).empty());
}
