// fast5 internals: the closed form of the lowest modes against dense M_q, against the banded
// solves, and its forward error against a binary128 reference (the reason it exists); the row
// forms of the right-hand side (fast5_rows.h) and the sweeps that read them; the capacitance
// blocks' low-rank preconditioner; the closed-form boundary values against dense solves.
#include <catch2/catch.hpp>

#include "coons/config.h"

#if COONS_HAVE_FFTW

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "fast5_fixtures.h"
#include "solvers/fast5_boundary_values.h"
#include "solvers/fast5_capacitance.h"
#include "solvers/fast5_low_modes.h"
#include "solvers/fast5_modes.h"
#include "solvers/linear_solver.h"
#include "solvers/sine_transform.h"

using namespace coons::solvers;
using namespace coons::solvers::fast5_detail;
using namespace coons::solvers::fast5_detail::testing;

TEST_CASE("solve_low_modes: M_q times its output is its input, and the dots are those of the output", "[solvers]") {
  const int rows = 13, cols = 10;
  for (const auto& [a, b] : {std::pair{0.0, 1.0}, {0.5, 0.5}, {2.0, 0.3}}) {
    const LowModes lm = low_modes(a, b, second_difference_eigenvalues(rows), second_difference_eigenvalues(cols), cols);
    REQUIRE(lm.modes == cols);
    detail::SineTransform along_i(rows, detail::fft_planning(SolverOptions{}));
    for (const bool add : {false, true}) {
      SweepFixture f(rows, cols, 7);
      const std::array<std::vector<double>, 3> before = f.grid;
      ChunkOutput out;
      out.grid = {f.grid[0].data(), f.grid[1].data(), f.grid[2].data()};
      out.add = add;
      Eigen::MatrixXd dot;
      solve_low_modes(lm, along_i, 3, f.input(-1.0), out, f.sines, dot);
      REQUIRE(dot.rows() == rows);
      REQUIRE(dot.cols() == 2 * 2 * 3);
      const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
      for (int c = 0; c < 3; ++c) {
        for (int q = 0; q < cols; ++q) {
          Eigen::VectorXd x(rows);
          for (int r = 0; r < rows; ++r) {
            const std::size_t at = std::size_t(r) * std::size_t(cols) + std::size_t(q);
            x[r] = f.grid[std::size_t(c)][at] - (add ? before[std::size_t(c)][at] : 0.0);
          }
          const Eigen::VectorXd v = f.input_column(q, c, -1.0);
          INFO("a = " << a << ", b = " << b << ", add = " << add << ", rhs " << c << ", mode " << q);
          CHECK((mode_matrix(a, b, nu[q], rows) * x - v).norm() <=
                1e-13 * v.norm() * mode_matrix(a, b, nu[q], rows).norm());
        }
        for (int r = 0; r < rows; ++r)
          for (int m = 0; m < 2; ++m)
            for (int p = 0; p < 2; ++p) {
              double expected = 0;
              for (int q = p; q < cols; q += 2)
                expected += f.grid[std::size_t(c)][std::size_t(r) * std::size_t(cols) + std::size_t(q)] * f.sines(q, m);
              CHECK(dot(r, 2 * (2 * c + m) + p) == Approx(expected).margin(1e-13));
            }
      }
    }
  }
}

TEST_CASE("solve_low_modes and solve_chunk: the same M_q inverse on the modes both solve", "[solvers]") {
  const int rows = 40, cols = 24;
  const double a = 0.5, b = 0.5;
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const LowModes lm = low_modes(a, b, second_difference_eigenvalues(rows), nu, cols);
  const ModeFactors factors = factor_modes(a, b, nu, rows, 1);
  detail::SineTransform along_i(rows, detail::fft_planning(SolverOptions{}));
  SweepFixture closed(rows, cols, 3), banded(rows, cols, 3);
  ChunkOutput out_closed, out_banded;
  out_closed.grid = {closed.grid[0].data(), closed.grid[1].data(), closed.grid[2].data()};
  out_banded.grid = {banded.grid[0].data(), banded.grid[1].data(), banded.grid[2].data()};
  Eigen::MatrixXd dot_closed, dot_banded;
  solve_low_modes(lm, along_i, 3, closed.input(1.0), out_closed, closed.sines, dot_closed);
  std::vector<double> buf(3 * std::size_t(rows) * std::size_t(cols));
  solve_chunk(factors, 0, cols, 3, banded.input(1.0), out_banded, buf.data(), banded.sines, dot_banded);
  for (int c = 0; c < 3; ++c) {
    const Eigen::Map<const Eigen::VectorXd> x(closed.grid[std::size_t(c)].data(), rows * cols);
    const Eigen::Map<const Eigen::VectorXd> y(banded.grid[std::size_t(c)].data(), rows * cols);
    CHECK((x - y).norm() <= 1e-12 * y.norm());
  }
  CHECK((dot_closed - dot_banded).norm() <= 1e-12 * dot_banded.norm());
}

TEST_CASE("solve_low_modes: the lowest mode far more accurately than banded LDL^T, whose error is kappa times eps",
          "[solvers]") {
  // Biharmonic (a = 0, b = 1), mode q = 0 of a 511 × 511 grid. The input M_0 x of a
  // known x is formed in binary128, rounded once to double; the reference solution of that rounded
  // input by LDLᵀ in binary128 too (forward error about κ·1e-34).
  const int rows = 511, cols = 511;
  const double a = 0, b = 1;
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  using Quad = __float128;
  const Quad alpha = Quad(a) * nu[0] * nu[0] + b, beta = 2 * Quad(b) * nu[0], gamma = Quad(b) * nu[0] * nu[0];
  const Quad d0 = 6 * alpha + 2 * beta + gamma, d1 = -4 * alpha - beta, d2 = alpha;
  const auto n = static_cast<std::size_t>(rows);
  std::vector<Quad> x(n), v(n);
  for (int r = 0; r < rows; ++r) x[std::size_t(r)] = Quad(std::sin(0.013 * r) + 0.3 * std::cos(0.2 * r));
  const auto at = [&](const std::vector<Quad>& w, int r) { return r >= 0 && r < rows ? w[std::size_t(r)] : Quad(0); };
  SweepFixture f(rows, cols, 11);
  for (int r = 0; r < rows; ++r) {
    const Quad value = d2 * at(x, r - 2) + d1 * at(x, r - 1) + d0 * at(x, r) + d1 * at(x, r + 1) + d2 * at(x, r + 2);
    f.hats[0][std::size_t(r) * std::size_t(cols)] = double(value);
    v[std::size_t(r)] = Quad(double(value));
  }
  // reference: banded LDLᵀ (bandwidth 2) of M_0 in binary128 on the rounded input
  std::vector<Quad> dd(n), l1(n), l2(n), y = v;
  for (int r = 0; r < rows; ++r) {
    const Quad dm1 = r >= 1 ? dd[std::size_t(r) - 1] : 0, dm2 = r >= 2 ? dd[std::size_t(r) - 2] : 0;
    const Quad l1m1 = r >= 1 ? l1[std::size_t(r) - 1] : 0, l2m1 = r >= 1 ? l2[std::size_t(r) - 1] : 0;
    const Quad l2m2 = r >= 2 ? l2[std::size_t(r) - 2] : 0;
    dd[std::size_t(r)] = d0 - l1m1 * l1m1 * dm1 - l2m2 * l2m2 * dm2;
    l1[std::size_t(r)] = (d1 - l2m1 * dm1 * l1m1) / dd[std::size_t(r)];
    l2[std::size_t(r)] = d2 / dd[std::size_t(r)];
  }
  for (int r = 0; r < rows; ++r)
    y[std::size_t(r)] -= (r >= 1 ? l1[std::size_t(r) - 1] * y[std::size_t(r) - 1] : 0) +
                         (r >= 2 ? l2[std::size_t(r) - 2] * y[std::size_t(r) - 2] : 0);
  for (int r = rows - 1; r >= 0; --r)
    y[std::size_t(r)] = y[std::size_t(r)] / dd[std::size_t(r)] -
                        (r + 1 < rows ? l1[std::size_t(r)] * y[std::size_t(r) + 1] : 0) -
                        (r + 2 < rows ? l2[std::size_t(r)] * y[std::size_t(r) + 2] : 0);
  // the two double-precision solves of mode 0 (the other modes and inputs do not matter here)
  f.z[0].setZero();
  f.z[1].setZero();
  const LowModes lm = low_modes(a, b, second_difference_eigenvalues(rows), nu, 2);
  const ModeFactors factors = factor_modes(a, b, nu, rows, 1);
  detail::SineTransform along_i(rows, detail::fft_planning(SolverOptions{}));
  SweepFixture closed = f, banded = f;
  ChunkOutput out_closed, out_banded;
  out_closed.grid = {closed.grid[0].data(), nullptr, nullptr};
  out_banded.grid = {banded.grid[0].data(), nullptr, nullptr};
  Eigen::MatrixXd dot;
  solve_low_modes(lm, along_i, 1, closed.input(1.0), out_closed, closed.sines, dot);
  std::vector<double> buf(3 * std::size_t(rows) * 2);
  solve_chunk(factors, 0, 2, 1, banded.input(1.0), out_banded, buf.data(), banded.sines, dot);
  const auto error = [&](const SweepFixture& s) {
    double e2 = 0, r2 = 0;
    for (int r = 0; r < rows; ++r) {
      const double ref = double(y[std::size_t(r)]);
      const double diff = double(Quad(s.grid[0][std::size_t(r) * std::size_t(cols)]) - y[std::size_t(r)]);
      e2 += diff * diff;
      r2 += ref * ref;
    }
    return std::sqrt(e2 / r2);
  };
  const double closed_error = error(closed), banded_error = error(banded);
  INFO("forward error: closed form " << closed_error << ", banded LDL^T " << banded_error);
  // measured: 5.7e-12 and 5.2e-9 (κ(SΛS) ≈ 2.8e9, so κ·ε ≈ 6e-7)
  CHECK(closed_error <= 5e-11);
  CHECK(banded_error >= 100 * closed_error);
}

TEST_CASE("split_edge_rows: edge rows as four values, full rows kept up to a limit, the largest magnitude and the norm",
          "[solvers]") {
  const int rows = 9, cols = 11;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(rows, cols);  // row-major data taken from bᵀ below
  for (int r = 0; r < rows; ++r)
    for (int j : {0, 1, cols - 2, cols - 1}) b(r, j) = u(gen);
  b(3, 5) = 0.5;   // full rows: 3 (an interior value), 6 (a value in column 2), 7 (in column cols − 3)
  b(6, 2) = -2.5;  // the largest magnitude
  b(7, cols - 3) = 1e-300;
  b(4, 4) = -0.0;  // −0 is zero
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major = b;
  for (int threads : {1, 2, 3}) {
    const EdgeRows f = split_edge_rows(row_major.data(), rows, cols, threads, 3);
    CHECK_FALSE(f.too_many);
    REQUIRE(f.full_rows() == 3);
    CHECK(f.slot == std::vector<int>{-1, -1, -1, 0, -1, -1, 1, 2, -1});
    for (int r : {3, 6, 7})
      for (int j = 0; j < cols; ++j) CHECK(f.values[std::size_t(f.slot[std::size_t(r)] * cols + j)] == b(r, j));
    for (int r : {0, 4, 8}) {
      const std::array<double, 4> ends{b(r, 0), b(r, 1), b(r, cols - 2), b(r, cols - 1)};
      CHECK(f.ends[std::size_t(r)] == ends);
    }
    CHECK(f.largest == 2.5);
    CHECK(f.norm == Approx(b.norm()).epsilon(1e-15));
  }
  // one full row more than it may keep: none kept, the largest magnitude and the norm still of b
  const EdgeRows dense = split_edge_rows(row_major.data(), rows, cols, 2, 2);
  CHECK(dense.too_many);
  CHECK(dense.full_rows() == 0);
  CHECK(dense.slot == std::vector<int>(std::size_t(rows), -1));
  CHECK(dense.largest == 2.5);
  CHECK(dense.norm == Approx(b.norm()).epsilon(1e-15));
  b(2, 0) = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> with_nan = b;
  CHECK(std::isnan(split_edge_rows(with_nan.data(), rows, cols, 1, rows).largest));
}

TEST_CASE("edge_row_transform: the sine transform of a row that is zero off its two end columns on each side",
          "[solvers]") {
  for (const int cols : {6, 7, 30, 31}) {
    Eigen::VectorXd row = Eigen::VectorXd::Zero(cols), s0(cols), s1(cols);
    const std::array<double, 4> e{0.3, -1.2, 2.0, 0.7};
    row[0] = e[0];
    row[1] = e[1];
    row[cols - 2] = e[2];
    row[cols - 1] = e[3];
    for (int q = 0; q < cols; ++q) {
      s0[q] = std::sqrt(2.0 / (cols + 1)) * std::sin(M_PI * (q + 1) / (cols + 1));
      s1[q] = std::sqrt(2.0 / (cols + 1)) * std::sin(2 * M_PI * (q + 1) / (cols + 1));
    }
    Eigen::VectorXd expected(cols), got(cols);
    detail::SineTransform along(cols, detail::fft_planning(SolverOptions{}));
    along.apply(row.data(), expected.data(), std::sqrt(2.0 / (cols + 1)));
    edge_row_transform(e, s0.data(), s1.data(), 0, cols, got.data());
    INFO("cols = " << cols);
    CHECK((got - expected).norm() <= 1e-14 * expected.norm());
    Eigen::VectorXd tail(cols - 3);  // from a mode q0 > 0 on
    edge_row_transform(e, s0.data(), s1.data(), 3, cols - 3, tail.data());
    CHECK((tail - got.tail(cols - 3)).cwiseAbs().maxCoeff() == 0);
  }
}

TEST_CASE(
    "solve_chunk and solve_low_modes: a right-hand side read from its row forms gives the bits of its stored transform",
    "[solvers]") {
  // rows = 120: the factors converge within the chunk, so that the down pass's segments also start
  // on odd modes (the edge rows formed in the down pass take the parity of their first mode)
  const int rows = GENERATE(30, 120), cols = 40;
  const double a = 0.5, b = 0.5;
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const ModeFactors factors = factor_modes(a, b, nu, rows, 1);
  const LowModes lm = low_modes(a, b, second_difference_eigenvalues(rows), nu, 10);
  detail::SineTransform along_i(rows, detail::fft_planning(SolverOptions{}));
  SweepFixture stored(rows, cols, 21), formed(rows, cols, 21);
  std::mt19937 gen(8);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd s0(cols), s1(cols);
  for (int q = 0; q < cols; ++q) {
    s0[q] = std::sqrt(2.0 / (cols + 1)) * std::sin(M_PI * (q + 1) / (cols + 1));
    s1[q] = std::sqrt(2.0 / (cols + 1)) * std::sin(2 * M_PI * (q + 1) / (cols + 1));
  }
  std::array<EdgeRows, 3> forms;
  for (int c = 0; c < 3; ++c) {  // row 0 full (its given hats), the others edge rows
    EdgeRows& f = forms[std::size_t(c)];
    f.rows = rows;
    f.cols = cols;
    f.ends.assign(std::size_t(rows), {});
    f.slot.assign(std::size_t(rows), -1);
    f.slot[0] = 0;
    f.values.assign(stored.hats[std::size_t(c)].begin(), stored.hats[std::size_t(c)].begin() + cols);
    for (int r = 1; r < rows; ++r) {
      f.ends[std::size_t(r)] = {u(gen), u(gen), u(gen), u(gen)};
      edge_row_transform(f.ends[std::size_t(r)], s0.data(), s1.data(), 0, cols,
                         stored.hats[std::size_t(c)].data() + std::ptrdiff_t(r) * cols);
    }
  }
  SweepInput from_forms = formed.input(-1.0);
  from_forms.hats = {};
  from_forms.edges = {&forms[0], &forms[1], &forms[2]};
  from_forms.s0 = s0.data();
  from_forms.s1 = s1.data();
  ChunkOutput out_stored, out_formed;
  out_stored.grid = {stored.grid[0].data(), stored.grid[1].data(), stored.grid[2].data()};
  out_formed.grid = {formed.grid[0].data(), formed.grid[1].data(), formed.grid[2].data()};
  Eigen::MatrixXd dot_stored, dot_formed;
  solve_low_modes(lm, along_i, 3, stored.input(-1.0), out_stored, stored.sines, dot_stored);
  solve_low_modes(lm, along_i, 3, from_forms, out_formed, formed.sines, dot_formed);
  CHECK((dot_stored - dot_formed).cwiseAbs().maxCoeff() == 0);
  std::vector<double> buf(3 * std::size_t(rows) * std::size_t(cols));
  solve_chunk(factors, 10, cols, 3, stored.input(-1.0), out_stored, buf.data(), stored.sines, dot_stored);
  solve_chunk(factors, 10, cols, 3, from_forms, out_formed, buf.data(), formed.sines, dot_formed);
  CHECK((dot_stored - dot_formed).cwiseAbs().maxCoeff() == 0);
  for (int c = 0; c < 3; ++c) CHECK(stored.grid[std::size_t(c)] == formed.grid[std::size_t(c)]);
  // with t, the edge rows (all but row 0) are formed inside the down pass: the same bits again
  const Eigen::VectorXd t = std::sqrt(2.0) * first_sine_column(cols);
  from_forms.t = t.data();
  std::array<std::vector<double>, 3> fused_grid = formed.grid;
  ChunkOutput out_fused;
  out_fused.grid = {fused_grid[0].data(), fused_grid[1].data(), fused_grid[2].data()};
  Eigen::MatrixXd dot_fused;
  solve_chunk(factors, 10, cols, 3, from_forms, out_fused, buf.data(), formed.sines, dot_fused);
  CHECK((dot_stored - dot_fused).cwiseAbs().maxCoeff() == 0);
  for (int c = 0; c < 3; ++c) CHECK(stored.grid[std::size_t(c)] == fused_grid[std::size_t(c)]);
  int odd_starts = 0;  // rows whose factors change from stored to limit at an odd mode of the chunk
  for (int r = 0; r < rows; ++r)
    odd_starts += factors.active[std::size_t(r)] > 10 && factors.active[std::size_t(r)] < cols &&
                  factors.active[std::size_t(r)] % 2 == 1;
  if (rows == 120) CHECK(odd_starts > 0);
}

TEST_CASE("capacitance_blocks: the low-rank Woodbury solve and one correction reach the dense solution", "[solvers]") {
  const int n = 255;
  const Eigen::VectorXd mu = second_difference_eigenvalues(n);
  const Eigen::VectorXd t = std::sqrt(2.0) * first_sine_column(n);
  for (double w : {0.0, 0.5}) {
    const std::array<CapacitanceBlock, 4> blocks = capacitance_blocks(w, 1 - w, mu, mu, t, 1);
    for (const CapacitanceBlock& blk : blocks) {
      const Eigen::Index m = blk.diag.size();
      INFO("w = " << w << ", block of " << m << " modes, preconditioner rank " << blk.W.cols() - 1);
      REQUIRE(blk.W.cols() > 1);
      CHECK(blk.W.cols() < 40);
      Eigen::MatrixXd cap = blk.diag.asDiagonal();
      cap -= blk.kappa * blk.u * blk.u.transpose() + blk.G * blk.G.transpose();
      Eigen::MatrixXd rhs(m, 3);
      for (Eigen::Index i = 0; i < m; ++i)
        for (Eigen::Index c = 0; c < 3; ++c) rhs(i, c) = std::cos(0.37 * double(i * (c + 1))) + 1.0 / double(i + 1);
      Eigen::MatrixXd X;
      const int iterations = blk.solve(rhs, X, 1e-13);
      CHECK(iterations == 1);
      const Eigen::MatrixXd dense = cap.llt().solve(rhs);
      CHECK((X - dense).norm() <= 1e-12 * dense.norm());
      // a poorer preconditioner (the rank-one term and two cross terms kept): the one correction
      // is not enough, and CG goes on from it to the same solution
      CapacitanceBlock poorer = blk;
      poorer.W.conservativeResize(Eigen::NoChange, 3);
      const Eigen::MatrixXd s =
          Eigen::MatrixXd::Identity(poorer.W.cols(), poorer.W.cols()) - poorer.W.transpose() * poorer.W;
      poorer.S_factor = s.llt().matrixL();
      Eigen::MatrixXd Z;
      const int poorer_iterations = poorer.solve(rhs, Z, 1e-13);
      CHECK(poorer_iterations > 1);
      CHECK((Z - dense).norm() <= 1e-12 * dense.norm());
      CapacitanceBlock diagonal_only = blk;  // the diagonal preconditioner this one replaces
      diagonal_only.W.resize(m, 0);
      Eigen::MatrixXd Y;
      CHECK(diagonal_only.solve(rhs, Y, 1e-13) >= iterations + 3);
      CHECK((Y - dense).norm() <= 1e-12 * dense.norm());
    }
  }
}

namespace {

// The orthonormal DST-I of order n as a dense matrix (symmetric, its own inverse).
Eigen::MatrixXd sine_matrix(int n) {
  Eigen::MatrixXd S(n, n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) S(i, k) = std::sqrt(2.0 / (n + 1)) * std::sin(M_PI * (i + 1) * (k + 1) / (n + 1));
  return S;
}

}  // namespace

TEST_CASE("capacitance_blocks: one grid column (no modes of odd parity along j) builds and solves", "[solvers]") {
  // The blocks of odd q have no columns: their preconditioner is the rank-one term alone (a
  // product of inner size 0 in its set-up divided by zero in Eigen from 48 modes on).
  const int rows = 100;
  const Eigen::VectorXd mu = second_difference_eigenvalues(rows), nu = second_difference_eigenvalues(1);
  const Eigen::VectorXd t = std::sqrt(2.0) * first_sine_column(1);
  const std::array<CapacitanceBlock, 4> blocks = capacitance_blocks(0.5, 0.5, mu, nu, t, 1);
  for (const CapacitanceBlock& blk : blocks) {
    const Eigen::Index m = blk.diag.size();
    Eigen::MatrixXd cap = blk.diag.asDiagonal();
    cap -= blk.kappa * blk.u * blk.u.transpose() + blk.G * blk.G.transpose();
    const Eigen::MatrixXd rhs = Eigen::MatrixXd::Constant(m, 3, 1.0);
    Eigen::MatrixXd X;
    blk.solve(rhs, X, 1e-13);
    INFO("block with " << blk.G.cols() << " columns");
    CHECK((X - cap.llt().solve(rhs)).norm() <= 1e-12 * X.norm());
  }
  CHECK(blocks[2].G.cols() == 0);
}

TEST_CASE("boundary_values: the closed form of g against dense solves of every M_q, rows != cols", "[solvers]") {
  const int R = 9, C = 11;
  const Eigen::MatrixXd Si = sine_matrix(R), Sj = sine_matrix(C);
  const Eigen::VectorXd mu = second_difference_eigenvalues(R), nu = second_difference_eigenvalues(C);
  const Eigen::VectorXd t = std::sqrt(2.0) * first_sine_column(C);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);
  // Full rows 0, 1, 7, 8 and the middle row 4 (its own mirror); the end columns on the other rows.
  const std::vector<int> full = {0, 1, 4, 7, 8};
  const std::vector<int> ends = {0, 1, C - 2, C - 1};
  std::vector<Eigen::MatrixXd> b(2, Eigen::MatrixXd::Zero(R, C));
  for (Eigen::MatrixXd& m : b) {
    for (int r : full)
      for (int j = 0; j < C; ++j) m(r, j) = uniform(rng);
    for (int r = 0; r < R; ++r)
      for (int j : ends) m(r, j) = uniform(rng);
  }
  const std::vector<int> keys = {0, 1, 4};
  const Eigen::VectorXd s0 = Sj.row(0).transpose(), s1 = Sj.row(1).transpose();  // S_j e₀, S_j e₁
  for (double w : {0.0, 0.5}) {
    const double a = w, bb = 1 - w;
    const std::array<CapacitanceBlock, 4> blocks = capacitance_blocks(a, bb, mu, nu, t, 1);
    for (int index = 0; index < 4; ++index) {
      const int qpar = index / 2, ppar = index % 2;
      std::vector<BoundarySource> sources;
      Eigen::MatrixXd expected(Eigen::Index(blocks[std::size_t(index)].modes.size()), 2);
      for (std::size_t c = 0; c < b.size(); ++c) {
        // the dense reference: ĝ = S_i Σ_q t_q M_q⁻¹ b̂(·, q) over the modes q of parity qpar
        const Eigen::MatrixXd bhat = b[c] * Sj;
        Eigen::VectorXd g = Eigen::VectorXd::Zero(R);
        for (int q = qpar; q < C; q += 2) g += t[q] * mode_matrix(a, bb, nu[q], R).llt().solve(bhat.col(q));
        const Eigen::VectorXd ghat = Si * g;
        for (std::size_t k = 0; k < blocks[std::size_t(index)].modes.size(); ++k)
          expected(Eigen::Index(k), Eigen::Index(c)) = ghat[blocks[std::size_t(index)].modes[k]];
        // the source: key rows combined with their mirrors, the end columns off the full rows
        BoundarySource src;
        for (int key : keys) {
          Eigen::VectorXd row = Sj * b[c].row(key).transpose();
          if (R - 1 - key != key) row += (ppar == 0 ? 1.0 : -1.0) * (Sj * b[c].row(R - 1 - key).transpose());
          src.rows.push_back(row);
        }
        Eigen::MatrixXd columns(R, 4);
        for (int j = 0; j < 4; ++j) {
          columns.col(j) = b[c].col(ends[std::size_t(j)]);
          for (int r : full) columns(r, j) = 0;
        }
        src.beta_hat = Si * columns;
        sources.push_back(src);
      }
      const Eigen::MatrixXd got =
          boundary_values(blocks[std::size_t(index)], qpar, t, s0.data(), s1.data(), keys, R, sources);
      INFO("w = " << w << ", block " << index);
      CHECK((got - expected).norm() <= 1e-13 * expected.norm());
      CHECK(expected.norm() > 0);
      // the same sources formed by the solver's path: the row forms of b, their full rows transformed
      std::vector<EdgeRows> edges;
      for (const Eigen::MatrixXd& m : b) {
        const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows_first = m;
        edges.push_back(split_edge_rows(rows_first.data(), R, C, 1, R));
        for (int k = 0; k < edges.back().full_rows(); ++k) {
          Eigen::Map<Eigen::VectorXd> row(edges.back().values.data() + std::ptrdiff_t(k) * C, C);
          row = (Sj * row).eval();
        }
      }
      coons::solvers::detail::SineTransform along_i(R, coons::solvers::detail::fft_planning(SolverOptions{}));
      std::vector<int> formed_keys;
      std::array<std::vector<BoundarySource>, 2> formed;
      REQUIRE(boundary_sources(edges.data(), 2, along_i, 4, formed_keys, formed));
      CHECK(formed_keys == keys);
      const Eigen::MatrixXd via_rows = boundary_values(blocks[std::size_t(index)], qpar, t, s0.data(), s1.data(),
                                                       formed_keys, R, formed[std::size_t(ppar)]);
      CHECK((via_rows - expected).norm() <= 1e-13 * expected.norm());
      CHECK_FALSE(boundary_sources(edges.data(), 2, along_i, 2, formed_keys, formed));  // three key rows
    }
  }
}

TEST_CASE("factor_modes: every row read back (stored or the limit) is the banded LDL^T of M_q, on 1 and 2 threads",
          "[solvers]") {
  const int rows = 90, cols = 24, first = 4;
  const double a = 0.3, b = 0.7;
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const ModeFactors f = factor_modes(a, b, nu, rows, 1, first);
  const ModeFactors f2 = factor_modes(a, b, nu, rows, 2, first);
  CHECK(f2.inv_d == f.inv_d);
  CHECK(f2.l1 == f.l1);
  CHECK(f2.l2 == f.l2);
  CHECK(f2.active == f.active);
  CHECK(f2.lim_inv_d == f.lim_inv_d);
  bool some_limit = false, some_stored = false;
  for (int q = 0; q < cols; ++q) {
    Eigen::MatrixXd L = Eigen::MatrixXd::Identity(rows, rows);
    Eigen::VectorXd d(rows);
    for (int r = 0; r < rows; ++r) {
      const bool stored = q < f.active[std::size_t(r)];
      (stored ? some_stored : some_limit) = true;
      const std::size_t at = f.offset[std::size_t(r)] + std::size_t(q);
      const double inv_d = stored ? f.inv_d[at] : f.lim_inv_d[std::size_t(q)];
      const double l1 = stored ? f.l1[at] : f.lim_l1[std::size_t(q)];
      const double l2 = stored ? f.l2[at] : f.lim_l2[std::size_t(q)];
      if (q < first) {  // not factored: every entry reads zero
        CHECK(inv_d == 0);
        CHECK(l1 == 0);
        CHECK(l2 == 0);
        continue;
      }
      d[r] = 1 / inv_d;
      if (r + 1 < rows) L(r + 1, r) = l1;
      if (r + 2 < rows) L(r + 2, r) = l2;
    }
    if (q < first) continue;
    const Eigen::MatrixXd M = mode_matrix(a, b, nu[q], rows);
    const Eigen::MatrixXd LDLt = L * d.asDiagonal() * L.transpose();
    INFO("mode " << q);
    CHECK((LDLt - M).cwiseAbs().maxCoeff() <= 1e-13 * M.cwiseAbs().maxCoeff());
  }
  CHECK(some_limit);  // the fixture reaches both kinds of rows
  CHECK(some_stored);
}

namespace {

// The reference sums of the G products, with every product rounded before its addition (volatile:
// no compiler may fuse them), in the order the kernels promise.
double eight_partial_sums(const double* a, const double* b, Eigen::Index n) {
  std::array<double, 8> acc{};
  Eigen::Index p = 0;
  for (; p + 8 <= n; p += 8)
    for (std::size_t l = 0; l < 8; ++l) {
      const volatile double product = a[p + Eigen::Index(l)] * b[p + Eigen::Index(l)];
      acc[l] += product;
    }
  double sum = ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
  for (; p < n; ++p) {
    const volatile double product = a[p] * b[p];
    sum += product;
  }
  return sum;
}

}  // namespace

TEST_CASE(
    "dots_of_columns and subtract_columns: the bits of eight partial sums and of one subtraction after another, "
    "in whichever clone runs",
    "[solvers]") {
  // The AVX-512 clone (where the machine has it) must round as the others: a fused multiply-add
  // (the library is built with -ffp-contract=off against it) changes the last bits of most sums.
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random = [&](Eigen::Index rows, Eigen::Index cols) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index k = 0; k < m.size(); ++k) m.data()[k] = uniform(gen);
    return m;
  };
  for (const Eigen::Index n : {1, 7, 8, 13, 64, 517})
    for (const Eigen::Index k : {1, 2, 3, 5})
      for (const Eigen::Index m : {1, 2, 3, 8}) {
        const Eigen::MatrixXd G = random(n, k), V = random(n, m), coef = random(k, m), start = random(n, m);
        Eigen::MatrixXd dots(k, m), out = start;
        for (Eigen::Index k0 = 0; k0 < k; k0 += 2) {
          dots_of_columns(G, k0, V, dots);
          subtract_columns(G, k0, coef, k0 % 4 == 2, out);
        }
        Eigen::MatrixXd expected = start;
        for (Eigen::Index j = 0; j < k; ++j)
          for (Eigen::Index c = 0; c < m; ++c) {
            INFO("n " << n << ", column " << j << " of " << k << ", right-hand side " << c << " of " << m);
            CHECK(dots(j, c) == eight_partial_sums(G.col(j).data(), V.col(c).data(), n));
            const double alpha = j % 4 >= 2 ? -coef(j, c) : coef(j, c);  // negated in the pairs k0 % 4 == 2
            for (Eigen::Index p = 0; p < n; ++p) {
              const volatile double product = alpha * G(p, j);
              expected(p, c) -= product;
            }
          }
        INFO("n " << n << ", " << k << " columns, " << m << " right-hand sides");
        CHECK((out.array() == expected.array()).all());
      }
}

#endif  // COONS_HAVE_FFTW
