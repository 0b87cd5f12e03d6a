// The separable banded solver (A = P ⊗ Q, pentadiagonal Toeplitz factors) against the sparse
// direct solve of the assembled operator, and its statuses.
#include "solvers/separable_banded_solver.h"

#include <Eigen/SparseLU>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "solvers/separable_outer_products.h"
#include "support/scaling_checks.h"

using namespace coons::solvers;

namespace {

Eigen::MatrixX3d random_rhs(Eigen::Index rows, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixX3d B(rows, 3);
  for (Eigen::Index k = 0; k < B.size(); ++k) B.data()[k] = u(rng);
  return B;
}

double relative_error(const Eigen::MatrixX3d& X, const Eigen::MatrixX3d& ref) { return (X - ref).norm() / ref.norm(); }

}  // namespace

TEST_CASE("separable_banded_matrix: entry (i,j),(k,l) is p_|i-k| q_|j-l|", "[solvers]") {
  const SeparableBandedOperator op{4, 6, {6, -4, 1}, {2, -1, 0}};
  const Eigen::MatrixXd A(separable_banded_matrix(op));
  const Eigen::MatrixXd P = (Eigen::MatrixXd(4, 4) << 6, -4, 1, 0, -4, 6, -4, 1, 1, -4, 6, -4, 0, 1, -4, 6).finished();
  Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(6, 6);
  for (int k = 0; k < 6; ++k) {
    Q(k, k) = 2;
    if (k + 1 < 6) Q(k, k + 1) = Q(k + 1, k) = -1;
  }
  Eigen::MatrixXd K(24, 24);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) K.block(i * 6, k * 6, 6, 6) = P(i, k) * Q;
  CHECK((A - K).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("separable_banded_solve: equals the sparse direct solve on several sizes", "[solvers]") {
  // B = A X* for a random X*: every mode is excited, so both solvers lose about κ·ε, with
  // κ ≈ (16/(π/(k+1))⁴)² for the fourth difference ⊗ itself (7e10 at 30 × 41, 1e-5 errors at
  // 120 × 100 for both). The separable solve must be as accurate as the sparse LU, and equal it
  // to 1e-10 wherever the LU is accurate to 1e-11.
  std::uint32_t seed = 1;
  const std::array<double, 3> fourth{6, -4, 1}, second{2, -1, 0}, dominant{7.5, -2, 0.5}, indefinite{-3, 1, 0.25};
  for (auto [rows, cols] : {std::pair{1, 1}, {2, 3}, {5, 7}, {17, 4}, {30, 41}, {64, 9}, {120, 100}, {13, 300}}) {
    for (const auto& [p, q] :
         {std::pair{fourth, fourth}, {fourth, second}, {dominant, fourth}, {indefinite, dominant}}) {
      INFO(rows << " x " << cols << ", p = (" << p[0] << ", " << p[1] << ", " << p[2] << ")");
      const SeparableBandedOperator op{rows, cols, p, q};
      const Eigen::SparseMatrix<double> A = separable_banded_matrix(op);
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
      REQUIRE(lu.info() == Eigen::Success);
      const Eigen::MatrixX3d Xstar = random_rhs(op.size(), seed++);
      Eigen::MatrixX3d B = A * Xstar, X;
      REQUIRE(separable_banded_solve(op, B, X) == SolveStatus::kSuccess);
      const double err = relative_error(X, Xstar), err_lu = relative_error(Eigen::MatrixX3d(lu.solve(B)), Xstar);
      CHECK(err <= 2 * err_lu + 1e-13);
      // the two agree to 1e-10 where the reference itself is that accurate, else within their errors
      const double diff = relative_error(X, Eigen::MatrixX3d(lu.solve(B)));
      CHECK(diff <= std::max(1e-10, 3 * (err + err_lu)));
      if (err_lu < 1e-11) CHECK(diff < 1e-10);
    }
  }
}

TEST_CASE("separable_banded_solve: the same solution bit for bit on 1, 2 and 3 threads", "[solvers]") {
  // blocks of rows along j and strips of columns along i, shared among threads: a partial last
  // block (rows 37) and a partial last strip (cols 300) included
  const SeparableBandedOperator op{37, 300, {6, -4, 1}, {7.5, -2, 0.5}};
  const Eigen::MatrixX3d B = random_rhs(op.size(), 3);
  Eigen::MatrixX3d X1, X2, X3;
  REQUIRE(separable_banded_solve(op, B, X1, 1) == SolveStatus::kSuccess);
  REQUIRE(separable_banded_solve(op, B, X2, 2) == SolveStatus::kSuccess);
  REQUIRE(separable_banded_solve(op, B, X3, 3) == SolveStatus::kSuccess);
  CHECK((separable_banded_matrix(op) * X1 - B).norm() / B.norm() < 1e-12);
  CHECK((X1 - X2).cwiseAbs().maxCoeff() == 0);
  CHECK((X1 - X3).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("make_separable_banded_solver: the LinearSolver life cycle with its statuses", "[solvers]") {
  const SeparableBandedOperator op{12, 15, {6, -4, 1}, {6, -4, 1}};
  const Eigen::SparseMatrix<double> A = separable_banded_matrix(op);
  auto solver = make_separable_banded_solver(op);
  CHECK(solver->name() == "separable-banded");
  LinearOperator lin;
  lin.matrix = &A;
  const Eigen::MatrixX3d B = random_rhs(op.size(), 9);
  Eigen::MatrixX3d X;
  const SolveSummary s = solver->compute_and_solve(lin, B, X);
  REQUIRE(s.ok());
  CHECK(s.relative_residual < 1e-9);
  CHECK(s.iterations == 1);
  // a second right-hand side reuses the factors
  const Eigen::MatrixX3d B2 = random_rhs(op.size(), 10);
  CHECK(solver->solve(B2, X).ok());
  CHECK((A * X - B2).norm() / B2.norm() < 1e-9);
  // an operator of another size does not apply
  const Eigen::SparseMatrix<double> small = separable_banded_matrix({3, 3, {6, -4, 1}, {6, -4, 1}});
  lin.matrix = &small;
  CHECK(solver->analyze(lin) == SolveStatus::kNotApplicable);
  // a singular factor: toeplitz(1, 1, 0) of size 2 is [[1, 1], [1, 1]]
  Eigen::MatrixX3d Y;
  CHECK(separable_banded_solve({2, 3, {1, 1, 0}, {6, -4, 1}}, random_rhs(6, 1), Y) == SolveStatus::kSingular);
  const SeparableBandedOperator bad{2, 3, {1, 1, 0}, {6, -4, 1}};
  const Eigen::SparseMatrix<double> Abad = separable_banded_matrix(bad);
  lin.matrix = &Abad;
  CHECK(make_separable_banded_solver(bad)->compute_and_solve(lin, random_rhs(6, 2), Y).status ==
        SolveStatus::kSingular);
}

TEST_CASE("make_separable_banded_solver: an indefinite factor is refused, not solved inaccurately", "[solvers]") {
  // (1, −2, 1) ⊗ (1, 1 + 1e-11, 1) on 11 × 6: Q = toeplitz(1 + 1e-11, 1) is indefinite and its
  // LDLᵀ without pivoting meets a pivot of about 1e-11 (the solution came out with relative error
  // 1e-6 and the status success); Q = toeplitz(1, 1) meets an exact zero pivot (it was called
  // singular, though A is regular).
  for (const double q0 : {1 + 1e-11, 1.0}) {
    const SeparableBandedOperator op{11, 6, {-2, 1, 0}, {q0, 1, 0}};
    const Eigen::SparseMatrix<double> A = separable_banded_matrix(op);
    LinearOperator lin;
    lin.matrix = &A;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_separable_banded_solver(op)->compute_and_solve(lin, random_rhs(op.size(), 4), X);
    INFO("q0 = " << q0 << ": " << s.brief_report());
    CHECK(s.status == SolveStatus::kNotApplicable);
    CHECK(s.message.find("indefinite") != std::string::npos);
    CHECK(separable_banded_solve(op, random_rhs(op.size(), 4), X) == SolveStatus::kNotApplicable);
    // The operator itself is regular: a pivoting LU solves it.
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
    CHECK(lu.info() == Eigen::Success);
  }
  // Definite factors of either sign are solved: (1, −2, 1) ⊗ (1, −2, 1) is positive definite.
  const SeparableBandedOperator op{11, 6, {-2, 1, 0}, {-2, 1, 0}};
  const Eigen::SparseMatrix<double> A = separable_banded_matrix(op);
  const Eigen::MatrixX3d B = random_rhs(op.size(), 5);
  Eigen::MatrixX3d X;
  REQUIRE(separable_banded_solve(op, B, X) == SolveStatus::kSuccess);
  CHECK((A * X - B).norm() / B.norm() < 1e-13);
}

namespace {

// A right-hand side of the data-ring form: every row zero in columns 2..cols−3, except `full`.
Eigen::MatrixX3d ring_rhs(int rows, int cols, const std::vector<int>& full, std::uint32_t seed) {
  Eigen::MatrixX3d B = random_rhs(Eigen::Index(rows) * cols, seed);
  for (int i = 0; i < rows; ++i) {
    if (std::find(full.begin(), full.end(), i) != full.end()) continue;
    for (int j = 2; j + 2 < cols; ++j) B.row(Eigen::Index(i) * cols + j).setZero();
  }
  return B;
}

}  // namespace

TEST_CASE("solve_outer_products: the data-ring right-hand side equals the sparse direct solve", "[solvers]") {
  // 0 to 8 full rows anywhere (the four next to the frame among them) are outer products; 9 full
  // rows, or fewer than 5 columns, are left to the sweeps, with x untouched
  const std::array<double, 3> fourth{6, -4, 1}, dominant{7.5, -2, 0.5};
  std::uint32_t seed = 11;
  for (auto [rows, cols] : {std::pair{1, 5}, {6, 5}, {9, 12}, {40, 33}, {17, 64}}) {
    const SeparableBandedOperator op{rows, cols, fourth, dominant};
    BandedLdlt fi, fj;
    REQUIRE(banded_ldlt(op.along_i, rows, fi) == SolveStatus::kSuccess);
    REQUIRE(banded_ldlt(op.along_j, cols, fj) == SolveStatus::kSuccess);
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(separable_banded_matrix(op));
    REQUIRE(lu.info() == Eigen::Success);
    std::vector<std::vector<int>> cases{{}, {0, 1, rows - 2, rows - 1}, {rows / 2}};
    std::vector<int> eight, nine;
    for (int i = 0; i < std::min(rows, 9); ++i) (i < 8 ? eight : nine).push_back(i);
    nine.insert(nine.begin(), eight.begin(), eight.end());
    cases.push_back(eight);
    for (std::vector<int>& c : cases)
      c.erase(std::remove_if(c.begin(), c.end(), [&](int i) { return i < 0; }), c.end());
    for (const std::vector<int>& full : cases) {
      INFO(rows << " x " << cols << ", " << full.size() << " full rows");
      const Eigen::MatrixX3d B = ring_rhs(rows, cols, full, seed++);
      const Eigen::MatrixX3d ref = lu.solve(B);
      Eigen::MatrixX3d X(B.rows(), 3);
      for (int c = 0; c < 3; ++c)
        REQUIRE(detail::solve_outer_products(fi, fj, rows, cols, B.col(c).data(), X.col(c).data()));
      CHECK(relative_error(X, ref) < 1e-12);
    }
    if (rows >= 9) {
      const Eigen::MatrixX3d B = ring_rhs(rows, cols, nine, seed++);
      Eigen::VectorXd x = Eigen::VectorXd::Constant(B.rows(), 7.0);
      CHECK_FALSE(detail::solve_outer_products(fi, fj, rows, cols, B.col(0).data(), x.data()));
      CHECK((x.array() == 7.0).all());
    }
  }
  const SeparableBandedOperator narrow{6, 4, fourth, fourth};
  BandedLdlt fi, fj;
  REQUIRE(banded_ldlt(narrow.along_i, 6, fi) == SolveStatus::kSuccess);
  REQUIRE(banded_ldlt(narrow.along_j, 4, fj) == SolveStatus::kSuccess);
  const Eigen::MatrixX3d B = random_rhs(24, 5);
  Eigen::VectorXd x(24);
  CHECK_FALSE(detail::solve_outer_products(fi, fj, 6, 4, B.col(0).data(), x.data()));
}

TEST_CASE("outer_form: the full rows and the largest magnitude of a data-ring column, in one read", "[solvers]") {
  const int rows = 12, cols = 9;
  std::uint32_t seed = 30;
  for (const std::vector<int>& full : {std::vector<int>{}, {0, 1, 10, 11}, {5}})
    // the largest value at a sparse row's end columns (0, 1, 7, 8) or inside a full row
    for (const auto& [i, j] : std::vector<std::pair<int, int>>{{3, 0}, {4, 1}, {6, 7}, {9, 8}, {0, 4}, {5, 3}}) {
      if (j > 1 && j + 2 < cols && std::find(full.begin(), full.end(), i) == full.end()) continue;
      for (const double big : {-9.5, 0x1p700}) {
        Eigen::MatrixX3d B = ring_rhs(rows, cols, full, seed++);
        B(Eigen::Index(i) * cols + j, 1) = big;
        INFO(full.size() << " full rows, (" << i << ", " << j << ") = " << big);
        const auto form = detail::outer_form(B.col(1).data(), rows, cols);
        REQUIRE(form);
        CHECK(form->full_rows == full);
        CHECK(form->largest == B.col(1).cwiseAbs().maxCoeff());
        CHECK(form->largest == std::abs(big));
        B(Eigen::Index(i) * cols + j, 1) = std::numeric_limits<double>::infinity();
        CHECK(std::isnan(detail::outer_form(B.col(1).data(), rows, cols)->largest));
      }
    }
  CHECK_FALSE(detail::outer_form(ring_rhs(rows, cols, {0, 1, 2, 3, 4, 5, 6, 7, 8}, 3).col(0).data(), rows, cols));
  CHECK_FALSE(detail::outer_form(ring_rhs(rows, 4, {}, 3).col(0).data(), rows, 4));
}

TEST_CASE("separable-banded: one solver object scales each right-hand side by its own largest magnitude", "[solvers]") {
  // It takes the scaling of B (solvers/column_scaling.h) from its form check and keeps the forms
  // for the solve: X is that of separable_banded_solve, which checks the forms itself, bit for bit.
  // Scaling by 2^e is exact here, so X(2^e B) = 2^e X(B) bit for bit, with every column of
  // outer-product form and with one to be swept; a NaN fails.
  const SeparableBandedOperator op{14, 11, {6, -4, 1}, {6, -4, 1}};
  const Eigen::SparseMatrix<double> A = separable_banded_matrix(op);
  LinearOperator lin;
  lin.matrix = &A;
  for (const bool swept : {false, true}) {
    Eigen::MatrixX3d B = ring_rhs(op.rows, op.cols, {0, 1, 12, 13}, 40);
    if (swept) B.col(2) = random_rhs(B.rows(), 41).col(0);
    auto solver = make_separable_banded_solver(op, {});
    Eigen::MatrixX3d X;
    REQUIRE(solver->compute_and_solve(lin, B, X).ok());
    Eigen::MatrixX3d Y;
    REQUIRE(separable_banded_solve(op, B, Y) == SolveStatus::kSuccess);
    CHECK((X - Y).cwiseAbs().maxCoeff() == 0);
    INFO((swept ? "a swept column" : "outer products only"));
    coons::test::check_scaled_solves(*solver, B, X, 1e-10, 5, 0);
  }
}

TEST_CASE("separable_banded_solve: columns of both forms in one call, the same bits on 1, 2 and 3 threads",
          "[solvers]") {
  // column 0 of the data-ring form (outer products, in blocks of 64 rows: 150 rows make three,
  // the last partial), columns 1 and 2 general (the sweeps)
  const SeparableBandedOperator op{150, 300, {7.5, -2, 0.5}, {7.5, -2, 0.5}};  // well conditioned: κ < 10
  Eigen::MatrixX3d B = random_rhs(op.size(), 21);
  B.col(0) = ring_rhs(150, 300, {0, 1, 148, 149}, 22).col(0);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(separable_banded_matrix(op));
  REQUIRE(lu.info() == Eigen::Success);
  const Eigen::MatrixX3d ref = lu.solve(B);
  Eigen::MatrixX3d X1, X2, X3;
  REQUIRE(separable_banded_solve(op, B, X1, 1) == SolveStatus::kSuccess);
  REQUIRE(separable_banded_solve(op, B, X2, 2) == SolveStatus::kSuccess);
  REQUIRE(separable_banded_solve(op, B, X3, 3) == SolveStatus::kSuccess);
  for (int c = 0; c < 3; ++c) CHECK((X1.col(c) - ref.col(c)).norm() / ref.col(c).norm() < 1e-12);
  CHECK((X1 - X2).cwiseAbs().maxCoeff() == 0);
  CHECK((X1 - X3).cwiseAbs().maxCoeff() == 0);
}
