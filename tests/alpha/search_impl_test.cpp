// search_impl.h includes Ceres, whose glog defines CHECK as Catch does: Catch's is the one used.
#include "coons/alpha/search_impl.h"
#undef CHECK

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {
// What the search asks of an evaluator besides evaluate(): its frame (that of a small random
// boundary, for the flat test's scale), the evaluations counted, no solves.
struct SyntheticObjective {
  struct Evaluation {
    double parameter = 0, value = 0, derivative = 0, derivative_noise = 0;
    bool has_derivative = true;
    solvers::SolveSummary summary;
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };
  NormalisedFrame frame = normalised_frame(make_random_boundary(3, 3, 1), objective_named("dirichlet"));
  int count = 0;
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return frame; }
  [[nodiscard]] int evaluations() const { return count; }
  [[nodiscard]] static int solves() { return 0; }
  [[nodiscard]] static double scale_origin() { return -0.25; }
};

// f(p) = 1 + (p − 1)²(p + 1.25)² − 0.02(p − 1)²: the scan over [−2, 2] is lowest at its point 1
// (f = 1), while its point −1 (1.17) leads to the lower minimum at −1.25882 (0.897).
struct TwoBasins : SyntheticObjective {
  Evaluation evaluate(double p, bool /*with_derivative*/ = true) {
    ++count;
    const double u = p - 1, v = p + 1.25;
    Evaluation e;
    e.parameter = p;
    e.value = 1 + u * u * v * v - 0.02 * u * u;
    e.derivative = 2 * u * v * v + 2 * u * u * v - 0.04 * u;
    return e;
  }
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

namespace {
// A pole at 0, with evaluations refused within `refuse` of it, and on one side (q = side·p > 0) a
// narrow dip at q0 between the pole and the interval's first scan point, behind the basin at
// q = 0.6: f = 1 + (q − 0.6)² − 0.8·exp(−((q − q0)/w)²) + strength/p². The other side rises to 2.
// With `root`, that side is f = 1 + 0.1·q^(1/8) + strength/p² instead: it falls towards the pole
// down to q ≈ 1e-13 (strength 1e-30).
struct PoleWithDip : SyntheticObjective {
  double side = 1, q0 = 0.03, w = 0.015, refuse = 1e-4, strength = 1e-9;
  bool root = false;
  Evaluation evaluate(double p, bool /*with_derivative*/ = true) {
    ++count;
    Evaluation e;
    e.parameter = p;
    if (std::abs(p) < refuse) {
      e.summary.status = solvers::SolveStatus::kSingular;
      return e;
    }
    const double q = side * p, pole = strength / (p * p), dpole = -2 * strength / (p * p * p);
    if (q < 0) {
      e.value = 2 + p * p + pole;
      e.derivative = 2 * p + dpole;
      return e;
    }
    if (root) {
      e.value = 1 + 0.1 * std::pow(q, 0.125) + pole;
      e.derivative = side * 0.0125 * std::pow(q, -0.875) + dpole;
      return e;
    }
    const double z = (q - q0) / w, dip = 0.8 * std::exp(-z * z);
    e.value = 1 + (q - 0.6) * (q - 0.6) - dip + pole;
    e.derivative = side * (2 * (q - 0.6) + dip * 2 * z / w) + dpole;
    return e;
  }
  [[nodiscard]] static std::vector<double> singular_parameters(double lower, double upper) {
    return lower < 0 && 0 < upper ? std::vector<double>{0.0} : std::vector<double>{};
  }
};
}  // namespace

TEST_CASE("search_impl: a minimum between a pole and its interval's first scan point is found", "[alpha]") {
  // Over [−1, 1] each interval's scan starts 1/8 off the pole. The dip at 0.03 lies in that margin
  // behind a rise, so no slope there points to it; the dip at 0.004 lies within 1/128 of the pole,
  // where the objective falls towards it. Before, the basin at 0.6 (value 1) was reported.
  for (const double side : {1.0, -1.0}) {
    for (const auto& [q0, w] : {std::pair{0.03, 0.015}, std::pair{0.004, 0.002}}) {
      PoleWithDip f;
      f.side = side;
      f.q0 = q0;
      f.w = w;
      AlphaSearchOptions options;
      options.lower = -1;
      options.upper = 1;
      const AlphaSearchSummary s = detail::search_impl(f, options);
      INFO("side " << side << ", dip at " << q0 << ": " << s.brief_report());
      REQUIRE(s.parameter);
      CHECK(s.status == SearchStatus::kSuccess);
      CHECK(side * *s.parameter == Approx(q0).margin(w / 4));
      CHECK(s.value < 0.6);
      CHECK(std::abs(f.evaluate(*s.parameter).derivative) < 1e-6);  // a stationary point, not a scan point
    }
  }
}

TEST_CASE("search_impl: a minimum closer to a pole than the margin searches go is no success", "[alpha]") {
  // The objective falls towards the pole down to about 1e-13 off it; the margin searches stop at
  // 1/16⁸ of the margin (1/8 here): 2.9e-11. The closest point searched was reported as a success
  // with a slope of 1.7e9; with evaluations refused within 1e-7 of the pole, the closest point
  // solved, 1.2e-7, as a success with a slope of 1.4e4.
  for (const double refuse : {1e-15, 1e-7})
    for (const double side : {1.0, -1.0}) {
      PoleWithDip f;
      f.side = side;
      f.root = true;
      f.refuse = refuse;
      f.strength = 1e-30;
      AlphaSearchOptions options;
      options.lower = -1;
      options.upper = 1;
      const AlphaSearchSummary s = detail::search_impl(f, options);
      INFO("side " << side << ", refused within " << refuse << ": " << s.brief_report() << " " << s.message);
      CHECK(s.status == SearchStatus::kNotConverged);
      CHECK_THAT(s.message, Catch::Contains("still falls towards the pole at 0 at the closest point solved"));
      REQUIRE(s.parameter);
      if (refuse < 1e-11) {
        CHECK(s.failed_evaluations == 0);
        CHECK(side * *s.parameter == Approx(0.125 / std::pow(16.0, 8)).epsilon(1e-9));
      } else {
        CHECK(s.failed_evaluations > 0);
        CHECK(side * *s.parameter > refuse);  // the closest point solved
        CHECK(side * *s.parameter < 1e-6);
      }
    }
}
