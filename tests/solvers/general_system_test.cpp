// Backends on general systems from outside coons (solvers/general_system.h).
#include "solvers/general_system.h"

#include <Eigen/LU>
#include <array>
#include <catch2/catch.hpp>
#include <random>

#include "support/fixtures.h"

using namespace coons::solvers;

namespace {

Eigen::SparseMatrix<double> sparse_of(const Eigen::MatrixXd& dense) { return dense.sparseView(); }

// The system run_general_system reads, borrowing A and B; balanced as bench-matrix balances it.
GeneralSystem system_of(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B, bool symmetric) {
  GeneralSystem system;
  system.A = &A;
  system.B = &B;
  system.symmetric = symmetric;
  system.exponent = balancing_exponent(A);
  return system;
}

// A diagonally dominant, nonsymmetric n by n matrix with a few off-diagonal entries per row.
Eigen::SparseMatrix<double> random_nonsymmetric(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, 8 + u(rng));
    for (int k = 0; k < 3; ++k) t.emplace_back(i, int((i * 7 + k * 13 + 1) % n), u(rng));
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

TEST_CASE("backward_error: the exact solution of a system is at rounding level", "[solvers]") {
  const Eigen::SparseMatrix<double> A = random_nonsymmetric(50, 3);
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(50, 2);
  const Eigen::MatrixXd B = A * X;  // X is exact up to the rounding of this product
  const double error = backward_error(A, X, B);
  CHECK(error < 4e-16);
  CHECK(relative_residual(A, X, B) < 1e-15);
}

TEST_CASE("backward_error: a perturbed solution has the Oettli-Prager value", "[solvers]") {
  // A = [2 1; 1 3], x = (1, 1), b = (3, 4); x' = (1.1, 1): r = (-0.2, -0.1),
  // |A||x'| + |b| = (6.2, 8.1), so the backward error is max(0.2/6.2, 0.1/8.1) = 1/31.
  const Eigen::SparseMatrix<double> A = sparse_of((Eigen::MatrixXd(2, 2) << 2, 1, 1, 3).finished());
  const Eigen::MatrixXd B = (Eigen::MatrixXd(2, 1) << 3, 4).finished();
  const Eigen::MatrixXd exact = Eigen::MatrixXd::Ones(2, 1);
  const Eigen::MatrixXd perturbed = (Eigen::MatrixXd(2, 1) << 1.1, 1).finished();
  CHECK(backward_error(A, exact, B) == 0);
  CHECK(backward_error(A, perturbed, B) == Approx(1.0 / 31).epsilon(1e-14));
  // and the worst column counts: the exact column beside it changes nothing
  Eigen::MatrixXd both(2, 2), rhs(2, 2);
  both << exact, perturbed;
  rhs << B, B;
  CHECK(backward_error(A, both, rhs) == Approx(1.0 / 31).epsilon(1e-14));
  // ‖r‖/‖b‖ = √0.05 / 5
  CHECK(relative_residual(A, perturbed, B) == Approx(std::sqrt(0.05) / 5).epsilon(1e-14));
}

TEST_CASE("relative_residual: right-hand sides near underflow or overflow give the unscaled ratio", "[solvers]") {
  const Eigen::SparseMatrix<double> A = random_nonsymmetric(40, 5);
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(40, 2);
  const Eigen::MatrixXd B = A * Eigen::MatrixXd::Random(40, 2);  // X is far from the solution
  const double plain = relative_residual(A, X, B);
  REQUIRE(plain > 0.1);
  for (const int e : {-600, 540}) {  // squares of about 1e-361 and 1e+325
    const double scale = std::ldexp(1.0, e);
    CHECK(relative_residual(A, X * scale, B * scale) == Approx(plain).epsilon(1e-14));
  }
}

TEST_CASE("backward_error and relative_residual: sums that overflow on the way to a finite A x are measured scaled",
          "[solvers]") {
  // Both figures are ratios that a common power of two on x and b leaves alone, bit for bit: each
  // system is measured as it is (near the top of the doubles) and scaled down by 2^-64, where no
  // sum overflows.
  const auto dense = [](std::initializer_list<double> v) {
    Eigen::SparseMatrix<double> A(2, 2);
    const auto* a = v.begin();
    A.insert(0, 0) = a[0];
    A.insert(0, 1) = a[1];
    A.insert(1, 0) = a[2];
    A.insert(1, 1) = a[3];
    return A;
  };
  // A x = (0.7e308, 1.3e308) for x = (0.95e308, 0.6e308), but 2·0.95e308 is beyond the doubles: the
  // residual went through +inf (every bench-matrix backend `failure`).
  const Eigen::SparseMatrix<double> A1 = dense({2, -2, 2, -1});
  // |A||x| + |b| overflows in the second row while A x is finite: the backward error was r/inf = 0.
  const Eigen::SparseMatrix<double> A2 = dense({1.1, -0.9, 0.3, 1.3});
  const std::pair<const Eigen::SparseMatrix<double>*, Eigen::Vector2d> systems[] = {{&A1, {0.7e308, 1.3e308}},
                                                                                    {&A2, {0.2e308, 1.6e308}}};
  const double down = std::ldexp(1.0, -64);
  for (const auto& [A, b] : systems) {
    const Eigen::MatrixXd B = b;
    // (a dense LU of the system as it stands overflows too: solved scaled down, scaled back up)
    const Eigen::MatrixXd X = Eigen::MatrixXd(*A).partialPivLu().solve(B * down) / down;
    REQUIRE(X.allFinite());
    const double residual = relative_residual(*A, X, B), error = backward_error(*A, X, B);
    CHECK(residual == relative_residual(*A, X * down, B * down));
    CHECK(error == backward_error(*A, X * down, B * down));
    CHECK(residual < 1e-15);
    CHECK(error < 1e-15);
  }
  // the second system's residual is not zero, so neither is its backward error
  const Eigen::MatrixXd B2 = systems[1].second;
  const Eigen::MatrixXd X2 = Eigen::MatrixXd(A2).partialPivLu().solve(B2 * down) / down;
  REQUIRE(relative_residual(A2, X2, B2) > 0);
  CHECK(backward_error(A2, X2, B2) > 0);
}

TEST_CASE("symmetry_defect: zero for a symmetric matrix, the relative asymmetry otherwise", "[solvers]") {
  const Eigen::SparseMatrix<double> S = sparse_of((Eigen::MatrixXd(2, 2) << 4, -1, -1, 4).finished());
  const Eigen::SparseMatrix<double> N = sparse_of((Eigen::MatrixXd(2, 2) << 4, -1, -0.5, 4).finished());
  CHECK(symmetry_defect(S) == 0);
  CHECK(symmetry_defect(N) == Approx(0.5 / 1).epsilon(0));  // |−1 − (−0.5)| / max(1, 0.5)
}

TEST_CASE("symmetry_defect: an asymmetric pair counts however large the other entries are", "[solvers]") {
  // A(2,3) = 1, A(3,2) = 0 beside A(1,1) = 1e15: measured against max |A| this passed as rounding
  // (1e-15), and the Cholesky-type backends of bench-matrix solved A's lower triangle instead.
  Eigen::MatrixXd hidden = Eigen::MatrixXd::Zero(3, 3);
  hidden << 1e15, 0, 0, 0, 1, 1, 0, 0, 1;
  CHECK(symmetry_defect(sparse_of(hidden)) == 1);
  CHECK(symmetry_defect(sparse_of(hidden.transpose())) == 1);
  Eigen::MatrixXd wide(2, 2);
  wide << 1e-300, 1, 0, 1e300;
  CHECK(symmetry_defect(sparse_of(wide)) == 1);
  // a pair that differs in its last digits (values written with 16 significant digits) is rounding
  Eigen::MatrixXd rounded(2, 2);
  rounded << 1e15, 0.1, std::nextafter(0.1, 1.0), 1;
  CHECK(symmetry_defect(sparse_of(rounded)) < kSymmetryDefectLimit);
  CHECK(symmetry_defect(sparse_of(rounded)) > 0);
}

TEST_CASE("run_general_system: every backend either measures its solution or says why not", "[solvers]") {
  const Eigen::SparseMatrix<double> A = random_nonsymmetric(40, 5);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(40, 4);  // two blocks: 3 + 1 columns
  const GeneralSystem system = system_of(A, B, symmetry_defect(A) <= kSymmetryDefectLimit);
  REQUIRE_FALSE(system.symmetric);
  SolverOptions options;
  options.tolerance = 1e-10;
  int solved = 0, skipped = 0;
  for (const SolverInfo& info : available_solvers()) {
    const GeneralRun run = run_general_system(info, system, options);
    INFO(info.name << ": " << run.status_name() << " " << run.reason);
    CHECK(run.solver == info.name);
    if (run.skipped) {
      ++skipped;
      CHECK_FALSE(run.reason.empty());
      CHECK_FALSE(run.analyze_seconds.has_value());
      CHECK_FALSE(run.backward_error.has_value());
      // the symmetric-only backends and the grid-only ones, nothing else
      CHECK((info.definite_only || !info.needs_matrix));
      if (info.definite_only) CHECK(run.reason.find("not symmetric") != std::string::npos);
      continue;
    }
    REQUIRE(run.ok());
    ++solved;
    REQUIRE(run.backward_error.has_value());
    REQUIRE(run.relative_residual.has_value());
    REQUIRE(run.solve_seconds.has_value());
    CHECK(*run.relative_residual < (info.family == SolverFamily::kDirect ? 1e-13 : 1e-9));
    CHECK(*run.backward_error < (info.family == SolverFamily::kDirect ? 1e-14 : 1e-9));
    if (info.family == SolverFamily::kDirect) CHECK(run.factor_nnz.value_or(0) >= A.rows());
  }
  CHECK(solved >= 3);  // eigen-lu, bicgstab, gmres at least
  CHECK(skipped >= 4);
}

TEST_CASE("run_general_system: every direct factor counts at least one entry per row, 1 by 1 and diagonal included",
          "[solvers]") {
  // LDLT keeps the unit diagonal of L implicit and D apart: counting only L's stored entries gave
  // 0 (printed null) on a 1 by 1 or diagonal matrix.
  for (const Eigen::Index n : {1, 5}) {
    const Eigen::SparseMatrix<double> A = sparse_of(Eigen::VectorXd::LinSpaced(n, 2, 3).asDiagonal());
    const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(n, 1);
    const GeneralSystem system = system_of(A, B, true);
    int direct = 0;
    for (const SolverInfo& info : available_solvers()) {
      if (info.family != SolverFamily::kDirect || !info.needs_matrix) continue;
      const GeneralRun run = run_general_system(info, system, SolverOptions{});
      INFO(n << " " << info.name << ": " << run.status_name() << " " << run.reason);
      REQUIRE(run.ok());
      ++direct;
      CHECK(run.factor_nnz.value_or(0) >= n);
    }
    CHECK(direct >= 3);  // eigen-lu, eigen-ldlt, eigen-llt at least
  }
}

TEST_CASE("balancing_exponent: centres the extreme magnitudes of A, and leaves ordinary matrices alone", "[solvers]") {
  auto diagonal = [](std::initializer_list<double> d) {
    Eigen::VectorXd v(Eigen::Index(d.size()));
    Eigen::Index k = 0;
    for (double x : d) v(k++) = x;
    return sparse_of(v.asDiagonal());
  };
  CHECK(balancing_exponent(diagonal({1e-30, 1e30})) == 0);  // 2^-100 ≈ 7.9e-31: inside
  CHECK(balancing_exponent(diagonal({3, -7})) == 0);
  CHECK(balancing_exponent(Eigen::SparseMatrix<double>(3, 3)) == 0);
  CHECK(balancing_exponent(diagonal({std::ldexp(1.0, -700), std::ldexp(1.0, -700)})) == 700);
  CHECK(balancing_exponent(diagonal({std::ldexp(1.0, 600), std::ldexp(1.0, 400)})) == -500);
  CHECK(balancing_exponent(diagonal({1e-310, 1e-310})) == 1030);  // subnormal: ilogb is -1030
  CHECK(balancing_exponent(diagonal({1e300, 1e-10})) == -481);    // 2^996 and 2^-34 become 2^515 and 2^-515
}

TEST_CASE("balancing_exponent: the largest entry stays finite when the magnitudes span more than the doubles",
          "[solvers]") {
  // diag(1e-320, 1e300): centring would scale by 2^34 and make 1e300 infinite, and every backend
  // then failed with a made-up reason (singular, underflow, overflow)
  const Eigen::SparseMatrix<double> A = sparse_of(Eigen::Vector2d(1e-320, 1e300).asDiagonal());
  CHECK(balancing_exponent(A) == 1015 - std::ilogb(1e300));
  // a largest entry already above 2^1016 is not scaled down when centring asks for up: the
  // smallest would go (5e-324 to 0, "row 0 is empty")
  CHECK(balancing_exponent(sparse_of(Eigen::Vector2d(5e-324, 1.7e308).asDiagonal())) == 0);
  CHECK(balancing_exponent(sparse_of(Eigen::Vector2d(1e-10, 1.7e308).asDiagonal())) < 0);  // down, as before
  const Eigen::MatrixXd B = Eigen::Vector2d(1e-320, 1e300);  // A·1 (the system keeps a pointer to it)
  const GeneralSystem system = system_of(A, B, true);
  for (const char* name : {"eigen-lu", "umfpack"}) {
    const GeneralRun run = run_general_system(coons::test::backend(name), system, SolverOptions{});
    INFO(name << ": " << run.status_name() << " " << run.reason);
    CHECK(run.ok());
    REQUIRE(run.relative_residual.has_value());
    CHECK(*run.relative_residual <= 1e-15);
    // x1 is lost to the column's scaling (b1 / ‖b‖ = 1e-620): said, not hidden
    CHECK_THAT(run.reason, Catch::Contains("componentwise backward error"));
  }
}

TEST_CASE("run_general_system: scaled identities of condition 1 are solved by every backend that applies",
          "[solvers]") {
  // 1e-200·I stopped gmres's incomplete LU ("singular": its row norms underflow) and 1e-310·I
  // every direct backend ("overflow"); balanced by 2^exponent they are the identity's system
  for (const double scale : {1e-310, 1e-200, 1e200, 1e300}) {
    const Eigen::SparseMatrix<double> A = sparse_of(Eigen::MatrixXd::Identity(6, 6) * scale);
    const Eigen::MatrixXd B = Eigen::VectorXd::LinSpaced(6, 1, 6) * scale;
    const GeneralSystem system = system_of(A, B, true);
    CHECK(system.exponent != 0);
    int solved = 0;
    for (const SolverInfo& info : available_solvers()) {
      const GeneralRun run = run_general_system(info, system, SolverOptions{});
      INFO(scale << " " << info.name << ": " << run.status_name() << " " << run.reason);
      CHECK(run.exponent == system.exponent);  // skipped rows too
      if (run.skipped) continue;
      REQUIRE(run.ok());
      ++solved;
      REQUIRE(run.backward_error.has_value());
      CHECK(*run.backward_error <= 1e-15);
    }
    CHECK(solved >= 8);
  }
}

TEST_CASE("run_general_system: a singular matrix fails with its status and no numbers", "[solvers]") {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(4, 4);
  dense(2, 2) = 0;  // a zero row and column
  const Eigen::SparseMatrix<double> A = sparse_of(dense);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(4, 1);
  const GeneralSystem system = system_of(A, B, true);
  const GeneralRun run = run_general_system(coons::test::backend("eigen-lu"), system, SolverOptions{});
  CHECK_FALSE(run.ok());
  CHECK_FALSE(run.skipped);
  CHECK(run.status_name() != "success");
  CHECK_FALSE(run.reason.empty());
  CHECK_FALSE(run.relative_residual.has_value());
  CHECK_FALSE(run.backward_error.has_value());
}

TEST_CASE("run_general_system: an ill-conditioned system solved backward stably is a success, a singular one is not",
          "[solvers]") {
  // The 10 × 10 Hilbert matrix, κ∞ = 3.5e13 < 1/ε, with b = e₁₀: no double x has a relative
  // residual below 9.6e−6 (the exact x, up to 3.9e11, rounded), above the exact backends' 1e−6.
  // Every exact backend used to call it "numerically singular".
  Eigen::MatrixXd hilbert(10, 10);
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) hilbert(i, j) = 1.0 / (i + j + 1);
  // Rank 2 of 3, its entries rounded (0.1 … 0.9): a pivot of rounding, κ beyond 1/ε.
  Eigen::MatrixXd rank_two(3, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rank_two(i, j) = (3 * i + j + 1) * 0.1;
  const Eigen::SparseMatrix<double> H = sparse_of(hilbert), S = sparse_of(rank_two);
  Eigen::MatrixXd e10 = Eigen::MatrixXd::Zero(10, 1), e1 = Eigen::MatrixXd::Zero(3, 1);
  e10(9) = 1;
  e1(0) = 1;
  for (const char* name : {"eigen-lu", "umfpack", "eigen-ldlt", "cholmod"}) {  // (SuiteSparse is required)
    const SolverInfo* info = find_solver(name);
    REQUIRE(info);
    const GeneralRun ill = run_general_system(*info, system_of(H, e10, true), SolverOptions{});
    INFO(name << ": " << ill.status_name() << ", " << ill.reason);
    CHECK(ill.ok());
    REQUIRE(ill.relative_residual.has_value());
    CHECK(*ill.relative_residual > 1e-6);  // above the limit, and still the best doubles allow
    CHECK(*ill.backward_error < 1e-15);
    CHECK_THAT(ill.reason, Catch::StartsWith("ill-conditioned: relative residual"));
    CHECK_THAT(ill.reason, Catch::Contains("condition estimate 3.5"));  // κ∞ = 3.54e13
    if (std::string(name) == "eigen-lu" || std::string(name) == "umfpack") {
      const GeneralRun singular = run_general_system(*info, system_of(S, e1, false), SolverOptions{});
      INFO(singular.reason);
      CHECK(singular.status == SolveStatus::kSingular);
      CHECK_THAT(singular.reason, Catch::Contains("(at least 1/(10 eps))"));
    }
  }
}

TEST_CASE("run_general_system: a singular matrix whose null vector the condition probes miss is not solved",
          "[solvers]") {
  // A = S·L·S, L the Neumann Laplacian of a 10 × 10 grid (A·s = 0) and S = diag(s) with signs s
  // orthogonal to the three ±1 patterns of the condition probes (each pattern is constant on the
  // classes of i mod 10, and s alternates within every class). With b = e₁ (sᵀb ≠ 0) no x solves
  // it; eigen-lu and umfpack returned X of about 1e15 with relative residual 0.54 and normwise
  // backward error 2e-16, and the probed condition estimate 41 turned `singular` into `success`.
  const int k = 10, n = k * k;
  Eigen::VectorXd s(n);
  std::array<int, 4> count{};
  for (int i = 0; i < n; ++i) {
    const int cls = 2 * (i % 2) + ((i * 7 + 3) % 5 < 2 ? 1 : 0);  // the probes' sign classes
    s(i) = count[std::size_t(cls)]++ % 2 == 0 ? 1 : -1;
  }
  for (const Eigen::VectorXd& probe :
       {Eigen::VectorXd(Eigen::VectorXd::Ones(n)),
        Eigen::VectorXd(Eigen::VectorXd::NullaryExpr(n, [](Eigen::Index i) { return i % 2 == 0 ? 1.0 : -1.0; })),
        Eigen::VectorXd(
            Eigen::VectorXd::NullaryExpr(n, [](Eigen::Index i) { return (i * 7 + 3) % 5 < 2 ? -1.0 : 1.0; }))})
    REQUIRE(s.dot(probe) == 0);
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b)
      for (const auto& [da, db] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        if (a + da < 0 || a + da >= k || b + db < 0 || b + db >= k) continue;
        L(a * k + b, (a + da) * k + b + db) = -1;
        L(a * k + b, a * k + b) += 1;
      }
  const Eigen::MatrixXd A = s.asDiagonal() * L * s.asDiagonal();
  REQUIRE((A * s).norm() == 0);
  Eigen::MatrixXd e1 = Eigen::MatrixXd::Zero(n, 1);
  e1(0) = 1;
  for (const char* name : {"eigen-lu", "umfpack"}) {
    const GeneralRun run =
        run_general_system(coons::test::backend(name), system_of(sparse_of(A), e1, false), SolverOptions{});
    INFO(name << ": " << run.status_name() << ", " << run.reason);
    CHECK(run.status == SolveStatus::kSingular);
    CHECK_THAT(run.reason, Catch::Contains("(at least 1/(10 eps))"));
  }
}

TEST_CASE("run_general_system: balancing never scales B, which may lie far from A's range", "[solvers]") {
  // A = diag(1, 2^-1000) gives k = 500: 2^k B would overflow in its first entry (2^1100), though
  // X = (2^600, 2^1000) is finite; A = diag(2^1000, 1) gives k = -500: 2^k B would make its second
  // entry subnormal and lose digits
  struct Case {
    double a0, a1, b0, b1;
  };
  for (const Case& c : {Case{1, std::ldexp(1.0, -1000), std::ldexp(1.0, 600), 1},
                        Case{std::ldexp(1.0, 1000), 1, 1, 1.23 * std::ldexp(1.0, -560)}}) {
    const Eigen::SparseMatrix<double> A = sparse_of(Eigen::Vector2d(c.a0, c.a1).asDiagonal());
    const Eigen::MatrixXd B = Eigen::Vector2d(c.b0, c.b1);
    const GeneralSystem system = system_of(A, B, true);
    REQUIRE(std::abs(system.exponent) == 500);
    for (const char* name : {"eigen-lu", "umfpack", "cholmod"}) {
      const SolverInfo* info = find_solver(name);
      REQUIRE(info != nullptr);
      const GeneralRun run = run_general_system(*info, system, SolverOptions{});
      INFO(name << ": " << run.status_name() << " " << run.reason);
      REQUIRE(run.ok());
      CHECK(*run.backward_error == 0);
    }
  }
}

TEST_CASE("run_general_system: eigen-lu calls a zero pivot singular, not structurally singular", "[solvers]") {
  // [[1, 1], [1, 1]]: its pattern is regular, its values are not; Eigen's own text said
  // "THE MATRIX IS STRUCTURALLY SINGULAR ... ZERO COLUMN AT 2"
  const Eigen::SparseMatrix<double> A = sparse_of(Eigen::MatrixXd::Ones(2, 2));
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(2, 1);
  const GeneralSystem system = system_of(A, B, true);
  const GeneralRun run = run_general_system(coons::test::backend("eigen-lu"), system, SolverOptions{});
  CHECK(run.status == SolveStatus::kSingular);
  CHECK(run.reason ==
        "SparseLU: a zero pivot at elimination step 2 (of the column-permuted matrix): singular, in its "
        "values or in its pattern");
}

TEST_CASE("run_general_system: a solution beyond the doubles above or below is a failure with its reason",
          "[solvers]") {
  // 1e30 x = 1e-300 (x = 1e-330 is 0 in doubles) gave success with a relative residual of 1;
  // 1e300 x = 1e-20 (balanced; x = 1e-320 is subnormal) success with 1.1e-5; 1e-300 x = 1e10
  // (balanced; x = 1e310 overflows) success with no numbers at all.
  struct Case {
    double a, b;
    const char* reason;
  };
  for (const Case& c :
       {Case{1e30, 1e-300, "underflow"}, Case{1e300, 1e-20, "underflow"}, Case{1e-300, 1e10, "overflow"}}) {
    const Eigen::SparseMatrix<double> A = sparse_of(Eigen::MatrixXd::Constant(1, 1, c.a));
    const Eigen::MatrixXd B = Eigen::MatrixXd::Constant(1, 1, c.b);
    const GeneralSystem system = system_of(A, B, true);
    int failed = 0;
    for (const SolverInfo& info : available_solvers()) {
      const GeneralRun run = run_general_system(info, system, SolverOptions{});
      INFO(c.a << " x = " << c.b << ", " << info.name << ": " << run.status_name() << " " << run.reason);
      if (run.skipped) continue;
      CHECK_FALSE(run.ok());
      CHECK(run.reason.find(c.reason) != std::string::npos);
      if (run.relative_residual) CHECK(*run.relative_residual > 1e-6);
      ++failed;
    }
    CHECK(failed >= 8);
  }
}

TEST_CASE("run_general_system: a column holding 1e-200 and 1e200 keeps both", "[solvers]") {
  // The common solve path scaled the column to a largest magnitude in [1/2, 1), which took 1e-200
  // below the doubles: every backend solved I x = (1e-200, 1e200) as x = (0, 1e200), "success" with
  // a backward error of 1. A Krylov method that normalises its vectors (gmres) still loses it
  // inside, and says so in its note.
  const Eigen::SparseMatrix<double> A = sparse_of(Eigen::MatrixXd::Identity(2, 2));
  const Eigen::MatrixXd B = Eigen::Vector2d(1e-200, 1e200);
  const GeneralSystem system = system_of(A, B, true);
  int exact = 0;
  for (const SolverInfo& info : available_solvers()) {
    const GeneralRun run = run_general_system(info, system, SolverOptions{});
    INFO(info.name << ": " << run.status_name() << " " << run.reason);
    if (run.skipped || !run.ok()) continue;
    REQUIRE(run.backward_error);
    if (*run.backward_error <= 1e-15)
      ++exact;
    else
      CHECK(run.reason.find("small entries of X may be wrong") != std::string::npos);
  }
  CHECK(exact >= 8);
}

TEST_CASE("relative_residual: b is not lost to cancellation in b - A x", "[solvers]") {
  // [[1, 1], [1, 1]] x = (1, 2) has no solution; CG's iterate x = (-c, c), c = 2^105, has A x = 0,
  // so the residual is b itself. Formed as b, then minus x_j times column j, it was (1 + c) - c = 0.
  const Eigen::SparseMatrix<double> A = sparse_of(Eigen::MatrixXd::Ones(2, 2));
  const Eigen::MatrixXd B = Eigen::Vector2d(1, 2);
  const double c = std::ldexp(1.0, 105);
  const Eigen::MatrixXd X = Eigen::Vector2d(-c, c);
  CHECK(relative_residual(A, X, B) == 1);
  CHECK(backward_error(A, X, B) == Approx(2 / (2 * c + 2)).epsilon(1e-12));
}

TEST_CASE(
    "run_general_system: a pivot is small against its own diagonal entry so a scaled regular matrix is not singular",
    "[solvers]") {
  // diag(1, 1e-20) and a grid Laplacian scaled by 10^(-8..8) row and column (D L D) were called
  // singular by eigen-ldlt, eigen-llt and cholmod-simplicial: a pivot below 1e-13 of the largest
  // one counted as zero. [[1, 1], [1, 1 + 1e-15]] is singular whatever the scaling.
  const int k = 8, n = k * k;
  std::vector<Eigen::Triplet<double>> t;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-8, 8);
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d(i) = std::pow(10.0, u(rng));
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      const int p = i * k + j;
      t.emplace_back(p, p, 4 * d(p) * d(p));
      if (i > 0) t.emplace_back(p, p - k, -d(p) * d(p - k));
      if (i + 1 < k) t.emplace_back(p, p + k, -d(p) * d(p + k));
      if (j > 0) t.emplace_back(p, p - 1, -d(p) * d(p - 1));
      if (j + 1 < k) t.emplace_back(p, p + 1, -d(p) * d(p + 1));
    }
  Eigen::SparseMatrix<double> dld(n, n);
  dld.setFromTriplets(t.begin(), t.end());
  const Eigen::SparseMatrix<double> diagonal = sparse_of(Eigen::Vector2d(1, 1e-20).asDiagonal());
  for (const Eigen::SparseMatrix<double>* A : std::array<const Eigen::SparseMatrix<double>*, 2>{&diagonal, &dld}) {
    const Eigen::MatrixXd B = *A * Eigen::VectorXd::Ones(A->rows());
    const GeneralSystem system = system_of(*A, B, true);
    for (const char* name : {"eigen-ldlt", "eigen-llt", "cholmod-simplicial", "cholmod"}) {
      const SolverInfo* info = find_solver(name);
      if (info == nullptr) continue;  // (a build without SuiteSparse)
      const GeneralRun run = run_general_system(*info, system, SolverOptions{});
      INFO(A->rows() << " rows, " << name << ": " << run.status_name() << " " << run.reason);
      REQUIRE(run.ok());
      // exact for the diagonal; for D L D, Cholesky's componentwise error is bounded by |Lᵀ||L|, not |A|
      CHECK(*run.backward_error < (A->rows() == 2 ? 1e-15 : 1e-8));
    }
  }
  // [[1, 1], [1, 1 + 1e-15]]: the second pivot is 1e-15 of its diagonal entry
  const Eigen::SparseMatrix<double> ones = sparse_of((Eigen::MatrixXd(2, 2) << 1, 1, 1, 1 + 1e-15).finished());
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(2, 1);
  for (const char* name : {"eigen-ldlt", "cholmod-simplicial"}) {
    const SolverInfo* info = find_solver(name);
    if (info == nullptr) continue;
    const GeneralRun run = run_general_system(*info, system_of(ones, b, true), SolverOptions{});
    INFO(name << ": " << run.reason);
    CHECK(run.status == SolveStatus::kSingular);
  }
}

TEST_CASE("run_general_system: a near-zero pivot among negative ones is indefinite, not singular", "[solvers]") {
  // [[1, 1, 0], [1, 1 + 1e-15, 1], [0, 1, 1]] is regular (det ≈ −1) and indefinite: LDLᵀ without
  // pivoting meets the pivot 1e-15 and then −1e15. eigen-ldlt called it singular (and a regular
  // 10-unknown 5×5 stencil system too, where eigen-lu solves it to 5e-16).
  const Eigen::SparseMatrix<double> A =
      sparse_of((Eigen::MatrixXd(3, 3) << 1, 1, 0, 1, 1 + 1e-15, 1, 0, 1, 1).finished());
  const Eigen::MatrixXd b = Eigen::MatrixXd::Ones(3, 1);
  for (const char* name : {"eigen-ldlt", "cholmod-simplicial"}) {
    const SolverInfo* info = find_solver(name);
    if (info == nullptr) continue;  // (a build without SuiteSparse)
    const GeneralRun run = run_general_system(*info, system_of(A, b, true), SolverOptions{});
    INFO(name << ": " << run.reason);
    CHECK(run.status == SolveStatus::kNotPositiveDefinite);
    CHECK_THAT(run.reason, Catch::Contains("negative pivot"));
  }
  const GeneralRun lu = run_general_system(*find_solver("eigen-lu"), system_of(A, b, true), SolverOptions{});
  CHECK(lu.ok());
}

TEST_CASE("run_general_system: a Cholesky-type backend stopped at a pivot tells singular from indefinite",
          "[solvers]") {
  // [[1, 2], [2, 4]] and the Neumann Laplacian of a path (scaled row by row: D A D) are positive
  // semidefinite and singular; [[0, 1], [1, 0]] and [[1, 2], [2, 3.9]] are regular and indefinite,
  // and so are [[1, 1], [1, 1 − 1e-11]] (eigenvalue −5e-12) and a 3×3 whose LDLᵀ meets an exact
  // zero pivot (eigenvalue −5e-13), which A + 1e-10·diag(A) alone called singular (review of
  // 2026-12-04), and one whose LDLᵀ pivot −2e-15 counts as zero (eigenvalue −8e-12). Each factorisation stops (at a
  // pivot 0, or below 0) or meets a negative pivot; all of them were "not positive definite", the singular ones
  // included.
  constexpr int kPath = 40;
  Eigen::MatrixXd neumann = Eigen::MatrixXd::Zero(kPath, kPath);
  for (int k = 0; k + 1 < kPath; ++k) {  // the edge (k, k + 1), its ends weighted 10^±3
    const double wk = std::pow(10.0, 3 * ((k % 3) - 1)), wl = std::pow(10.0, 3 * (((k + 1) % 3) - 1));
    neumann(k, k) += wk * wk;
    neumann(k + 1, k + 1) += wl * wl;
    neumann(k, k + 1) -= wk * wl;
    neumann(k + 1, k) -= wk * wl;
  }
  // A 15 × 15 Neumann grid Laplacian, edge weights in [0.1, 10], scaled D A D by 10^{−8, −4, 0, 4, 8}:
  // cholmod's supernodal LLᵀ goes through it and, b being consistent, called it solved (second
  // review of 2026-12-04)
  constexpr int kGrid = 15;
  Eigen::MatrixXd grid = Eigen::MatrixXd::Zero(kGrid * kGrid, kGrid * kGrid);
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j)
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}}) {
        if (i + di >= kGrid || j + dj >= kGrid) continue;
        const int a = i * kGrid + j, b = (i + di) * kGrid + j + dj;
        const double w = 0.1 + 9.9 * double((7 * a + 3 * b) % 11) / 10;
        grid(a, a) += w;
        grid(b, b) += w;
        grid(a, b) -= w;
        grid(b, a) -= w;
      }
  Eigen::VectorXd scale(kGrid * kGrid);
  for (int k = 0; k < kGrid * kGrid; ++k) scale(k) = std::pow(10.0, 4 * ((k * 7) % 5 - 2));
  grid = scale.asDiagonal() * grid * scale.asDiagonal();
  const std::vector<std::pair<Eigen::MatrixXd, SolveStatus>> cases = {
      {(Eigen::MatrixXd(2, 2) << 1, 2, 2, 4).finished(), SolveStatus::kSingular},
      {neumann, SolveStatus::kSingular},
      {grid, SolveStatus::kSingular},
      {(Eigen::MatrixXd(2, 2) << 0, 1, 1, 0).finished(), SolveStatus::kNotPositiveDefinite},
      {(Eigen::MatrixXd(2, 2) << 1, 2, 2, 3.9).finished(), SolveStatus::kNotPositiveDefinite},
      {(Eigen::MatrixXd(2, 2) << 1, 1, 1, 1 - 1e-11).finished(), SolveStatus::kNotPositiveDefinite},
      {(Eigen::MatrixXd(3, 3) << 1, 1, 0, 1, 1, 1e-6, 0, 1e-6, 1).finished(), SolveStatus::kNotPositiveDefinite},
      // eigenvalue −8e-12: the LDLᵀ pivot −2e-15 counts as zero and none is negative, which was
      // `singular` straight away (second review of 2026-12-04)
      {(Eigen::MatrixXd(3, 3) << 1, 1, 2e-6, 1, 1 - 2e-15, -2e-6, 2e-6, -2e-6, 1).finished(),
       SolveStatus::kNotPositiveDefinite}};
  for (const auto& [dense, expected] : cases) {
    // consistent: b in A's range, so no residual gives a singular matrix away
    const Eigen::MatrixXd b = dense * Eigen::VectorXd::LinSpaced(dense.rows(), 1, 2);
    for (const char* name : {"eigen-ldlt", "eigen-llt", "cholmod", "cholmod-simplicial"}) {
      const SolverInfo* info = find_solver(name);
      if (info == nullptr) continue;  // (a build without SuiteSparse)
      const GeneralRun run = run_general_system(*info, system_of(sparse_of(dense), b, true), SolverOptions{});
      INFO(dense.rows() << " rows, " << name << ": " << run.status_name() << " " << run.reason);
      CHECK(run.status == expected);
      CHECK_FALSE(run.backward_error.has_value());
    }
  }
}

TEST_CASE("run_general_system: a success with a large componentwise backward error carries a note", "[solvers]") {
  // cg on diag(1, 1e-20): x2 = 1e-20 for 1 meets the normwise target (residual 1e-20) with a
  // componentwise backward error of 1, and said only "success"
  const Eigen::SparseMatrix<double> A = sparse_of(Eigen::Vector2d(1, 1e-20).asDiagonal());
  const Eigen::MatrixXd B = A * Eigen::VectorXd::Ones(2);
  const GeneralRun cg = run_general_system(coons::test::backend("cg"), system_of(A, B, true), SolverOptions{});
  INFO(cg.status_name() << " " << cg.reason);
  REQUIRE(cg.ok());
  REQUIRE(*cg.backward_error >= kNotedBackwardError);
  CHECK(cg.reason.find("componentwise backward error") != std::string::npos);
  const GeneralRun lu = run_general_system(coons::test::backend("eigen-lu"), system_of(A, B, true), SolverOptions{});
  REQUIRE(lu.ok());
  CHECK(*lu.backward_error < kNotedBackwardError);
  CHECK(lu.reason.empty());  // an accurate success carries none
}

TEST_CASE("Krylov backends: a zero right-hand-side column adds no iterations", "[solvers]") {
  // A symmetric positive definite matrix: the nonsymmetric one plus its transpose, shifted.
  const Eigen::SparseMatrix<double> N = random_nonsymmetric(60, 9);
  Eigen::SparseMatrix<double> A = Eigen::SparseMatrix<double>(N.transpose()) + N;
  for (int i = 0; i < 60; ++i) A.coeffRef(i, i) += 4;
  LinearOperator op;
  op.matrix = &A;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(60, -1, 2);
  Eigen::MatrixX3d padded = Eigen::MatrixX3d::Zero(60, 3), full(60, 3);
  padded.col(0) = b;
  full << b, b, b;
  for (const char* name : {"cg", "cg-jacobi", "cg-ic", "bicgstab", "gmres"}) {
    INFO(name);
    Eigen::MatrixX3d X;
    const SolveSummary with_zeros = make_solver(name)->compute_and_solve(op, padded, X);
    REQUIRE(with_zeros.ok());
    CHECK(X.rightCols(2).cwiseAbs().maxCoeff() == 0);
    const SolveSummary without = make_solver(name)->compute_and_solve(op, full, X);
    CHECK(with_zeros.iterations == without.iterations);
    CHECK(with_zeros.iterations < 100);
  }
}
