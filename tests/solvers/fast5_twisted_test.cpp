// The twisted sweep of fast5 (solvers/fast5_twisted.h): against dense solves of every M_q and the
// row transforms, on grids from its fewest rows up, odd and even, rows != cols; and the lowest modes
// in parts, which the twisted sweep runs on the threads.
#include <catch2/catch.hpp>

#include "coons/config.h"

#if COONS_HAVE_FFTW

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

#include "fast5_fixtures.h"
#include "solvers/fast5_low_modes.h"
#include "solvers/fast5_modes.h"
#include "solvers/fast5_twisted.h"
#include "solvers/linear_solver.h"
#include "solvers/sine_transform.h"

using namespace coons::solvers;
using namespace coons::solvers::fast5_detail;
using namespace coons::solvers::fast5_detail::testing;

TEST_CASE(
    "twisted_down and TwistedUp: every row is the sine transform of M_q inverse of the input, on one and two threads",
    "[solvers]") {
  // (one GENERATE per line: Catch2 tells its generators apart by their line)
  const int rows =
      GENERATE(int(kMinTwistRows), 9, 10, 31, 120);  // (a copy: an lvalue would make it a generator of references)
  const int cols = GENERATE(7, 12, 40);
  const auto [a, b] = GENERATE(std::pair{0.5, 0.5}, std::pair{0.0, 1.0}, std::pair{0.99, 0.01});
  const int threads = GENERATE(1, 2);
  const int low = cols / 4;
  CAPTURE(rows, cols, a, b, threads);
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const ModeFactors factors = factor_modes(a, b, nu, rows, 1, low);
  const TwistFactors tw = twist_factors(factors, low);
  SweepFixture fx(rows, cols, unsigned(rows * 100 + cols));
  const SweepInput in = fx.input(-1.0);
  const std::array<double*, 3> grid{fx.grid[0].data(), fx.grid[1].data(), fx.grid[2].data()};
  // the expected grid: the columns < low as the grid holds them (the lowest modes, written before),
  // the others M_q⁻¹ of the input; each row then transformed
  std::array<Eigen::MatrixXd, 3> expected;
  for (std::size_t c = 0; c < 3; ++c) {
    expected[c].resize(rows, cols);
    for (int r = 0; r < rows; ++r)
      for (int q = 0; q < low; ++q) expected[c](r, q) = fx.grid[c][std::size_t(r) * std::size_t(cols) + std::size_t(q)];
    for (int q = low; q < cols; ++q)
      expected[c].col(q) = mode_matrix(a, b, nu[q], rows).ldlt().solve(fx.input_column(q, int(c), -1.0));
  }
  detail::SineTransform along_j(cols, detail::fft_planning(SolverOptions{}));
  const double scale_j = std::sqrt(2.0 / (cols + 1));
  for (std::size_t c = 0; c < 3; ++c)
    for (int r = 0; r < rows; ++r) {
      Eigen::VectorXd row = expected[c].row(r).transpose();
      along_j.apply(row.data(), row.data(), scale_j);
      expected[c].row(r) = row.transpose();
    }
  std::array<TwistEnds, 2> ends;
  for (int half = 0; half < 2; ++half) twisted_down(factors, tw, half, in, grid, ends[std::size_t(half)]);
  std::array<std::vector<double>, 2> windows;
  for (auto& w : windows) w.resize(9 * std::size_t(cols));
  // done(c, r, row) once per row, with the row written (each (c, r) its own entries: no race)
  std::vector<int> seen(3 * std::size_t(rows), 0);
  std::vector<char> at_row(3 * std::size_t(rows), 0);
  const auto done = [&](int c, int r, const double* row) {
    const std::size_t k = std::size_t(c) * std::size_t(rows) + std::size_t(r);
    ++seen[k];
    at_row[k] = row == grid[std::size_t(c)] + std::ptrdiff_t(r) * cols;
  };
  TwistedUp up(factors, tw, ends, grid, {windows[0].data(), windows[1].data()}, scale_j, done);
  if (threads == 1) {
    up.work(0, 1, along_j);
  } else {  // every thread its own transform
    detail::SineTransform other(cols, detail::fft_planning(SolverOptions{}));
    std::thread second([&] { up.work(1, 2, other); });
    up.work(0, 2, along_j);
    second.join();
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  CHECK(std::all_of(at_row.begin(), at_row.end(), [](char ok) { return ok == 1; }));
  for (std::size_t c = 0; c < 3; ++c) {
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> got(
        fx.grid[c].data(), rows, cols);
    CHECK((got - expected[c]).cwiseAbs().maxCoeff() <= 1e-12 * expected[c].cwiseAbs().maxCoeff());
  }
}

TEST_CASE("twisted_solve: the bits of its steps run one by one, on one and two threads", "[solvers]") {
  const int rows = GENERATE(int(kMinTwistRows), 33);
  const int cols = GENERATE(9, 64);
  const double a = 0.4, b = 0.6;
  const int low = cols / 4;
  CAPTURE(rows, cols);
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const ModeFactors factors = factor_modes(a, b, nu, rows, 1, low);
  const TwistFactors tw = twist_factors(factors, low);
  const LowModes lm = low_modes(a, b, second_difference_eigenvalues(rows), nu, low);
  const unsigned planning = detail::fft_planning(SolverOptions{});
  // the steps one by one on this thread: both ways down, the lowest modes in one call, the ways up
  SweepFixture steps(rows, cols, 17);
  {
    const std::array<double*, 3> grid{steps.grid[0].data(), steps.grid[1].data(), steps.grid[2].data()};
    const SweepInput in = steps.input(-1.0);
    std::array<TwistEnds, 2> ends;
    for (int half = 0; half < 2; ++half) twisted_down(factors, tw, half, in, grid, ends[std::size_t(half)]);
    detail::SineTransform along_i(rows, planning), along_j(cols, planning);
    ChunkOutput out;
    out.grid = grid;
    Eigen::MatrixXd dot;
    solve_low_modes(lm, along_i, 3, in, out, Eigen::MatrixXd(cols, 0), dot);
    std::array<std::vector<double>, 2> scratch;
    for (auto& w : scratch) w.resize(9 * std::size_t(cols));
    TwistedUp up(factors, tw, ends, grid, {scratch[0].data(), scratch[1].data()}, std::sqrt(2.0 / (cols + 1)),
                 [](int, int, const double*) {});
    up.work(0, 1, along_j);
  }
  for (const int threads : {1, 2}) {
    CAPTURE(threads);
    SweepFixture fx(rows, cols, 17);
    const std::array<double*, 3> grid{fx.grid[0].data(), fx.grid[1].data(), fx.grid[2].data()};
    TwistedBuffers buffers = twisted_buffers(rows, cols, threads, planning);
    REQUIRE(buffers.low_along_i.size() == std::size_t(threads - 1));
    REQUIRE(buffers.scratch[1].size() == 9 * std::size_t(cols));
    detail::SineTransform along_i(rows, planning);
    std::vector<detail::SineTransform> along_j;
    along_j.reserve(std::size_t(threads));
    for (int t = 0; t < threads; ++t) along_j.emplace_back(cols, planning);
    std::vector<std::atomic<int>> seen(3 * std::size_t(rows));
    twisted_solve(factors, tw, lm, fx.input(-1.0), grid, buffers, along_i, along_j, threads,
                  [&](int c, int r, const double*) { ++seen[std::size_t(c) * std::size_t(rows) + std::size_t(r)]; });
    CHECK(std::all_of(seen.begin(), seen.end(), [](const std::atomic<int>& n) { return n == 1; }));
    for (std::size_t c = 0; c < 3; ++c) CHECK(fx.grid[c] == steps.grid[c]);
  }
}

TEST_CASE("twisted_buffers: none below kMinTwistRows rows", "[solvers]") {
  const TwistedBuffers b = twisted_buffers(kMinTwistRows - 1, 20, 2, detail::fft_planning(SolverOptions{}));
  CHECK(b.low_along_i.empty());
  CHECK(b.scratch[0].size() + b.scratch[1].size() == 0);
}

TEST_CASE("solve_low_modes: the modes in parts give the bits of one call over all of them", "[solvers]") {
  const int rows = 37, cols = 30, modes = 9;
  const Eigen::VectorXd nu = second_difference_eigenvalues(cols);
  const LowModes lm = low_modes(0.3, 0.7, second_difference_eigenvalues(rows), nu, modes);
  detail::SineTransform along_i(rows, detail::fft_planning(SolverOptions{}));
  SweepFixture whole(rows, cols, 5), parts(rows, cols, 5);
  ChunkOutput out_whole, out_parts;
  out_whole.grid = {whole.grid[0].data(), whole.grid[1].data(), whole.grid[2].data()};
  out_parts.grid = {parts.grid[0].data(), parts.grid[1].data(), parts.grid[2].data()};
  Eigen::MatrixXd dot;
  solve_low_modes(lm, along_i, 3, whole.input(-1.0), out_whole, whole.sines, dot);
  const Eigen::MatrixXd dot_whole = dot;
  Eigen::MatrixXd dot_sum = Eigen::MatrixXd::Zero(dot.rows(), dot.cols());
  for (const auto& [first, last] : {std::pair{0, 4}, std::pair{4, 5}, std::pair{5, modes}}) {
    solve_low_modes(lm, along_i, 3, parts.input(-1.0), out_parts, parts.sines, dot, first, last);
    dot_sum += dot;
  }
  for (std::size_t c = 0; c < 3; ++c) CHECK(whole.grid[c] == parts.grid[c]);  // every column, written or not
  CHECK((dot_sum - dot_whole).cwiseAbs().maxCoeff() <= 1e-14 * dot_whole.cwiseAbs().maxCoeff());
}

#else
TEST_CASE("twisted_down and TwistedUp: skipped", "[solvers]") { WARN("skipped: fast5 needs FFTW (libfftw3-dev)"); }
#endif
