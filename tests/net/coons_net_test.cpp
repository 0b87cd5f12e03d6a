#include "coons/net/coons_net.h"

#include <catch2/catch.hpp>

#include "coons/io/boundary_io.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/net/bernstein.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The continuous Boolean-sum Coons patch of the four boundary curves with blend f0 (f1 = 1 − f0).
template <class F0>
Eigen::RowVector3d coons_patch(const Boundary& b, double u, double v, F0 f0) {
  const Eigen::RowVector3d c0 = bezier_curve(b.bottom, u), c1 = bezier_curve(b.top, u);
  const Eigen::RowVector3d d0 = bezier_curve(b.left, v), d1 = bezier_curve(b.right, v);
  const double fu = f0(u), fv = f0(v);
  const Eigen::RowVector3d corners = fu * fv * b.bottom.row(0) + (1 - fu) * fv * b.bottom.row(b.m) +
                                     fu * (1 - fv) * b.top.row(0) + (1 - fu) * (1 - fv) * b.top.row(b.m);
  return fv * c0 + (1 - fv) * c1 + fu * d0 + (1 - fu) * d1 - corners;
}

double linear_f0(double t) { return 1 - t; }
double hermite_f0(double t) { return 1 - 3 * t * t + 2 * t * t * t; }

const std::pair<int, int> kSizes[] = {{2, 2}, {3, 3},   {2, 5},  {5, 2}, {4, 7},
                                      {9, 6}, {12, 12}, {17, 8}, {1, 4}, {6, 1}};

}  // namespace

TEST_CASE("discrete_coons_net: equals the alpha = -1/4 mask solve", "[net]") {
  std::uint32_t seed = 1;
  for (auto [m, n] : kSizes) {
    const Boundary b = make_random_boundary(m, n, seed++);
    const ControlNet closed = discrete_coons_net(b);
    const MaskSolveResult solved = solve_mask_net(b, alpha_mask(-0.25), backend("eigen-ldlt"));
    INFO("m = " << m << ", n = " << n);
    REQUIRE(solved.summary.ok());
    CHECK(max_difference(closed, solved.net) < 1e-12);
  }
}

TEST_CASE("discrete_coons_net: its surface is the bilinearly blended Coons patch", "[net]") {
  std::uint32_t seed = 100;
  for (auto [m, n] : kSizes) {
    const Boundary b = make_random_boundary(m, n, seed++);
    const ControlNet net = discrete_coons_net(b);
    for (double u : {0.0, 0.13, 0.5, 0.77, 1.0})
      for (double v : {0.0, 0.31, 0.5, 0.9, 1.0}) {
        INFO("m = " << m << ", n = " << n << ", u = " << u << ", v = " << v);
        CHECK((evaluate(net, u, v) - coons_patch(b, u, v, linear_f0)).norm() < 1e-13);
      }
  }
}

TEST_CASE("hermite_coons_net: its surface is the Hermite-blended Coons patch", "[net]") {
  std::uint32_t seed = 200;
  for (auto [m, n] : {std::pair{3, 3}, {3, 5}, {6, 4}, {8, 8}, {11, 7}}) {
    const Boundary b = make_random_boundary(m, n, seed++);
    const ControlNet net = hermite_coons_net(b);
    for (double u : {0.0, 0.21, 0.5, 0.66, 1.0})
      for (double v : {0.0, 0.4, 0.5, 0.95, 1.0}) {
        INFO("m = " << m << ", n = " << n << ", u = " << u << ", v = " << v);
        CHECK((evaluate(net, u, v) - coons_patch(b, u, v, hermite_f0)).norm() < 1e-13);
      }
  }
}

TEST_CASE("hermite_blend_weights: Bernstein coefficients of F0 at every degree", "[net]") {
  for (int k = 3; k <= 20; ++k) {
    const std::vector<double> w = hermite_blend_weights(k);
    const Eigen::Map<const Eigen::VectorXd> W(w.data(), k + 1);
    for (double t : {0.0, 0.2, 0.5, 0.8, 1.0})
      CHECK(bernstein_basis(k, t).dot(W) == Approx(hermite_f0(t)).margin(1e-14));
  }
}

TEST_CASE("solve_mask_net: affine invariance for every alpha", "[net]") {
  Eigen::Matrix3d M;
  M << 1.3, -0.4, 0.2, 0.5, 0.9, -1.1, 0.3, 0.7, 2.0;
  const Eigen::RowVector3d t(3, -2, 0.5);
  const Boundary b = make_random_boundary(6, 9, 7);
  for (double alpha : {-0.25, -0.1, 0.0, 0.2}) {
    const ControlNet a = solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net;
    const ControlNet ta = solve_mask_net(transformed(b, M, t), alpha_mask(alpha), backend("eigen-ldlt")).net;
    INFO("alpha = " << alpha);
    CHECK(max_difference(transformed(a, M, t), ta) < 1e-12);
  }
  const ControlNet c = discrete_coons_net(b);
  CHECK(max_difference(transformed(c, M, t), discrete_coons_net(transformed(b, M, t))) < 1e-12);
}

TEST_CASE("solve_mask_net: transposing or flipping the boundary transposes or flips the net", "[net]") {
  const ControlNet random = make_random_net(5, 8, 11);
  const Boundary b = boundary_of(random);
  for (double alpha : {-0.25, -0.05, 0.0, 0.15}) {
    const ControlNet net = solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net;
    const ControlNet net_t =
        solve_mask_net(boundary_of(transposed(random)), alpha_mask(alpha), backend("eigen-ldlt")).net;
    const ControlNet net_f =
        solve_mask_net(boundary_of(flipped_u(random)), alpha_mask(alpha), backend("eigen-ldlt")).net;
    INFO("alpha = " << alpha);
    CHECK(max_difference(transposed(net), net_t) < 1e-13);
    CHECK(max_difference(flipped_u(net), net_f) < 1e-13);
  }
  CHECK(max_difference(transposed(discrete_coons_net(b)), discrete_coons_net(boundary_of(transposed(random)))) < 1e-14);
  CHECK(max_difference(flipped_u(hermite_coons_net(b)), hermite_coons_net(boundary_of(flipped_u(random)))) < 1e-14);
}

TEST_CASE("solve_mask_net: every alpha reproduces bilinear nets", "[net]") {
  for (auto [m, n] : {std::pair{3, 3}, {4, 9}, {10, 5}}) {
    const ControlNet bilinear = make_bilinear_net(m, n, 5);
    for (double alpha : {-0.25, -0.2, -0.1, 0.0, 0.1, 0.25}) {
      INFO("m = " << m << ", n = " << n << ", alpha = " << alpha);
      CHECK(max_difference(solve_mask_net(boundary_of(bilinear), alpha_mask(alpha), backend("eigen-ldlt")).net,
                           bilinear) < 1e-13);
    }
    CHECK(max_difference(discrete_coons_net(boundary_of(bilinear)), bilinear) < 1e-14);
  }
}

TEST_CASE("seed example 1: the interior point is (1, 0, 1) for every alpha", "[net][seed]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/seed_example1.json").boundary;
  for (double alpha : {-0.25, -0.1, 0.0, 0.25}) {
    const ControlNet net = solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net;
    CHECK((net.at(1, 1) - Eigen::RowVector3d(1, 0, 1)).norm() < 1e-15);
  }
  const ControlNet coons = discrete_coons_net(b);
  CHECK((coons.at(1, 1) - Eigen::RowVector3d(1, 0, 1)).norm() < 1e-15);
  // The patch is (u + v, u² − v², 1 − u + v).
  for (double u : {0.1, 0.5, 0.8})
    for (double v : {0.2, 0.6})
      CHECK((evaluate(coons, u, v) - Eigen::RowVector3d(u + v, u * u - v * v, 1 - u + v)).norm() < 1e-14);
}

TEST_CASE("seed example 2: every alpha reproduces the hyperbolic paraboloid z = 2uv", "[net][seed]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/seed_example2.json").boundary;
  for (double alpha : {-0.25, -0.1, 0.0, 0.2}) {
    const ControlNet net = solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net;
    for (double u : {0.0, 0.3, 0.5, 1.0})
      for (double v : {0.25, 0.75}) CHECK((evaluate(net, u, v) - Eigen::RowVector3d(u, v, 2 * u * v)).norm() < 1e-14);
  }
}

TEST_CASE("dome: the centre heights of docs/math.md §7", "[net][seed]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/dome.json").boundary;
  const std::pair<double, double> table[] = {{-0.25, 0.828427}, {-0.20, 0.724874}, {-0.10, 0.595432}, {0.0, 0.517767}};
  for (auto [alpha, z] : table) {
    const ControlNet net = solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net;
    CHECK(evaluate(net, 0.5, 0.5)(2) == Approx(z).margin(5e-7));
  }
  CHECK(evaluate(discrete_coons_net(b), 0.5, 0.5)(2) == Approx(0.828427).margin(5e-7));
}

TEST_CASE("discrete_coons_net: a 1000 x 1000 net is computed", "[net]") {
  const Boundary b = make_random_boundary(1000, 1000, 3);
  const ControlNet net = discrete_coons_net(b);
  CHECK(net.points.rows() == 1001 * 1001);
  CHECK(net.points.allFinite());
  // Spot-check one interior point against the formula of docs/math.md §2.
  const int i = 317, j = 845;
  const double u = i / 1000.0, v = j / 1000.0;
  const Eigen::RowVector3d expected = (1 - v) * b.bottom.row(i) + v * b.top.row(i) + (1 - u) * b.left.row(j) +
                                      u * b.right.row(j) -
                                      ((1 - u) * (1 - v) * b.bottom.row(0) + u * (1 - v) * b.bottom.row(1000) +
                                       (1 - u) * v * b.top.row(0) + u * v * b.top.row(1000));
  CHECK((net.at(i, j) - expected).norm() < 1e-13);
}
