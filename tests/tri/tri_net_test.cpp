#include "coons/tri/tri_net.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/fixtures.h"
#include "tri/tri_fixtures.h"

using namespace coons::tri;
using coons::tri_test::factorial;
using coons::tri_test::random_tri_net;

namespace {

// The Bernstein sum written out: Σ b_ijk n!/(i!j!k!) u^i v^j w^k.
Eigen::RowVector3d bernstein_sum(const TriNet& net, const Eigen::Vector3d& uvw) {
  const int n = net.n;
  Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n - i; ++j) {
      const int k = n - i - j;
      p += factorial(n) / (factorial(i) * factorial(j) * factorial(k)) * std::pow(uvw(0), i) * std::pow(uvw(1), j) *
           std::pow(uvw(2), k) * net.at(i, j, k);
    }
  return p;
}

const Eigen::Vector3d kSamplePoints[] = {
    {0.2, 0.3, 0.5}, {1, 0, 0}, {0, 0.4, 0.6}, {0.7, 0.2, 0.1}, {1.0 / 3, 1.0 / 3, 1.0 / 3}};

}  // namespace

TEST_CASE("net_index: rows k = 0..n, j increasing, interior numbered in the same order", "[tri]") {
  for (int n = 0; n <= 20; ++n) {
    Eigen::Index expected = 0, expected_interior = 0;
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n - k; ++j) {
        REQUIRE(net_index(n, j, k) == expected++);
        if (is_interior(n, n - k - j, j, k)) REQUIRE(interior_index(n, j, k) == expected_interior++);
      }
    REQUIRE(expected == net_size(n));
    REQUIRE(expected_interior == interior_size(n));
    if (n >= 1) REQUIRE(interior_size(n) == (n - 1) * (n - 2) / 2);
  }
  const TriNet net = random_tri_net(4, 2);
  const Eigen::MatrixX3d row1 = net_row(net, 1);  // net[1] = b[3][0][1], b[2][1][1], b[1][2][1], b[0][3][1]
  REQUIRE(row1.rows() == 4);
  REQUIRE(row1.row(0) == net.at(3, 0, 1));
  REQUIRE(row1.row(3) == net.at(0, 3, 1));
  REQUIRE(net_row(net, 4).rows() == 1);
  REQUIRE(net_row(net, 4).row(0) == net.at(0, 0, 4));
}

TEST_CASE("boundary_of: sides run as in the contract and frame_net puts them back", "[tri]") {
  const TriNet net = random_tri_net(5, 11);
  const TriBoundary b = boundary_of(net, "t");
  REQUIRE(b.sides[0].row(0) == net.at(5, 0, 0));
  REQUIRE(b.sides[0].row(2) == net.at(3, 2, 0));
  REQUIRE(b.sides[0].row(5) == net.at(0, 5, 0));
  REQUIRE(b.sides[1].row(1) == net.at(0, 4, 1));
  REQUIRE(b.sides[1].row(5) == net.at(0, 0, 5));
  REQUIRE(b.sides[2].row(1) == net.at(1, 0, 4));
  REQUIRE(b.sides[2].row(5) == net.at(5, 0, 0));
  REQUIRE(largest_corner_gap(b).gap == 0.0);
  const TriNet frame = frame_net(b);
  for (int k = 0; k <= 5; ++k)
    for (int j = 0; j <= 5 - k; ++j) {
      const int i = 5 - k - j;
      if (is_interior(5, i, j, k))
        REQUIRE(frame.at(i, j, k).isZero());
      else
        REQUIRE(frame.at(i, j, k) == net.at(i, j, k));
    }
  TriBoundary moved = b;
  moved.sides[1](5, 2) += 0.25;  // b[0][0][n] as the end of side 1
  const TriCornerGap gap = largest_corner_gap(moved);
  REQUIRE(gap.corner == "b[0][0][n]");
  REQUIRE(gap.gap == Approx(0.25));
}

TEST_CASE("evaluate: de Casteljau equals the Bernstein sum and interpolates the sides", "[tri]") {
  for (int n = 1; n <= 12; ++n) {
    const TriNet net = random_tri_net(n, 100 + n);
    for (const auto& uvw : kSamplePoints) REQUIRE((evaluate(net, uvw) - bernstein_sum(net, uvw)).norm() < 1e-12);
    REQUIRE((evaluate(net, {0, 0, 1}) - net.at(0, 0, n)).norm() < 1e-14);
    const TriBoundary b = boundary_of(net);
    for (const double t : {0.1, 0.5, 0.8}) {  // side 0 is the curve w = 0 from (1,0,0) to (0,1,0)
      REQUIRE((evaluate(net, {1 - t, t, 0}) - coons::test::bezier_curve(b.sides[0], t)).norm() < 1e-12);
      REQUIRE((evaluate(net, {0, 1 - t, t}) - coons::test::bezier_curve(b.sides[1], t)).norm() < 1e-12);
      REQUIRE((evaluate(net, {t, 0, 1 - t}) - coons::test::bezier_curve(b.sides[2], t)).norm() < 1e-12);
    }
  }
}

TEST_CASE("derivative_net: first and second directional derivatives match finite differences", "[tri]") {
  const Eigen::Vector3d d1(1, 0, -1), d2(-0.5, 1, -0.5);
  for (int n = 1; n <= 9; n += 2) {
    const TriNet net = random_tri_net(n, 200 + n);
    for (const Eigen::Vector3d& uvw : {Eigen::Vector3d(0.2, 0.3, 0.5), Eigen::Vector3d(0.6, 0.1, 0.3)}) {
      const double h = 1e-5;
      const Eigen::RowVector3d fd = (evaluate(net, uvw + h * d1) - evaluate(net, uvw - h * d1)) / (2 * h);
      REQUIRE((directional_derivative(net, uvw, d1) - fd).norm() < 1e-6);
      const Eigen::RowVector3d fd2 =
          (directional_derivative(net, uvw + h * d2, d1) - directional_derivative(net, uvw - h * d2, d1)) / (2 * h);
      REQUIRE((second_directional_derivative(net, uvw, d1, d2) - fd2).norm() < 1e-5 * (1 + fd2.norm()));
    }
  }
}

TEST_CASE("elevate_degree: the surface does not change", "[tri]") {
  for (int n = 1; n <= 10; ++n) {
    const TriNet net = random_tri_net(n, 300 + n);
    const TriNet up = elevate_degree(net, 3);
    REQUIRE(up.n == n + 3);
    REQUIRE((up.at(n + 3, 0, 0) - net.at(n, 0, 0)).norm() < 1e-15);
    for (const auto& uvw : kSamplePoints) REQUIRE((evaluate(up, uvw) - evaluate(net, uvw)).norm() < 1e-12);
  }
}

TEST_CASE("subdivide_at: each of the three parts is the surface over its sub-triangle", "[tri]") {
  const Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
  for (int n = 1; n <= 10; ++n) {
    const TriNet net = random_tri_net(n, 400 + n);
    const Eigen::Vector3d P(0.3, 0.45, 0.25);
    const auto parts = subdivide_at(net, P);
    for (const auto& s : kSamplePoints)
      for (int m = 0; m < 3; ++m) {
        Eigen::Matrix3d corners = e;  // columns: the sub-triangle's vertices in barycentrics
        corners.col(m) = P;
        const Eigen::Vector3d original = corners * s;
        REQUIRE((evaluate(parts[m], s) - evaluate(net, original)).norm() < 1e-12);
      }
    REQUIRE((parts[0].at(n, 0, 0) - evaluate(net, P)).norm() < 1e-13);
  }
}

TEST_CASE("permuted: the net of the surface with permuted barycentrics", "[tri]") {
  const TriNet net = random_tri_net(6, 17);
  for (const auto& perm : coons::tri_test::all_permutations()) {
    const TriNet q = permuted(net, perm);
    for (const auto& uvw : kSamplePoints) {
      Eigen::Vector3d moved;
      for (int m = 0; m < 3; ++m) moved(perm[m]) = uvw(m);
      REQUIRE((evaluate(q, moved) - evaluate(net, uvw)).norm() < 1e-12);
    }
  }
}

TEST_CASE("sub_net: the index sub-triangle i >= i0, j >= j0, k >= k0 as a net", "[tri]") {
  const TriNet net = random_tri_net(8, 21);
  const TriNet s = sub_net(net, 2, 1, 3);
  REQUIRE(s.n == 2);
  REQUIRE(s.at(2, 0, 0) == net.at(4, 1, 3));
  REQUIRE(s.at(0, 2, 0) == net.at(2, 3, 3));
  REQUIRE(s.at(0, 0, 2) == net.at(2, 1, 5));
  REQUIRE(s.at(1, 0, 1) == net.at(3, 1, 4));
}
