#include "coons/net/degree_elevation.h"

#include <catch2/catch.hpp>
#include <random>

#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("elevate_curve: the curve does not change", "[net]") {
  std::mt19937 rng(91);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int degree = 1; degree <= 6; ++degree) {
    Eigen::MatrixX3d P(degree + 1, 3);
    for (Eigen::Index k = 0; k < P.size(); ++k) P.data()[k] = u(rng);
    for (const int to : {degree, degree + 1, degree + 7}) {
      const Eigen::MatrixX3d Q = elevate_curve(P, to);
      REQUIRE(Q.rows() == to + 1);
      for (int k = 0; k <= 20; ++k) {
        INFO("degree " << degree << " to " << to << ", t = " << k / 20.0);
        CHECK((bezier_curve(Q, k / 20.0) - bezier_curve(P, k / 20.0)).norm() < 1e-14);
      }
    }
  }
}

TEST_CASE("elevate_curve: equal neighbours stay equal bit for bit", "[net]") {
  // A constant side elevated from 3 to 30, and a side whose z is constant: a Q_{i-1} + (1 - a) Q_i
  // gave 3.0000000000000004 for 3, a spread the α search scaled up to a shape.
  Eigen::MatrixX3d P(4, 3);
  P.rowwise() = Eigen::RowVector3d(1, 2, 3);
  for (int to = 4; to <= 30; ++to) {
    const Eigen::MatrixX3d Q = elevate_curve(P, to);
    INFO("degree " << to);
    CHECK((Q.rowwise() - Eigen::RowVector3d(1, 2, 3)).cwiseAbs().maxCoeff() == 0);
  }
  P << 0, 0, 0.7, 0.3, 1, 0.7, 0.9, -1, 0.7, 1.3, 0.2, 0.7;
  const Eigen::MatrixX3d Q = elevate_curve(P, 17);
  CHECK((Q.col(2).array() == 0.7).all());
}
