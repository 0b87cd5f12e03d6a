#include "coons/mask/near_singular.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <utility>

#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/mask/stencil_system.h"
#include "solvers/registry.h"

using namespace coons;

TEST_CASE("estimate_eigenvalue_ratio: on two data rings it finds the closed-form smallest eigenvalue", "[mask]") {
  // Two data rings of an (m, n) net leave the (m−3)×(n−3) inside free: the one-ring system of
  // degree (m−2, n−2), whose eigenvalues the sine modes give (mask9_eigenvalue_ratio). The
  // estimate's min|λ| (ratio·‖A‖₁) is an upper bound of the true one and, near a singular α,
  // equal to it (away from one it may stop early: only its size matters there).
  const int m = 12, n = 9;
  StencilProblem p = rings_problem(ControlNet(m, n), 2);
  auto solver = solvers::make_solver("eigen-lu");
  for (double alpha : {0.3, 0.36, 0.5, 0.75, -0.4, -0.7}) {
    const Mask9 mask = alpha_mask(alpha);
    const StencilSystem system = assemble_stencil_system(p, alpha_stencil(mask));
    solvers::LinearOperator op;
    op.matrix = &system.A;
    REQUIRE(solver->analyze(op) == solvers::SolveStatus::kSuccess);
    REQUIRE(solver->factorize(op) == solvers::SolveStatus::kSuccess);
    const EigenvalueRatioEstimate e = estimate_eigenvalue_ratio(system.A, *solver, 40);
    REQUIRE(e.failure.ok());
    double lowest = HUGE_VAL, highest = 0;
    for (int a = 1; a < m - 2; ++a)
      for (int b = 1; b < n - 2; ++b) {
        const double ca = std::cos(M_PI * a / (m - 2)), cb = std::cos(M_PI * b / (n - 2));
        const double lambda = std::abs(1 - 2 * mask.edge_i * ca - 2 * mask.edge_j * cb - 4 * mask.diag * ca * cb);
        lowest = std::min(lowest, lambda);
        highest = std::max(highest, lambda);
      }
    REQUIRE(lowest / highest == Approx(mask9_eigenvalue_ratio(mask, m - 2, n - 2)).epsilon(1e-12));
    const double norm = 1 + 4 * std::abs(0.25 - alpha) + 4 * std::abs(alpha);  // ‖A‖₁ on the inside
    INFO("alpha " << alpha << ": estimate " << e.ratio * norm << ", min |lambda| " << lowest);
    CHECK(e.ratio * norm >= lowest * (1 - 1e-9));
  }
  // 1e-9 from each singular α of the modes (1, 1), (2, 5) and (9, 6), the default steps put the
  // estimate below the threshold
  for (auto [a, b] : {std::pair{1, 1}, std::pair{2, 5}, std::pair{9, 6}}) {
    const double ca = std::cos(M_PI * a / (m - 2)), cb = std::cos(M_PI * b / (n - 2));
    // λ = 1 − (ca + cb)/2 + α·(2(ca + cb) − 4·ca·cb) = 0
    const double star = -(1 - (ca + cb) / 2) / (2 * (ca + cb) - 4 * ca * cb) + 1e-9;
    const StencilSystem system = assemble_stencil_system(p, alpha_stencil(alpha_mask(star)));
    solvers::LinearOperator op;
    op.matrix = &system.A;
    REQUIRE(solver->analyze(op) == solvers::SolveStatus::kSuccess);
    REQUIRE(solver->factorize(op) == solvers::SolveStatus::kSuccess);
    const EigenvalueRatioEstimate e = estimate_eigenvalue_ratio(system.A, *solver);
    INFO("mode (" << a << ", " << b << "), alpha " << star << ": estimate " << e.ratio << " after " << e.solves);
    CHECK(e.failure.ok());
    CHECK(e.ratio <= kNearSingularEigenvalueRatio);
    const double norm = 1 + 4 * std::abs(0.25 - star) + 4 * std::abs(star);
    const double lowest = std::abs(1 - (ca + cb) / 2 + star * (2 * (ca + cb) - 4 * ca * cb));
    CHECK(e.ratio * norm == Approx(lowest).epsilon(1e-3));
  }
}

TEST_CASE("near_singular_summary: status singular, the ratio and the threshold named", "[mask]") {
  const solvers::SolveSummary s = near_singular_summary(2.5e-9, "closed-form eigenvalues");
  CHECK(s.status == solvers::SolveStatus::kSingular);
  CHECK(s.solver == "closed-form eigenvalues");
  CHECK_THAT(s.message, Catch::Contains("2.5e-09 <= 1e-06"));
}
