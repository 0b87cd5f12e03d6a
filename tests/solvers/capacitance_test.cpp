#include "solvers/capacitance.h"

#include <Eigen/Dense>
#include <Eigen/SparseLU>
#include <catch2/catch.hpp>
#include <random>
#include <tuple>
#include <vector>

#include "solvers/structured_solvers.h"

using namespace coons::solvers;

namespace {

using detail::largest_prime_factor;

// The rule of interface_columns, as specified: a real FFT length m is fast when its prime
// factors are at most 13 and it is even or below 256.
bool fast_length(int m) { return largest_prime_factor(m) <= 13 && (m % 2 == 0 || m < 256); }

}  // namespace

TEST_CASE("largest_prime_factor: of primes, prime powers and products", "[solvers]") {
  CHECK(largest_prime_factor(1) == 1);
  CHECK(largest_prime_factor(2) == 2);
  CHECK(largest_prime_factor(1024) == 2);
  CHECK(largest_prime_factor(1031) == 1031);
  CHECK(largest_prime_factor(1029) == 7);   // 3·7³
  CHECK(largest_prime_factor(1023) == 31);  // 3·11·31
  CHECK(largest_prime_factor(1014) == 13);  // 2·3·13²
  CHECK(largest_prime_factor(2 * 1021) == 1021);
}

TEST_CASE("interface_columns: the transform length below cols + 1 is 13-smooth and even", "[solvers]") {
  // hand-checked: 1031 is prime and 1024 = 2^10; 1001 = 7·11·13 is odd; 1023 = 3·11·31 and
  // 1022 = 2·7·73 down to 1014 = 2·3·13²; 17 is prime and 16 = 2^4
  CHECK(detail::interface_columns(1023) == 0);
  CHECK(detail::interface_columns(1030) == 7);
  CHECK(detail::interface_columns(1000) == 1);
  CHECK(detail::interface_columns(1022) == 9);
  CHECK(detail::interface_columns(16) == 1);
  CHECK(detail::interface_columns(7) == 0);
  for (int cols = 8; cols <= 5000; ++cols) {
    const int k = detail::interface_columns(cols);
    INFO("cols = " << cols << ", k = " << k);
    REQUIRE(k >= 0);
    REQUIRE(k <= detail::kMaxInterface);
    if (k == 0) {  // a fast length already, or none within kMaxInterface
      if (!fast_length(cols + 1))
        for (int j = 1; j <= detail::kMaxInterface; ++j) CHECK(!fast_length(cols - j + 1));
      continue;
    }
    CHECK(!fast_length(cols + 1));
    CHECK(fast_length(cols - k + 1));
    for (int j = 1; j < k; ++j) CHECK(!fast_length(cols - j + 1));  // the nearest one
  }
}

TEST_CASE("fast: an interface of k columns gives the sparse LU's solution", "[solvers]") {
  // 95 = 5·19 and 94 = 2·47, 93 = 3·31, 92 = 4·23 are slow; 91 = 7·13 is odd but short: k = 4.
  // 188 = 4·47 down to 182 = 2·7·13: k = 6.
  for (auto [rows, cols, k] : {std::tuple{6, 94, 4}, {11, 187, 6}, {40, 57, 2}}) {
    REQUIRE(detail::interface_columns(cols) == k);
    for (double alpha : {-0.2, -0.1, 0.0, 0.2}) {
      const double beta = 0.25 - alpha;
      const GridStencil s{rows, cols, 1.0, -beta, -beta, -alpha};
      LinearOperator op;
      op.stencil = s;
      const Eigen::SparseMatrix<double> A = stencil_matrix(s);
      std::mt19937 rng(static_cast<std::uint32_t>(rows * cols));
      std::uniform_real_distribution<double> u(-1, 1);
      // dense: every row transformed; ring: values next to the frame only, so most rows are
      // sparse and the interface moves into their `last` values
      Eigen::MatrixX3d dense(s.size(), 3), ring = Eigen::MatrixX3d::Zero(s.size(), 3);
      for (Eigen::Index i = 0; i < dense.size(); ++i) dense.data()[i] = u(rng);
      for (int i = 0; i < rows; ++i)
        for (int j = 0; j < cols; ++j)
          if (i == 0 || j == 0 || i == rows - 1 || j == cols - 1) ring.row(Eigen::Index(i) * cols + j) = dense.row(i);
      const Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(A);
      for (const Eigen::MatrixX3d& B : {dense, ring}) {
        Eigen::MatrixX3d X;
        const SolveSummary summary = make_fast_solver({})->compute_and_solve(op, B, X);
        INFO(rows << "x" << cols << ", alpha " << alpha << ": " << summary.brief_report());
        REQUIRE(summary.ok());
        const Eigen::MatrixX3d reference = lu.solve(B);
        CHECK((X - reference).cwiseAbs().maxCoeff() <= 1e-12 * reference.cwiseAbs().maxCoeff());
      }
    }
  }
}
