// One harness for every registered backend (cf. AMGCL's tests, Eigen's sparse_solver.h): agreement
// with a dense reference, right-hand side untouched, analyze-once = fresh solves, failure statuses.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/matrix_checks.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

namespace {

struct Problem {
  MaskSystem system;
  Eigen::MatrixX3d reference;  // dense LU solution
};

Problem make_problem(int m, int n, double alpha, std::uint32_t seed) {
  Problem p;
  p.system = assemble_mask_system(make_random_net(m, n, seed), alpha_mask(alpha));
  p.reference = Eigen::MatrixXd(p.system.A).fullPivLu().solve(Eigen::MatrixXd(p.system.B));
  return p;
}

// The Jacobi iteration matrix is I − A (centre weight 1): it diverges when an eigenvalue of A
// leaves (0, 2), which happens for every α < 0 on large enough grids.
bool jacobi_diverges(const GridStencil& s) {
  const auto [lo, hi] = stencil_eigenvalue_range(s);
  return lo <= 0 || hi >= 2;
}

GridStencil grid_stencil_of(const ControlNet& net, double alpha) {
  return mask_stencil(alpha_mask(alpha), net.m - 1, net.n - 1);
}

// The backends built for other stencils: fast5 (5×5 a·C + b·T only) and separable-banded
// (separable stencils: of the α family only α = −1/4). They must say not_applicable here; their
// own classes are in stencil_conformance_test.cpp. hypre-pfmg declines α = ±1/4, where the
// stencil is not h-elliptic (its symbol vanishes at (π, 0) and at (π, π)): PFMG's point smoother
// cannot reduce those modes.
bool declines_alpha_mask(const std::string& name, double alpha) {
  return name == "fast5" || (name == "separable-banded" && alpha != -0.25) ||
         (name == "hypre-pfmg" && std::abs(alpha) == 0.25);
}

LinearOperator operator_of(const MaskSystem& s) {
  LinearOperator op;
  op.matrix = &s.A;
  op.stencil = s.stencil;
  return op;
}

}  // namespace

TEST_CASE("every solver: agrees with a dense reference on small nets", "[solvers]") {
  for (const SolverInfo& info : available_solvers()) {
    std::uint32_t seed = 1;
    for (auto [m, n] : {std::pair{3, 3}, {5, 9}, {10, 4}, {12, 12}})
      for (double alpha : {-0.25, -0.1, 0.0, 0.2, 0.25}) {
        const Problem p = make_problem(m, n, alpha, seed++);
        const Eigen::MatrixX3d B_copy = p.system.B;
        auto solver = make_solver(info.name);
        Eigen::MatrixX3d X;
        const SolveSummary s = solver->compute_and_solve(operator_of(p.system), p.system.B, X);
        INFO(info.name << ": m = " << m << ", n = " << n << ", alpha = " << alpha << ": " << s.brief_report());
        CHECK(p.system.B == B_copy);
        if (declines_alpha_mask(info.name, alpha)) {
          CHECK(s.status == SolveStatus::kNotApplicable);
          continue;
        }
        if (info.name == "jacobi" && jacobi_diverges(p.system.stencil)) {  // docs/math.md §3
          CHECK(s.status == SolveStatus::kDiverged);
          continue;
        }
        REQUIRE(s.ok());
        CHECK((X - p.reference).cwiseAbs().maxCoeff() < 1e-9 * std::max(1.0, p.reference.cwiseAbs().maxCoeff()));
        CHECK(s.relative_residual < 1e-10);
      }
  }
}

TEST_CASE("every solver: analyze once, factorize many equals fresh solves", "[solvers]") {
  for (const SolverInfo& info : available_solvers()) {
    if (declines_alpha_mask(info.name, -0.1)) continue;  // their sweeps: stencil_conformance_test.cpp
    const ControlNet net = make_random_net(8, 11, 77);
    auto reused = make_solver(info.name);
    const MaskSystem first = assemble_mask_system(net, alpha_mask(-0.25));
    REQUIRE(reused->analyze(operator_of(first)) == SolveStatus::kSuccess);
    for (double alpha : {-0.25, -0.2, -0.1, 0.0, 0.1}) {
      if (info.name == "jacobi" && jacobi_diverges(grid_stencil_of(net, alpha))) continue;  // tested above
      if (declines_alpha_mask(info.name, alpha)) continue;                                  // tested above
      const MaskSystem s = assemble_mask_system(net, alpha_mask(alpha));
      REQUIRE(reused->factorize(operator_of(s)) == SolveStatus::kSuccess);
      Eigen::MatrixX3d X_reused, X_fresh;
      const SolveSummary reused_summary = reused->solve(s.B, X_reused);
      const SolveSummary fresh_summary = make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X_fresh);
      INFO(info.name << ", alpha = " << alpha << ": " << reused_summary.brief_report() << " / "
                     << fresh_summary.brief_report());
      REQUIRE(reused_summary.ok());
      REQUIRE(fresh_summary.ok());
      CHECK((X_reused - X_fresh).cwiseAbs().maxCoeff() < 1e-12);
    }
  }
}

TEST_CASE("every solver: reports indefinite and singular systems", "[solvers]") {
  for (const SolverInfo& info : available_solvers()) {
    INFO(info.name);
    {  // α = −1/2 at m = n = 3 is singular
      const MaskSystem s = assemble_mask_system(make_random_net(3, 3, 5), alpha_mask(-0.5));
      Eigen::MatrixX3d X;
      const SolveSummary summary = make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X);
      INFO(summary.brief_report());
      CHECK(summary.status != SolveStatus::kSuccess);
      if (info.family == SolverFamily::kDirect)
        CHECK((summary.status == SolveStatus::kSingular || summary.status == SolveStatus::kNotPositiveDefinite));
    }
    {  // α = −0.4 on a 20×20 net is indefinite
      const MaskSystem s = assemble_mask_system(make_random_net(20, 20, 6), alpha_mask(-0.4));
      Eigen::MatrixX3d X;
      const SolveSummary summary = make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X);
      INFO(summary.brief_report());
      if (info.definite_only)
        CHECK(summary.status == SolveStatus::kNotPositiveDefinite);
      else if (info.name == "jacobi")
        CHECK(summary.status == SolveStatus::kDiverged);
      else if (summary.ok())
        CHECK(summary.relative_residual < 1e-8);
      CHECK(std::isfinite(summary.relative_residual));
    }
  }
}

TEST_CASE("every exact solver: a failed solve reports the residual of the X it returns, 1 for X = 0", "[solvers]") {
  // docs/formats.md, "The solver block": a failed factorisation returns X = 0, whose relative
  // residual ‖A·0 − B‖/‖B‖ is 1 (it used to say 0, the value of a perfect solve)
  int zero_solutions = 0;
  for (const SolverInfo& info : available_solvers()) {
    if (info.family == SolverFamily::kIterative) continue;             // a diverged iteration names its own residual
    for (const auto& [n, alpha] : {std::pair{3, -0.5}, {20, -0.4}}) {  // singular, indefinite
      const MaskSystem s = assemble_mask_system(make_random_net(n, n, 7), alpha_mask(alpha));
      Eigen::MatrixX3d X;
      const SolveSummary summary = make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X);
      INFO(info.name << ", alpha = " << alpha << ": " << summary.brief_report());
      if (summary.ok()) continue;
      REQUIRE(X.rows() == s.B.rows());
      CHECK(summary.relative_residual == Approx(relative_residual(operator_of(s), s.B, X)).epsilon(1e-12));
      if (X.isZero(0)) {
        CHECK(summary.relative_residual == 1);
        ++zero_solutions;
      }
    }
  }
  CHECK(zero_solutions > 0);  // eigen-llt, at least, cannot factorize them
  // a failed member of a sweep likewise
  const ControlNet net = make_random_net(20, 20, 7);
  const MaskSystem good = assemble_mask_system(net, alpha_mask(-0.1)),
                   bad = assemble_mask_system(net, alpha_mask(-0.4));
  std::vector<SolveSummary> sunk;
  make_solver("eigen-llt")
      ->sweep({good.B, bad.B}, {{operator_of(good), {1, 0}}, {operator_of(bad), {0, 1}}},
              [&](std::size_t, const Eigen::MatrixX3d& X, const SolveSummary& summary) {
                sunk.push_back(summary);
                CHECK(X.rows() == good.B.rows());
                if (!summary.ok()) CHECK(X.isZero(0));
              });
  REQUIRE(sunk.size() == 2);
  CHECK(sunk[0].ok());
  CHECK(sunk[0].relative_residual < 1e-10);
  CHECK(sunk[1].status == SolveStatus::kNotPositiveDefinite);
  CHECK(sunk[1].relative_residual == 1);
}

TEST_CASE("registry: names are unique and make_solver knows every listed name", "[solvers]") {
  std::set<std::string> names;
  for (const SolverInfo& info : available_solvers()) {
    CHECK(names.insert(info.name).second);
    auto solver = make_solver(info.name);
    REQUIRE(solver);
    CHECK(solver->name() == info.name);
    CHECK(find_solver(info.name) == &info);
  }
  CHECK(!make_solver("no-such-solver"));
  CHECK(find_solver("eigen-ldlt"));
}

TEST_CASE("stencil_matrix: apply_stencil equals the matrix product", "[solvers]") {
  GridStencil s{7, 5, 1.0, -0.3, -0.2, 0.05};
  const Eigen::SparseMatrix<double> A = stencil_matrix(s);
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(s.size(), 3);
  Eigen::MatrixXd Y;
  apply_stencil(s, X, Y);
  CHECK((Y - A * X).cwiseAbs().maxCoeff() < 1e-15);
  // eigenvalues in closed form
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Eigen::MatrixXd(A)).eigenvalues();
  const auto [lo, hi] = stencil_eigenvalue_range(s);
  CHECK(lo == Approx(ev.minCoeff()).epsilon(1e-12));
  CHECK(hi == Approx(ev.maxCoeff()).epsilon(1e-12));
}

TEST_CASE("jacobi: diverges for alpha < 0 on a large net and says so", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(30, 30, 8), alpha_mask(-0.25));
  Eigen::MatrixX3d X;
  const SolveSummary summary = make_solver("jacobi")->compute_and_solve(operator_of(s), s.B, X);
  CHECK(summary.status == SolveStatus::kDiverged);
  CHECK_THAT(summary.message, Catch::Contains("grew"));
  CHECK(X.allFinite());
  CHECK(std::isfinite(summary.relative_residual));
}

TEST_CASE("gauss-seidel: converges at alpha = -1/4, and SOR needs fewer sweeps", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(10, 10, 9), alpha_mask(-0.25));
  Eigen::MatrixX3d X_gs, X_sor;
  SolverOptions sor;
  sor.sor_omega = 1.8;
  const SolveSummary gs = make_solver("gauss-seidel")->compute_and_solve(operator_of(s), s.B, X_gs);
  const SolveSummary fast = make_solver("gauss-seidel", sor)->compute_and_solve(operator_of(s), s.B, X_sor);
  REQUIRE(gs.ok());
  REQUIRE(fast.ok());
  CHECK(fast.iterations < gs.iterations);
  CHECK((X_gs - X_sor).cwiseAbs().maxCoeff() < 1e-8);
}

TEST_CASE("gauss-seidel: SOR near omega = 2 on a definite system stops not_converged, never diverged", "[solvers]") {
  // Ostrowski–Reich: SOR converges for 0 < ω < 2 on a positive definite system, but its residual
  // rises first (ω = 1.9 on a degree-8 net: 1.85 after one sweep, 2.2 after 5). A residual above
  // its start at the iteration limit was called diverged and the iterate thrown away.
  const MaskSystem s = assemble_mask_system(make_random_net(8, 8, 1), alpha_mask(-0.25));
  for (const double omega : {1.9, 1.99}) {
    SolverOptions o;
    o.sor_omega = omega;
    o.max_iterations = 5;
    Eigen::MatrixX3d X;
    const SolveSummary r = make_solver("gauss-seidel", o)->compute_and_solve(operator_of(s), s.B, X);
    INFO("omega = " << omega << ": " << r.brief_report());
    CHECK(r.status == SolveStatus::kNotConverged);
    CHECK(r.relative_residual == Approx(relative_residual(operator_of(s), s.B, X)).epsilon(1e-12));
    CHECK_FALSE(X.isZero(0));  // the iterate is kept
  }
  // Jacobi at α = −1/4 really diverges: still diverged
  SolverOptions few;
  few.max_iterations = 50;
  Eigen::MatrixX3d X;
  CHECK(make_solver("jacobi", few)->compute_and_solve(operator_of(s), s.B, X).status == SolveStatus::kDiverged);
}

TEST_CASE("iterative backends: a tolerance below rounding with 2^31 iterations stops as stagnated, not hours later",
          "[solvers]") {
  // --tolerance 1e-300 --max-iterations 2147483647 ran cg, cg-jacobi, cg-ic, bicgstab, jacobi and
  // gauss-seidel for 30 minutes to hours on a 7x7 net: nothing noticed the residual had stopped
  // falling at about 1e-16. The iteration counts below are the proof: a run to the limit would be
  // 2^31 (counts are deterministic, so this checks no clock).
  // (degree 20: hypre's PCG stops on its error flag at a true residual of 3e-13 there, which a
  // floor tuned on 7x7 nets, 1e-13, called a breakdown)
  for (const auto& [degree, alpha] : {std::pair{6, -0.25}, std::pair{6, 0.0}, std::pair{20, -0.25}}) {
    const MaskSystem s = assemble_mask_system(make_random_net(degree, degree, 3), alpha_mask(alpha));
    SolverOptions o;
    o.tolerance = 1e-300;
    o.max_iterations = std::numeric_limits<int>::max();
    for (const SolverInfo& info : available_solvers()) {
      if (info.family != SolverFamily::kIterative) continue;
      if (info.name == "jacobi" && jacobi_diverges(s.stencil)) continue;  // diverged: its own test
      if (declines_alpha_mask(info.name, alpha)) continue;
      Eigen::MatrixX3d X;
      const SolveSummary r = make_solver(info.name, o)->compute_and_solve(operator_of(s), s.B, X);
      INFO(info.name << " at degree " << degree << ", alpha = " << alpha << ": " << r.brief_report());
      CHECK(r.status == SolveStatus::kNotConverged);
      CHECK(r.iterations < 100'000);
      CHECK(r.relative_residual < 1e-13);
      CHECK(r.relative_residual == Approx(relative_residual(operator_of(s), s.B, X)).epsilon(1e-6));
      CHECK((X - Eigen::MatrixXd(s.A).fullPivLu().solve(Eigen::MatrixXd(s.B))).cwiseAbs().maxCoeff() < 1e-10);
    }
  }
}

TEST_CASE("gauss-seidel: SOR whose residual stays flat for a while far above rounding is not called stagnated",
          "[solvers]") {
  // omega = 1.99 at degree 20: the residual stays near 0.03 for over 1000 sweeps, then falls
  // steadily to 1e-12. A stagnation test without a floor stopped it there, not_converged.
  const MaskSystem s = assemble_mask_system(make_random_net(20, 20, 5), alpha_mask(-0.25));
  SolverOptions o;
  o.sor_omega = 1.99;
  o.tolerance = 1e-10;
  Eigen::MatrixX3d X;
  const SolveSummary r = make_solver("gauss-seidel", o)->compute_and_solve(operator_of(s), s.B, X);
  INFO(r.brief_report());
  CHECK(r.status == SolveStatus::kSuccess);
  CHECK(r.message.find("stagnated") == std::string::npos);
}

TEST_CASE("iteration_limit: automatic limits are finite and bounded by the work", "[solvers]") {
  const SolverOptions automatic;
  CHECK(iteration_limit(automatic, 3844, 1000, 1e8) == 26014);  // 64×64 net: 1e8 / 3844 sweeps
  CHECK(iteration_limit(automatic, 9, 1000, 1e8) == 9000);      // small nets: 1000 per unknown
  CHECK(iteration_limit(automatic, 1, 20, 2e10) == 100);        // at least 100
  CHECK(iteration_limit(automatic, 1'000'000'000, 1000, 1e8) == 100);
  SolverOptions fixed;
  fixed.max_iterations = 7;
  CHECK(iteration_limit(fixed, 3844, 1000, 1e8) == 7);
}

namespace {
// The α = −1/4 system of a random degree-n net solved by `name`.
SolveSummary solve_coons_system(const char* name, int n, std::uint32_t seed, const SolverOptions& options,
                                MaskSystem& s, Eigen::MatrixX3d& X) {
  s = assemble_mask_system(make_random_net(n, n, seed), alpha_mask(-0.25));
  return make_solver(name, options)->compute_and_solve(operator_of(s), s.B, X);
}
}  // namespace

TEST_CASE("gauss-seidel: a 64x64 net stops at the automatic limit with the residual reached", "[solvers]") {
  // At α = −1/4 Gauss–Seidel needs O(N⁴) sweeps here: the finite automatic limit stops it.
  MaskSystem s;
  Eigen::MatrixX3d X;
  const SolveSummary summary = solve_coons_system("gauss-seidel", 63, 12, {}, s, X);
  INFO(summary.brief_report());
  REQUIRE(summary.status == SolveStatus::kNotConverged);
  CHECK(summary.iterations == iteration_limit(SolverOptions{}, s.B.rows(), 1000, 1e8));
  CHECK(summary.relative_residual > SolverOptions{}.tolerance);
  CHECK(summary.relative_residual < 1);
  CHECK(summary.relative_residual == Approx(relative_residual(operator_of(s), s.B, X)).epsilon(1e-12));
  CHECK_THAT(summary.message, Catch::Contains("residual " + format_g(summary.relative_residual)));
  CHECK_THAT(summary.message, Catch::Contains("iteration limit"));
  CHECK_THAT(summary.message, Catch::Contains("tolerance 1e-12"));
}

TEST_CASE("iterative solvers: the time limit stops them with not_converged", "[solvers]") {
  SolverOptions options;
  options.time_limit_seconds = 1e-3;
  options.max_iterations = 1'000'000;
  for (const char* name : {"gauss-seidel", "cg"}) {
    MaskSystem s;
    Eigen::MatrixX3d X;
    const SolveSummary summary = solve_coons_system(name, 63, 13, options, s, X);
    INFO(name << ": " << summary.brief_report());
    CHECK(summary.status == SolveStatus::kNotConverged);
    CHECK(summary.iterations < options.max_iterations);
    CHECK(std::isfinite(summary.relative_residual));
    CHECK_THAT(summary.message, Catch::Contains("time limit 0.001 s"));
    CHECK_THAT(summary.message, Catch::Contains("residual " + format_g(summary.relative_residual)));
  }
}

TEST_CASE("jacobi: a diverged solve reports the residual it reached, not that of the zero net", "[solvers]") {
  MaskSystem s;
  Eigen::MatrixX3d X;
  const SolveSummary summary = solve_coons_system("jacobi", 30, 8, {}, s, X);
  INFO(summary.brief_report());
  REQUIRE(summary.status == SolveStatus::kDiverged);
  CHECK(summary.relative_residual > 1e8);  // grew 1e8-fold from 1
  CHECK(std::isfinite(summary.relative_residual));
  CHECK_THAT(summary.message, Catch::Contains("to " + format_g(summary.relative_residual)));
  CHECK_THAT(summary.brief_report(), Catch::Contains("residual " + format_g(summary.relative_residual)));
  CHECK(X.isZero(0));
}

TEST_CASE("SolverOptions: a negative or non-finite time limit is invalid", "[solvers]") {
  std::string why;
  SolverOptions options;
  CHECK(options.is_valid(&why));
  options.time_limit_seconds = -1;
  CHECK_FALSE(options.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("time_limit_seconds"));
  options.time_limit_seconds = HUGE_VAL;
  CHECK_FALSE(options.is_valid(&why));
}

TEST_CASE("LinearSolver::analyze: unusable options are a failure naming the option, on every backend", "[solvers]") {
  // is_valid was the CLI's to call: a library caller's tolerance of 2 reached the iterations
  const MaskSystem s = assemble_mask_system(make_random_net(6, 5, 4), alpha_mask(-0.1));
  SolverOptions options;
  options.tolerance = 2;
  for (const SolverInfo& info : available_solvers()) {
    Eigen::MatrixX3d X;
    const SolveSummary summary = make_solver(info.name, options)->compute_and_solve(operator_of(s), s.B, X);
    INFO(info.name << ": " << summary.brief_report());
    CHECK(summary.status == SolveStatus::kFailure);
    CHECK(summary.message == "invalid solver options: tolerance must lie in (0, 1)");
    CHECK(X.isZero(0));
    CHECK(summary.relative_residual == 1);  // of X = 0
  }
}

TEST_CASE("SolverOptions: threads lie in 0 .. 256, and 0 means every core", "[solvers]") {
  std::string why;
  SolverOptions options;
  CHECK(options.threads == 1);
  for (int threads : {0, 1, 2, kMaxThreads}) {
    options.threads = threads;
    CHECK(options.is_valid(&why));
  }
  for (int threads : {-1, kMaxThreads + 1}) {
    options.threads = threads;
    CHECK_FALSE(options.is_valid(&why));
    CHECK_THAT(why, Catch::Contains("threads"));
  }
  CHECK(resolved_threads(3) == 3);
  CHECK(resolved_threads(0) >= 1);
  CHECK(resolved_threads(0) <= kMaxThreads);
}

TEST_CASE("options_problem: names the first unusable field, and is_valid says the same", "[solvers]") {
  using F = SolverOptionsField;
  CHECK(options_problem(SolverOptions{}).field == F::kNone);
  const std::vector<std::pair<F, std::function<void(SolverOptions&)>>> cases = {
      {F::kTolerance, [](SolverOptions& o) { o.tolerance = 1; }},
      {F::kTolerance, [](SolverOptions& o) { o.tolerance = std::nan(""); }},
      {F::kMaxIterations, [](SolverOptions& o) { o.max_iterations = -1; }},
      {F::kTimeLimitSeconds, [](SolverOptions& o) { o.time_limit_seconds = -1; }},
      {F::kSorOmega, [](SolverOptions& o) { o.sor_omega = 2; }},
      {F::kSingularResidual, [](SolverOptions& o) { o.singular_residual = 0; }},
      {F::kThreads, [](SolverOptions& o) { o.threads = kMaxThreads + 1; }},
  };
  for (const auto& [field, spoil] : cases) {
    SolverOptions options;
    spoil(options);
    const SolverOptionsProblem problem = options_problem(options);
    INFO(to_string(field));
    CHECK(problem.field == field);
    CHECK_FALSE(problem.reason.empty());
    std::string why;
    CHECK_FALSE(options.is_valid(&why));
    CHECK(why == std::string(to_string(field)) + " " + problem.reason);
  }
}

TEST_CASE("format_g: prints like %g, never 0.000000 for a small tolerance", "[solvers]") {
  CHECK(format_g(1e-12) == "1e-12");
  CHECK(format_g(0.25) == "0.25");
  CHECK(format_g(1.4e8) == "1.4e+08");
}

TEST_CASE("check_preconditioner_matrix: an empty row or a zero diagonal is refused before a library crashes on it",
          "[solvers]") {
  // a matrix with no entries made cg-ic segfault (Eigen's IncompleteCholesky) and hypre-amg abort
  // the process; a matrix whose last row is empty made hypre-amg call MPI_Abort
  Eigen::SparseMatrix<double> empty(3, 3), last_empty(3, 3);
  last_empty.insert(0, 0) = 1;
  last_empty.insert(1, 1) = 1;
  last_empty.makeCompressed();
  const auto reason = [](const Eigen::SparseMatrix<double>& A, bool need_diagonal, SolveStatus expected) {
    std::string why;
    CHECK(check_preconditioner_matrix(A, need_diagonal, &why) == expected);
    return why;
  };
  CHECK(reason(empty, false, SolveStatus::kSingular) == "row 0 (counting from 0) is empty: the matrix is singular");
  CHECK(reason(last_empty, false, SolveStatus::kSingular) ==
        "row 2 (counting from 0) is empty: the matrix is singular");
  Eigen::SparseMatrix<double> off(2, 2);
  off.insert(0, 1) = 1;
  off.insert(1, 0) = 1;
  CHECK(reason(off, false, SolveStatus::kSuccess).empty());
  CHECK(reason(off, true, SolveStatus::kNotApplicable) ==
        "the diagonal is zero at row 0 (counting from 0): the preconditioner needs it");
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(3, 3);
  for (const SolverInfo& info : available_solvers()) {
    if (info.family != SolverFamily::kIterative || !info.needs_matrix) continue;
    for (const Eigen::SparseMatrix<double>* A : {&empty, &last_empty}) {
      LinearOperator op;
      op.matrix = A;
      Eigen::MatrixX3d X;
      const SolveSummary s = make_solver(info.name)->compute_and_solve(op, B, X);
      INFO(info.name << ": " << s.brief_report());
      CHECK_FALSE(s.ok());
    }
  }
}
