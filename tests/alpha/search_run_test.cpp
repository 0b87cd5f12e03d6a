// search_run.h includes Ceres, whose glog defines CHECK as Catch does: Catch's is the one used.
#include "coons/alpha/search_run.h"
#undef CHECK

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {
// f(p) = 1 + (p − 1)²(p + 1.25)² − 0.02(p − 1)²: the scan over [−2, 2] is lowest at its point 1
// (f = 1), while its point −1 (1.17) leads to the lower minimum at −1.25882 (0.897).
struct TwoBasins {
  struct Evaluation {
    double parameter = 0, value = 0, derivative = 0, derivative_noise = 0;
    bool has_derivative = true;
    solvers::SolveSummary summary;
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };
  NormalisedFrame frame = normalised_frame(make_random_boundary(3, 3, 1), objective_named("dirichlet"));
  int count = 0;
  Evaluation evaluate(double p, bool /*with_derivative*/ = true) {
    ++count;
    const double u = p - 1, v = p + 1.25;
    Evaluation e;
    e.parameter = p;
    e.value = 1 + u * u * v * v - 0.02 * u * u;
    e.derivative = 2 * u * v * v + 2 * u * u * v - 0.04 * u;
    return e;
  }
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return frame; }
  [[nodiscard]] int evaluations() const { return count; }
  [[nodiscard]] static int solves() { return 0; }
  [[nodiscard]] static double scale_origin() { return -0.25; }
};
}  // namespace

TEST_CASE("search_impl: every minimum of the scan is refined and the lowest result kept", "[alpha]") {
  TwoBasins f;
  AlphaSearchOptions options;
  options.lower = -2;
  options.upper = 2;
  const AlphaSearchSummary s = detail::search_impl(f, options);
  INFO(s.brief_report());
  REQUIRE(s.parameter);
  CHECK(s.status == SearchStatus::kSuccess);
  CHECK(*s.parameter == Approx((-5.5 - std::sqrt(5.5 * 5.5 - 16 * 0.585)) / 8).margin(1e-9));  // f' = 0
  CHECK(s.value < 0.91);
  CHECK_THAT(
      s.message,
      Catch::Contains("the best scan point and 1 other minima of the scan were refined and the lowest result kept"));
  CHECK_THAT(s.message, Catch::Contains("led to 1, value 1)"));  // in the caller's units
}
