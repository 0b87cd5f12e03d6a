// The checks of a stencil problem (bad input of issue 11): a free grid of the wrong shape, too
// few data rings, free points in the rings or whose stencil leaves the net, and free sets that
// make the system singular, each naming the field and the point.
#include "coons/mask/stencil_problem.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <string>

#include "coons/io/input_error.h"
#include "coons/io/stencil_json.h"
#include "mask/stencil_reference.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

bool mentions(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

StencilProblem problem_with(int m, int n, int rings, FreeGrid free = {}) {
  StencilProblem p;
  p.net = make_random_net(m, n, 7);
  p.rings = rings;
  p.free = std::move(free);
  return p;
}

}  // namespace

TEST_CASE("check_stencil_problem: a valid problem has no issue", "[mask]") {
  CHECK(check_stencil_problem(problem_with(6, 9, 2), c1_coons_stencil()).empty());
  CHECK(check_stencil_problem(problem_with(6, 9, 1), alpha_stencil(alpha_mask(-0.25))).empty());
  CHECK(check_stencil_problem(problem_with(8, 5, 2, random_free(8, 5, 2, 0.6, 3)), biharmonic_stencil()).empty());
  CHECK(check_stencil_problem(problem_with(3, 3, 2), c1_coons_stencil()).empty());  // nothing free
}

TEST_CASE("check_stencil_problem: unusable options are the caller's error, not an issue of the input", "[mask]") {
  // ProblemCheckOptions::is_valid was never called: a dense_limit of 0, which it rejects, was used
  // as given. As an issue it would have read as bad input in the user's file.
  ProblemCheckOptions options;
  options.dense_limit = 0;
  CHECK_THROWS_WITH(check_stencil_problem(problem_with(6, 9, 2), c1_coons_stencil(), options),
                    "check_stencil_problem: dense_limit must be >= 1");
}

TEST_CASE("check_stencil_problem: a free grid of the wrong shape names the field", "[mask]") {
  const auto issues = check_stencil_problem(problem_with(5, 6, 1, FreeGrid::Constant(6, 6, false)), c1_coons_stencil());
  REQUIRE(issues.size() == 1);
  CHECK(issues[0].field == "free");
  CHECK(mentions(issues[0].reason, "6 rows of 6 points; the net has 6 rows of 7"));
}

TEST_CASE("check_stencil_problem: too few rings for a 5x5 mask", "[mask]") {
  const auto issues = check_stencil_problem(problem_with(6, 6, 1), biharmonic_stencil());
  REQUIRE(issues.size() >= 2);
  CHECK(issues[0].field == "rings");
  CHECK(mentions(issues[0].reason, "too few for a 5x5 mask"));
  // and the free points at depth 1 whose stencil leaves the net are named
  const auto leaves =
      std::find_if(issues.begin(), issues.end(), [](const ProblemIssue& i) { return i.field == "free[1][1]"; });
  REQUIRE(leaves != issues.end());
  CHECK(leaves->i == 1);
  CHECK(leaves->j == 1);
  CHECK(mentions(leaves->reason, "leaves the net"));
  CHECK(check_stencil_problem(problem_with(6, 6, -1), alpha_stencil(alpha_mask(0)))[0].field == "rings");
}

TEST_CASE("check_stencil_problem: a free point in the data rings is free when its stencil stays in the net", "[mask]") {
  FreeGrid free = random_free(7, 7, 2, 1.0, 1);
  free(1, 3) = true;
  const auto issues = check_stencil_problem(problem_with(7, 7, 2, free), c1_coons_stencil());
  REQUIRE(issues.size() == 1);
  CHECK(issues[0].field == "free[1][3]");
  CHECK(mentions(issues[0].reason, "the 5x5 mask at this free point leaves the net"));
  // The contract's example (docs/formats.md): two data rings and free points on the second ring
  // with a 3×3 mask, whose stencil there stays in the net: `free` decides.
  FreeGrid two = random_free(7, 7, 2, 1.0, 1);
  two(1, 3) = true;
  CHECK(check_stencil_problem(problem_with(7, 7, 2, two), alpha_stencil(alpha_mask(0))).empty());
  // With one data ring and a 3×3 mask the same point is a valid free point.
  FreeGrid one = random_free(7, 7, 1, 0.0, 1);
  one(1, 3) = true;
  one(4, 4) = true;
  const auto issues1 = check_stencil_problem(problem_with(7, 7, 1, one), alpha_stencil(alpha_mask(0)));
  CHECK(issues1.empty());
}

TEST_CASE("check_stencil_problem: a singular free set names the points that decouple", "[mask]") {
  // α = 1/2 (indefinite): a 2×2 free block is singular (λ = 1 − 2β(x+y) − 4αxy = 0 at x = y = −1/2),
  // a separate 3×3 block is not. The issue names exactly the four points of the 2×2 block.
  FreeGrid free = FreeGrid::Constant(12, 10, false);
  free.block(2, 2, 2, 2).setConstant(true);  // (2,2), (2,3), (3,2), (3,3)
  free.block(6, 4, 3, 3).setConstant(true);
  const StencilProblem p = problem_with(11, 9, 1, free);
  const Stencil s = alpha_stencil(alpha_mask(0.5));
  for (int dense_limit : {400, 1}) {  // the dense eigen-decomposition and the sparse inverse iteration
    INFO("dense_limit = " << dense_limit);
    ProblemCheckOptions options;
    options.dense_limit = dense_limit;
    const auto issues = check_stencil_problem(p, s, options);
    REQUIRE(issues.size() == 1);
    CHECK(issues[0].field == "free[2][2]");
    CHECK(mentions(issues[0].reason, "the free points (2, 2), (2, 3), (3, 2), (3, 3) decouple"));
    CHECK_FALSE(mentions(issues[0].reason, "(6, 4)"));
  }
  // the α family at m = n = 3 (a 2×2 interior) is singular at α = −1/2 too, and not at α = −1/4
  CHECK(check_stencil_problem(problem_with(3, 3, 1), alpha_stencil(alpha_mask(-0.5))).size() == 1);
  CHECK(check_stencil_problem(problem_with(3, 3, 1), alpha_stencil(alpha_mask(-0.25))).empty());
  // without the singular block nothing is reported
  free.block(2, 2, 2, 2).setConstant(false);
  CHECK(check_stencil_problem(problem_with(11, 9, 1, free), s).empty());
}

TEST_CASE("check_stencil_problem: the checks can be switched off and options are validated", "[mask]") {
  ProblemCheckOptions options;
  options.check_singular = false;
  CHECK(check_stencil_problem(problem_with(3, 3, 1), alpha_stencil(alpha_mask(-0.5)), options).empty());
  std::string why;
  CHECK(options.is_valid(&why));
  options.dense_limit = 0;
  CHECK_FALSE(options.is_valid(&why));
  CHECK(mentions(why, "dense_limit"));
}

TEST_CASE("require_valid_problem: throws InputError naming the file, the field and the point", "[mask]") {
  FreeGrid free = random_free(7, 7, 2, 1.0, 1);
  free(1, 5) = true;
  try {
    require_valid_problem(problem_with(7, 7, 2, free), c1_coons_stencil(), "hole.json");
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(e.field() == "free[1][5]");
    CHECK(std::string(e.what()) == "hole.json: free[1][5]: the 5x5 mask at this free point leaves the net");
  }
  CHECK_THROWS_AS(require_valid_problem(problem_with(3, 3, 1), alpha_stencil(alpha_mask(-0.5)), "x.json"), InputError);
  CHECK_NOTHROW(require_valid_problem(problem_with(7, 7, 2), c1_coons_stencil(), "x.json"));
}
