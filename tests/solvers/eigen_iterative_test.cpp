// The Eigen Krylov backends (solvers/eigen_iterative.cpp): the iterations they report are the
// updates of x they did (one product with A each), whatever Eigen's own counter says.
#include <Eigen/SparseCore>
#include <catch2/catch.hpp>
#include <cmath>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

namespace {

SolveSummary solve_with(const char* name, const MaskSystem& s, const SolverOptions& options) {
  LinearOperator op;
  op.matrix = &s.A;
  op.stencil = s.stencil;
  Eigen::MatrixX3d X;
  return make_solver(name, options)->compute_and_solve(op, s.B, X);
}

}  // namespace

TEST_CASE("eigen krylov backends: a diagonal system takes one iteration not zero", "[solvers]") {
  // A = 2I: one step of CG (or of BiCGSTAB) is exact. Eigen's ConjugateGradient counts 0 for it.
  Eigen::SparseMatrix<double> A(6, 6);
  A.setIdentity();
  A *= 2;
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Random(6, 3);
  for (const char* name : {"cg", "cg-jacobi", "cg-ic", "bicgstab"}) {
    LinearOperator op;
    op.matrix = &A;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(name)->compute_and_solve(op, B, X);
    INFO(s.brief_report());
    REQUIRE(s.ok());
    CHECK(s.iterations == 1);
    CHECK((X - B / 2).cwiseAbs().maxCoeff() < 1e-15);
  }
}

TEST_CASE("cg: the reported iteration count is a limit under which the same solve converges", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(14, 12, 41), alpha_mask(-0.1));
  for (const char* name : {"cg", "cg-jacobi", "cg-ic"}) {
    SolverOptions options;
    options.tolerance = 1e-8;  // far above rounding: no refinement round adds iterations
    const SolveSummary free_run = solve_with(name, s, options);
    INFO(free_run.brief_report());
    REQUIRE(free_run.ok());
    const int k = free_run.iterations;
    REQUIRE(k > 2);
    options.max_iterations = k;
    const SolveSummary at_limit = solve_with(name, s, options);
    INFO(at_limit.brief_report());
    CHECK(at_limit.ok());
    CHECK(at_limit.iterations == k);
    options.max_iterations = k - 1;
    const SolveSummary below = solve_with(name, s, options);
    INFO(below.brief_report());
    CHECK(below.status == SolveStatus::kNotConverged);
    CHECK(below.iterations == k - 1);
  }
}

TEST_CASE("bicgstab: a right-hand side that is not finite ends the solve at once", "[solvers]") {
  // Eigen's BiCGSTAB returns without an update, not converged, when ‖b‖² is NaN; the backend called
  // it again and again until its iteration limit, which no call advanced: for ever. (The time limit
  // is only the way out the old loop had, here to keep the test from hanging.)
  const MaskSystem s = assemble_mask_system(make_random_net(8, 8, 47), alpha_mask(0.1));
  Eigen::MatrixX3d B = s.B;
  B(3, 0) = std::nan("");
  SolverOptions options;
  options.time_limit_seconds = 30;
  LinearOperator op;
  op.matrix = &s.A;
  Eigen::MatrixX3d X;
  const SolveSummary summary = make_solver("bicgstab", options)->compute_and_solve(op, B, X);
  INFO(summary.brief_report());
  CHECK(summary.status == SolveStatus::kDiverged);
  CHECK_THAT(summary.message, !Catch::Contains("time limit"));
  CHECK(X.allFinite());
}

TEST_CASE("bicgstab: a breakdown keeps the last finite iterate, not NaN turned into a zero X", "[solvers]") {
  // A tridiagonal matrix: its incomplete LU is exact, BiCGSTAB's residual vanishes within a few
  // steps, and at a tolerance below rounding the next step divides by rho = 0. The NaN was
  // reported as `diverged` ("grew from 1 to overflow") with X = 0, an exact solution thrown away.
  const int n = 3;
  Eigen::SparseMatrix<double> A(n, n);
  for (int i = 0; i < n; ++i) {
    A.insert(i, i) = 4;
    if (i > 0) A.insert(i, i - 1) = -1;
    if (i + 1 < n) A.insert(i, i + 1) = -1;
  }
  A.makeCompressed();
  const Eigen::MatrixX3d X_true = Eigen::MatrixX3d::Ones(n, 3);  // (bench-matrix's default B = A·1)
  const Eigen::MatrixX3d B = A * X_true;
  LinearOperator op;
  op.matrix = &A;
  SolverOptions below_rounding;
  below_rounding.tolerance = 1e-100;
  Eigen::MatrixX3d X;
  const SolveSummary s = make_solver("bicgstab", below_rounding)->compute_and_solve(op, B, X);
  INFO(s.brief_report());
  CHECK(s.status == SolveStatus::kNotConverged);
  CHECK_THAT(s.message, Catch::Contains("broke down"));
  CHECK(s.iterations >= 1);
  REQUIRE(X.allFinite());
  CHECK((X - X_true).cwiseAbs().maxCoeff() < 1e-13);
  CHECK(s.relative_residual < 1e-14);
  // at a reachable tolerance the same system is a success, as before
  const SolveSummary t = make_solver("bicgstab")->compute_and_solve(op, B, X);
  INFO(t.brief_report());
  CHECK(t.ok());
  CHECK((X - X_true).cwiseAbs().maxCoeff() < 1e-13);
}

TEST_CASE("eigen krylov backends: an iteration limit reached on a definite system is not_converged, not diverged",
          "[solvers]") {
  // CG's residual norm may rise before it falls: after one step on this α = −1/4 system it is 2.3
  // times the start, which was reported as `diverged` (and X thrown away).
  const MaskSystem s = assemble_mask_system(make_random_net(10, 10, 12), alpha_mask(-0.25));
  for (const char* name : {"cg", "cg-jacobi", "cg-ic", "bicgstab"}) {
    for (const int limit : {1, 3}) {
      SolverOptions options;
      options.max_iterations = limit;
      const SolveSummary summary = solve_with(name, s, options);
      INFO(name << ", limit " << limit << ": " << summary.brief_report());
      CHECK((summary.status == SolveStatus::kNotConverged || summary.status == SolveStatus::kSuccess));
    }
  }
}

TEST_CASE("eigen krylov backends: not_converged reports the true residual of the X it returns", "[solvers]") {
  // A tolerance no iteration reaches: CG's recurrence drove its estimate to 5.5e-127, which was
  // reported as the relative residual of an X whose true one is near 1e-16.
  const MaskSystem s = assemble_mask_system(make_random_net(6, 6, 13), alpha_mask(-0.1));
  LinearOperator op;
  op.matrix = &s.A;
  for (const char* name : {"cg", "cg-jacobi", "cg-ic"}) {
    SolverOptions options;
    options.tolerance = 1e-300;
    options.max_iterations = 100;
    Eigen::MatrixX3d X;
    const SolveSummary summary = make_solver(name, options)->compute_and_solve(op, s.B, X);
    INFO(name << ": " << summary.brief_report());
    REQUIRE(summary.status == SolveStatus::kNotConverged);
    const double truth = relative_residual(op, s.B, X);
    CHECK(summary.relative_residual == truth);
    CHECK(truth > 1e-20);
    CHECK_THAT(summary.message, Catch::Contains("true relative residual " + format_g(truth)));
  }
}
