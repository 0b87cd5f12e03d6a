// The structured solvers (dst, fast) against a dense LU reference on small grids, on both kinds of
// right-hand side (on the ring next to the frame, as for mask systems, and dense), across α.
#include <catch2/catch.hpp>

#include "coons/config.h"

#if COONS_HAVE_FFTW

#include <fftw3.h>

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "solvers/sine_basis.h"
#include "solvers/sine_transform.h"
#include "solvers/structured_solvers.h"
#include "support/grid_fixtures.h"
#include "support/scaling_checks.h"

using namespace coons::solvers;
using coons::test::alpha_grid_stencil;

namespace {

using Factory = std::function<std::unique_ptr<LinearSolver>(const SolverOptions&)>;

const std::vector<std::pair<const char*, Factory>>& structured() {
  static const std::vector<std::pair<const char*, Factory>> list = {{"dst", make_dst_solver},
                                                                    {"fast", make_fast_solver}};
  return list;
}

// Anisotropic variant (docs/math.md §3): α = −mn/D, β_i = (2mn + μ m/n)/D, β_j = (2mn + μ n/m)/D.
GridStencil anisotropic_stencil(int rows, int cols, double mu) {
  const double m = rows + 1, n = cols + 1, D = 4 * m * n + 2 * mu * (m / n + n / m);
  return {rows, cols, 1.0, -(2 * m * n + mu * m / n) / D, -(2 * m * n + mu * n / m) / D, m * n / D};
}

Eigen::MatrixX3d dense_rhs(const GridStencil& s, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixX3d B(s.size(), 3);
  for (Eigen::Index k = 0; k < B.size(); ++k) B.data()[k] = u(rng);
  return B;
}

// Non-zero only next to the frame: rows 0 and rows−1, columns 0 and cols−1.
Eigen::MatrixX3d ring_rhs(const GridStencil& s, std::uint32_t seed) {
  Eigen::MatrixX3d B = dense_rhs(s, seed);
  for (int i = 0; i < s.rows; ++i)
    for (int j = 0; j < s.cols; ++j)
      if (i > 0 && i + 1 < s.rows && j > 0 && j + 1 < s.cols) B.row(Eigen::Index(i) * s.cols + j).setZero();
  return B;
}

Eigen::MatrixX3d dense_reference(const GridStencil& s, const Eigen::MatrixX3d& B) {
  return Eigen::MatrixXd(stencil_matrix(s)).fullPivLu().solve(Eigen::MatrixXd(B));
}

LinearOperator grid_operator(const GridStencil& s) {
  LinearOperator op;
  op.stencil = s;
  return op;
}

void check_against_reference(const char* name, const Factory& make, const GridStencil& s, const Eigen::MatrixX3d& B) {
  // NOLINTNEXTLINE(performance-unnecessary-copy-initialization): a snapshot of B, to see the solver leave it alone
  const Eigen::MatrixX3d B_copy = B;
  const Eigen::MatrixX3d reference = dense_reference(s, B);
  Eigen::MatrixX3d X;
  const SolveSummary summary = make({})->compute_and_solve(grid_operator(s), B, X);
  INFO(name << ": " << s.rows << "x" << s.cols << ", c = " << s.center << ", e_i = " << s.edge_i
            << ", e_j = " << s.edge_j << ", d = " << s.diag << ": " << summary.brief_report());
  REQUIRE(summary.ok());
  CHECK(summary.iterations == 1);
  CHECK(summary.factor_nnz == 0);
  CHECK(summary.ordering.empty());
  CHECK(summary.solver == name);
  CHECK((X - reference).cwiseAbs().maxCoeff() <= 1e-10 * std::max(1.0, reference.cwiseAbs().maxCoeff()));
  CHECK(summary.relative_residual < 1e-11);
  CHECK(B == B_copy);
}

const std::vector<std::pair<int, int>>& grids() {
  static const std::vector<std::pair<int, int>> list = {
      {1, 1},
      {1, 6},
      {6, 1},
      {2, 2},
      {2, 5},
      {3, 3},
      {4, 7},
      {7, 4},
      {9, 9},
      {12, 17},
      {16, 15},
      // cols + 1 with a prime factor > 13: fast transforms the first L columns, L + 1 fast, and
      // eliminates the k others (capacitance.h): k = 1 (17, 23, 37), 2 (38), 4 (95), 6 (188)
      {7, 16},
      {16, 22},
      {5, 36},
      {1, 16},
      {9, 37},
      {6, 94},
      {3, 187}};
  return list;
}

}  // namespace

TEST_CASE("AlignedBuffer: every buffer starts on a 64-byte cache line", "[solvers]") {
  // fast pads the rows of its back-substitution blocks to multiples of 8 doubles and cuts the
  // modes its threads share at multiples of 8 (fast_solver.cpp): whole cache lines only when the
  // buffers start on one (fftw_alloc_real gives 32-byte alignment on x86-64 builds with AVX).
  std::vector<detail::AlignedBuffer> buffers;
  for (std::size_t n = 1; n < 400; n += 7) {
    buffers.emplace_back(n);
    INFO(n << " doubles");
    CHECK(reinterpret_cast<std::uintptr_t>(buffers.back().data()) % 64 == 0);
  }
}

TEST_CASE("SineTransform: equals half of FFTW's RODFT00 and inverts itself", "[solvers]") {
  for (int n : {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 63, 64, 100, 127, 130, 255}) {
    INFO("n = " << n);
    detail::SineTransform S(n, FFTW_ESTIMATE);
    const auto len = static_cast<std::size_t>(n);
    std::vector<double> f(len), F(len), back(len);
    std::mt19937 rng(static_cast<std::uint32_t>(n));
    std::uniform_real_distribution<double> u(-1, 1);
    for (double& v : f) v = u(rng);
    detail::AlignedBuffer in(len), out(len);
    fftw_plan plan = fftw_plan_r2r_1d(n, in.data(), out.data(), FFTW_RODFT00, FFTW_ESTIMATE);
    std::copy(f.begin(), f.end(), in.data());
    fftw_execute(plan);
    fftw_destroy_plan(plan);
    S.apply(f.data(), F.data());
    double err = 0;
    for (int k = 0; k < n; ++k) err = std::max(err, std::abs(F[std::size_t(k)] - 0.5 * out[std::size_t(k)]));
    CHECK(err < 1e-14 * n);
    S.apply(F.data(), back.data(), 2.0 / (n + 1));
    for (int k = 0; k < n; ++k) CHECK(back[std::size_t(k)] == Approx(f[std::size_t(k)]).margin(1e-14 * n));
    S.apply(f.data(), f.data());  // in place
    for (int k = 0; k < n; ++k) CHECK(f[std::size_t(k)] == F[std::size_t(k)]);
  }
}

TEST_CASE("sine_transform_1d: orthonormal, and the 2-D transform of u ⊗ v is û ⊗ v̂", "[solvers]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> r(-1, 1);
  for (auto [rows, cols] : {std::pair{1, 1}, {3, 7}, {16, 9}, {31, 40}}) {
    INFO(rows << "x" << cols);
    const Eigen::VectorXd u = Eigen::VectorXd::NullaryExpr(rows, [&] { return r(rng); });
    const Eigen::VectorXd v = Eigen::VectorXd::NullaryExpr(cols, [&] { return r(rng); });
    const Eigen::VectorXd uh = sine_transform_1d(u), vh = sine_transform_1d(v);
    CHECK(uh.norm() == Approx(u.norm()).epsilon(1e-13));            // orthonormal
    CHECK((sine_transform_1d(uh) - u).norm() <= 1e-13 * u.norm());  // its own inverse
    Eigen::MatrixXd grid(Eigen::Index(rows) * cols, 1);             // u ⊗ v, row-major
    for (int i = 0; i < rows; ++i) grid.block(Eigen::Index(i) * cols, 0, cols, 1) = u(i) * v;
    const Eigen::MatrixXd g = sine_transform_2d(grid, rows, cols);
    for (int p = 0; p < rows; ++p)
      for (int q = 0; q < cols; ++q) CHECK(g(Eigen::Index(p) * cols + q, 0) == Approx(uh(p) * vh(q)).margin(1e-13));
  }
}

TEST_CASE("structured solvers: equal the dense reference for every alpha", "[solvers]") {
  std::uint32_t seed = 10;
  for (const auto& [name, make] : structured())
    for (auto [rows, cols] : grids())
      for (double alpha : {-0.25, -0.1, 0.0, 0.2, 0.25}) {
        const GridStencil s = alpha_grid_stencil(rows, cols, alpha);
        check_against_reference(name, make, s, ring_rhs(s, seed++));
        check_against_reference(name, make, s, dense_rhs(s, seed++));
      }
}

TEST_CASE("structured solvers: two and three threads give the one-thread solution bit for bit", "[solvers]") {
  // fast: one thread eliminates every mode with the same operations on the same numbers, and
  // the rows are transformed alike whichever thread takes them. dst: each row and each strip of
  // columns is transformed alike whichever thread takes it. So the split cannot change a bit.
  // 150 + 1 columns is prime: fast eliminates the last column of that grid (the capacitance
  // path), whose two passes go through the threads too.
  for (const auto& [name, make] : structured())
    for (auto [rows, cols] : {std::pair{127, 131}, {70, 150}, {33, 255}}) {
      const GridStencil s = alpha_grid_stencil(rows, cols, -0.1);
      for (const Eigen::MatrixX3d& B : {dense_rhs(s, 53), ring_rhs(s, 54)}) {
        Eigen::MatrixX3d X1;
        const SolveSummary s1 = make({})->compute_and_solve(grid_operator(s), B, X1);
        REQUIRE(s1.ok());
        CHECK(s1.relative_residual < 1e-11);
        for (int threads : {2, 3}) {
          SolverOptions many;
          many.threads = threads;
          Eigen::MatrixX3d X;
          const SolveSummary sk = make(many)->compute_and_solve(grid_operator(s), B, X);
          INFO(name << " " << rows << "x" << cols << ", " << threads << " threads: " << sk.brief_report());
          REQUIRE(sk.ok());
          CHECK(std::memcmp(X1.data(), X.data(), sizeof(double) * std::size_t(X1.size())) == 0);
        }
      }
    }
}

TEST_CASE("dst: a right-hand side next to the frame skips the forward transform and agrees with the full path",
          "[solvers]") {
  // The same ring right-hand side once as it is (closed-form transform from its four sides) and
  // once with a tiny value inside (the full 2-D transform): the solutions differ by that value's
  // contribution only, so their difference is bounded by it.
  for (auto [rows, cols] : {std::pair{3, 3}, {9, 14}, {31, 40}}) {
    const GridStencil s = alpha_grid_stencil(rows, cols, -0.1);
    const Eigen::MatrixX3d ring = ring_rhs(s, 56);
    Eigen::MatrixX3d nudged = ring;
    const Eigen::Index inner = Eigen::Index(rows / 2) * cols + cols / 2;
    nudged.row(inner).setConstant(1e-300);  // below rounding of every solution value
    Eigen::MatrixX3d X_ring, X_full;
    const SolveSummary a = make_dst_solver({})->compute_and_solve(grid_operator(s), ring, X_ring);
    const SolveSummary b = make_dst_solver({})->compute_and_solve(grid_operator(s), nudged, X_full);
    INFO(rows << "x" << cols << ": " << a.brief_report() << "; " << b.brief_report());
    REQUIRE(a.ok());
    REQUIRE(b.ok());
    CHECK((X_ring - X_full).cwiseAbs().maxCoeff() <= 1e-14 * std::max(1.0, X_ring.cwiseAbs().maxCoeff()));
    CHECK((X_ring - dense_reference(s, ring)).cwiseAbs().maxCoeff() <=
          1e-12 * std::max(1.0, X_ring.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("dst: its one pass over B finds an interior value in any row, on 1, 2 and 3 threads", "[solvers]") {
  // rhs_scaling decides, band by band of rows, which columns lie on the ring (closed-form
  // transform) and which need the forward transform: a value missed inside would be dropped.
  const int rows = 70, cols = 150;
  const GridStencil s = alpha_grid_stencil(rows, cols, -0.1);
  for (const int row : {1, rows / 2 - 1, rows / 2, rows - 2})
    for (const int column : {0, 2}) {
      Eigen::MatrixX3d B = ring_rhs(s, 57);
      B(Eigen::Index(row) * cols + cols / 3, column) = 1e-3;               // one value inside, in one column
      Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(stencil_matrix(s));  // 10,500 unknowns: sparse
      REQUIRE(lu.info() == Eigen::Success);
      const Eigen::MatrixX3d reference = lu.solve(Eigen::MatrixXd(B));
      for (int threads : {1, 2, 3}) {
        SolverOptions options;
        options.threads = threads;
        Eigen::MatrixX3d X;
        const SolveSummary summary = make_dst_solver(options)->compute_and_solve(grid_operator(s), B, X);
        INFO("row " << row << ", column " << column << ", " << threads << " threads: " << summary.brief_report());
        REQUIRE(summary.ok());
        CHECK((X - reference).cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, reference.cwiseAbs().maxCoeff()));
      }
    }
}

TEST_CASE("structured solvers: equal the dense reference on anisotropic stencils", "[solvers]") {
  std::uint32_t seed = 30;
  for (const auto& [name, make] : structured())
    for (auto [rows, cols] : {std::pair{5, 11}, {11, 5}, {8, 13}})
      for (double mu : {0.5, 3.0, 10.0}) {
        const GridStencil s = anisotropic_stencil(rows, cols, mu);
        REQUIRE(s.edge_i != s.edge_j);
        check_against_reference(name, make, s, ring_rhs(s, seed++));
        check_against_reference(name, make, s, dense_rhs(s, seed++));
      }
}

TEST_CASE("fast: the Kronecker path equals the transform path", "[solvers]") {
  // c·d = e_i·e_j: the stencil is T_i ⊗ T_j and fast solves it without transforms; dst always
  // goes through the 2-D transform. Ring right-hand sides take the rank-4 route, dense ones and
  // those with more than a few dense rows the two batches of tridiagonal solves.
  std::uint32_t seed = 40;
  const std::vector<GridStencil> kronecker = {
      alpha_grid_stencil(13, 10, -0.25), {9, 14, 2.0, -0.6, -0.5, 0.15}, {10, 10, 1.0, -0.3, 0.0, 0.0},  // T_j = I
      {1, 8, 1.0, -0.5, -0.5, 0.25},     {8, 1, 1.0, -0.5, -0.5, 0.25},
  };
  for (const GridStencil& s : kronecker) {
    REQUIRE(s.center * s.diag == Approx(s.edge_i * s.edge_j));
    for (const Eigen::MatrixX3d& B : {ring_rhs(s, seed++), dense_rhs(s, seed++)}) {
      Eigen::MatrixX3d X_fast, X_dst;
      const SolveSummary f = make_fast_solver({})->compute_and_solve(grid_operator(s), B, X_fast);
      const SolveSummary d = make_dst_solver({})->compute_and_solve(grid_operator(s), B, X_dst);
      INFO(s.rows << "x" << s.cols << ": " << f.brief_report() << "; " << d.brief_report());
      REQUIRE(f.ok());
      REQUIRE(d.ok());
      CHECK((X_fast - X_dst).cwiseAbs().maxCoeff() <= 1e-11 * std::max(1.0, X_dst.cwiseAbs().maxCoeff()));
      check_against_reference("fast", make_fast_solver, s, B);
    }
  }
}

TEST_CASE("fast: one solver object scales each right-hand side by its own largest magnitude, on every path",
          "[solvers]") {
  // fast finds the scaling of B (solvers/column_scaling.h) in the scan its solve needs and keeps
  // that scan for the solve: each B must get its own. 12 × 30: cols + 1 = 31 is prime, so the
  // transform path has interface columns; 12 × 15: none; α = −1/4: the Kronecker path. Scaling by
  // 2^e is exact here, so X(2^e B) = 2^e X(B) bit for bit; a NaN fails the solve.
  for (const GridStencil& s :
       {alpha_grid_stencil(12, 30, -0.1), alpha_grid_stencil(12, 15, -0.1), alpha_grid_stencil(12, 30, -0.25)})
    for (const Eigen::MatrixX3d& B : {ring_rhs(s, 80), dense_rhs(s, 81)}) {
      auto solver = make_fast_solver({});
      Eigen::MatrixX3d X;
      REQUIRE(solver->compute_and_solve(grid_operator(s), B, X).ok());
      INFO(s.rows << "x" << s.cols << ", alpha " << -s.diag);
      coons::test::check_scaled_solves(*solver, B, X, 1e-12, B.rows() - 1, 1);
    }
}

TEST_CASE("structured solvers: a sweep equals separate solves", "[solvers]") {
  const GridStencil base = alpha_grid_stencil(11, 9, 0.0);
  // An α sweep of a mask system: B(α) = B0 + α·B1 (ring), plus a dense basis member.
  const std::vector<Eigen::MatrixX3d> basis = {ring_rhs(base, 50), ring_rhs(base, 51), dense_rhs(base, 52)};
  std::vector<LinearSolver::SweepMember> members;
  for (double alpha : {-0.25, -0.1, 0.1, 0.25, -0.2}) {
    const double dense_weight = alpha == -0.2 ? 0.5 : 0.0;
    members.push_back({grid_operator(alpha_grid_stencil(11, 9, alpha)), {1.0, alpha, dense_weight}});
  }
  for (const auto& [name, make] : structured()) {
    auto solver = make({});
    std::vector<Eigen::MatrixX3d> swept(members.size());
    std::vector<SolveSummary> summaries(members.size());
    solver->sweep(basis, members, [&](std::size_t k, const Eigen::MatrixX3d& X, const SolveSummary& s) {
      swept[k] = X;
      summaries[k] = s;
    });
    for (std::size_t k = 0; k < members.size(); ++k) {
      Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(base.size(), 3);
      for (std::size_t r = 0; r < basis.size(); ++r) B += members[k].rhs_weights[r] * basis[r];
      Eigen::MatrixX3d X;
      const SolveSummary alone = make({})->compute_and_solve(members[k].op, B, X);
      INFO(name << ", member " << k << ": " << summaries[k].brief_report());
      REQUIRE(summaries[k].ok());
      CHECK(summaries[k].iterations == 1);
      CHECK(summaries[k].solver == name);
      CHECK(summaries[k].relative_residual < 1e-11);
      CHECK((swept[k] - X).cwiseAbs().maxCoeff() <= 1e-12 * std::max(1.0, X.cwiseAbs().maxCoeff()));
      CHECK(alone.ok());
    }
  }
}

TEST_CASE("structured solvers: report a singular stencil", "[solvers]") {
  // The 3×3 net (rows = cols = 2) at α = −1/2: an eigenvalue is exactly zero.
  const GridStencil s = alpha_grid_stencil(2, 2, -0.5);
  for (const auto& [name, make] : structured()) {
    Eigen::MatrixX3d X;
    const SolveSummary summary = make({})->compute_and_solve(grid_operator(s), ring_rhs(s, 60), X);
    INFO(name << ": " << summary.brief_report());
    CHECK(summary.status == SolveStatus::kSingular);
    CHECK(!summary.message.empty());
  }
}

TEST_CASE("structured solvers: an indefinite stencil is solved exactly or reported, never NaN", "[solvers]") {
  for (double alpha : {-0.4, 0.4, -1.0})
    for (auto [rows, cols] : {std::pair{19, 19}, {17, 22}}) {
      const GridStencil s = alpha_grid_stencil(rows, cols, alpha);
      const Eigen::MatrixX3d B = ring_rhs(s, 70);
      for (const auto& [name, make] : structured()) {
        Eigen::MatrixX3d X;
        const SolveSummary summary = make({})->compute_and_solve(grid_operator(s), B, X);
        INFO(name << ", " << rows << "x" << cols << ", alpha = " << alpha << ": " << summary.brief_report());
        CHECK(std::isfinite(summary.relative_residual));
        if (summary.ok()) {
          CHECK(summary.relative_residual < 1e-8);
          CHECK(X.allFinite());
          const Eigen::MatrixX3d reference = dense_reference(s, B);
          CHECK((X - reference).cwiseAbs().maxCoeff() <= 1e-8 * std::max(1.0, reference.cwiseAbs().maxCoeff()));
        }
      }
    }
}

TEST_CASE("fast: an interface is as accurate as dst on indefinite stencils", "[solvers]") {
  // cols + 1 = 17 and 19 are primes above 13, so fast transforms 15 and 17 columns and
  // eliminates the last one. At these α the symbol changes sign and a mode of the smaller grid
  // can lie next to its zero set: the widened grid this replaced lost up to 6 digits there
  // (29 × 16, α = −0.4240075: relative difference 9.6e-8 with success), or reported a regular
  // operator singular (α = −0.4240077).
  const std::vector<GridStencil> stencils = {
      alpha_grid_stencil(29, 16, -0.4240075442251117), alpha_grid_stencil(29, 16, -0.4240077442251117),
      alpha_grid_stencil(19, 18, 1.5),
      // (1, −2, 1) ⊗ (1, 1.0001, 1) as weights: centre −2.0002, e_i = 1.0001, e_j = −2, d = 1
      GridStencil{29, 16, -2.0002, 1.0001, -2.0, 1.0}};
  for (const GridStencil& s : stencils) {
    const Eigen::MatrixX3d B = ring_rhs(s, 75);
    Eigen::MatrixX3d X, Y;
    const SolveSummary fast = make_fast_solver({})->compute_and_solve(grid_operator(s), B, X);
    const SolveSummary dst = make_dst_solver({})->compute_and_solve(grid_operator(s), B, Y);
    INFO(s.rows << "x" << s.cols << ", c = " << s.center << ", e_i = " << s.edge_i << ", d = " << s.diag << ": "
                << fast.brief_report() << " / " << dst.brief_report());
    REQUIRE(dst.ok());
    REQUIRE(fast.ok());
    CHECK(fast.relative_residual < 1e-13);
    CHECK((X - Y).cwiseAbs().maxCoeff() <= 1e-12 * Y.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("structured solvers: need the grid stencil", "[solvers]") {
  const GridStencil s = alpha_grid_stencil(4, 4, 0.0);
  const Eigen::SparseMatrix<double> A = stencil_matrix(s);
  LinearOperator op;
  op.matrix = &A;
  for (const auto& [name, make] : structured()) {
    Eigen::MatrixX3d X;
    const SolveSummary summary = make({})->compute_and_solve(op, dense_rhs(s, 80), X);
    INFO(name);
    CHECK(summary.status == SolveStatus::kNotApplicable);
    CHECK(!summary.message.empty());
  }
}

TEST_CASE("fast: analyze once, factorize across the Kronecker and transform paths", "[solvers]") {
  const GridStencil base = alpha_grid_stencil(10, 13, 0.0);
  const Eigen::MatrixX3d B = ring_rhs(base, 90);
  auto solver = make_fast_solver({});
  REQUIRE(solver->analyze(grid_operator(base)) == SolveStatus::kSuccess);
  int compared = 0;
  for (double alpha : {-0.25, 0.1, -0.25, -0.4, 0.25, -0.25}) {
    const GridStencil s = alpha_grid_stencil(10, 13, alpha);
    INFO("alpha = " << alpha);
    // α in [−1/4, 1/4] is definite: it must be solved; the indefinite −0.4 may be reported instead
    const bool definite = alpha >= -0.25 && alpha <= 0.25;
    const SolveStatus factorized = solver->factorize(grid_operator(s));
    if (definite) REQUIRE(factorized == SolveStatus::kSuccess);
    if (factorized != SolveStatus::kSuccess) continue;
    Eigen::MatrixX3d X;
    const SolveSummary summary = solver->solve(B, X);
    INFO(summary.brief_report());
    if (definite) REQUIRE(summary.ok());
    if (!summary.ok()) continue;
    const Eigen::MatrixX3d reference = dense_reference(s, B);
    CHECK((X - reference).cwiseAbs().maxCoeff() <= 1e-9 * std::max(1.0, reference.cwiseAbs().maxCoeff()));
    ++compared;
  }
  CHECK(compared >= 5);  // the five definite α at least
}

TEST_CASE("structured solvers: two solver objects give bitwise equal results", "[solvers]") {
  // FFTW_ESTIMATE plans are chosen without timing: the same algorithm, the same rounding, in
  // every object and every run (FFTW_MEASURE ones may differ in the last digits).
  for (const auto& [name, make] : structured()) {
    for (auto [rows, cols] : {std::pair{39, 39}, {60, 34}, {127, 100}}) {
      const GridStencil s = alpha_grid_stencil(rows, cols, -0.2);
      const Eigen::MatrixX3d B = dense_rhs(s, 31);
      Eigen::MatrixX3d X1, X2;
      const SolveSummary a = make({})->compute_and_solve(grid_operator(s), B, X1);
      const SolveSummary b = make({})->compute_and_solve(grid_operator(s), B, X2);
      INFO(name << " " << rows << "x" << cols);
      REQUIRE(a.ok());
      REQUIRE(b.ok());
      CHECK(std::memcmp(X1.data(), X2.data(), sizeof(double) * std::size_t(X1.size())) == 0);
    }
  }
}

#endif  // COONS_HAVE_FFTW
