#include "coons/alpha/search_failures.h"

#include <catch2/catch.hpp>

using namespace coons;

namespace {
// A search between two intervals split by a pole at 0, where evaluations are refused: the optimum
// 0.02 (value 0.9) of the upper interval rests on its scan point 0.01; the scan point −0.01 below
// it belongs to the interval across the pole.
AlphaSearchSummary optimum_beside_a_pole() {
  AlphaSearchSummary s;
  s.status = SearchStatus::kSuccess;
  s.parameter = 0.02;
  s.value = 0.9;
  s.scan = {{-0.5, 3}, {-0.01, 5}, {0.01, 1}, {0.5, 2}};
  return s;
}
const std::vector<std::pair<double, bool>> kLog = {{-0.5, true}, {-0.01, true}, {-1e-5, false}, {1e-5, false},
                                                   {0.01, true}, {0.5, true},   {0.02, true}};
}  // namespace

TEST_CASE("judge_failures: an optimum is judged by the scan it rests on, not by a neighbour across a pole", "[alpha]") {
  AlphaSearchSummary joined = optimum_beside_a_pole();
  detail::judge_failures(joined, kLog);  // the joined scan: −0.01 and the failures at 0 are its evidence
  CHECK(joined.status == SearchStatus::kFailedRegion);
  CHECK_FALSE(joined.parameter);

  AlphaSearchSummary own = optimum_beside_a_pole();
  detail::judge_failures(own, kLog, {{0.01, 1}, {0.5, 2}});  // the upper interval's own scan
  INFO(own.message);
  CHECK(own.status == SearchStatus::kSuccess);
  REQUIRE(own.parameter);
  CHECK(*own.parameter == 0.02);
  CHECK(own.failed_evaluations == 2);
  CHECK(own.failed_intervals == std::vector<std::pair<double, double>>{{-1e-5, 1e-5}});
  CHECK_THAT(own.message, Catch::Contains("away from the optimum"));

  AlphaSearchSummary touched = optimum_beside_a_pole();  // its own scan reaching into the failures
  detail::judge_failures(touched, kLog, {{-2e-5, 7}, {0.01, 1}, {0.5, 2}});
  CHECK(touched.status == SearchStatus::kFailedRegion);
}
