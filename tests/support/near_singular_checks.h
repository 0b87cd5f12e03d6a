// The checks shared by the tests of a search whose lower bound sits just above a singular α
// (family_search_test.cpp, bspline_search_test.cpp): the first evaluations fail as singular and
// are located, none of them gives a value, and no optimum is claimed next to the singular α.
#pragma once

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/alpha/alpha_search.h"

namespace coons::test {

inline void check_refused_near_singular(const AlphaSearchSummary& s, const AlphaSearchOptions& options, double star) {
  CHECK(s.first_failure == solvers::SolveStatus::kSingular);
  REQUIRE_FALSE(s.failed_intervals.empty());
  CHECK(s.failed_intervals.front().first == options.lower);
  for (const auto& [lo, hi] : s.failed_intervals) CHECK(hi < star + 1e-6);
  REQUIRE_FALSE(s.scan.empty());
  CHECK(s.scan.front().second == HUGE_VAL);  // no value from the near-singular system
  if (s.parameter) CHECK(*s.parameter > star + 1e-6);
  CHECK(std::isfinite(s.value));
}

}  // namespace coons::test
