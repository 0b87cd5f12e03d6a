#include "coons/mask/nonuniform_mask.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "coons/mask/mask_residual.h"
#include "coons/study/bspline_net.h"
#include "coons/surfaces/bspline_surface.h"
#include "solvers/registry.h"
#include "support/bspline_fixtures.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

Eigen::VectorXd greville_of(int degree, const Eigen::VectorXd& knots) {
  const int count = int(knots.size()) - degree - 1;
  return greville_abscissae(BSplineCurve(degree, knots, Eigen::MatrixX3d::Zero(count, 3)));
}

// The frame of a random net (interior zero).
ControlNet random_frame(int m, int n, std::uint32_t seed) {
  return frame_net(boundary_of(make_random_net(m, n, seed)));
}

double sparse_distance(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& B) {
  return Eigen::MatrixXd(A - B).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("assemble_nonuniform_mask_system: on equally spaced abscissae is the mask family of docs/math.md §3",
          "[mask][bspline]") {
  // Equally spaced Greville abscissae: the Bézier knot vector of one segment (ξ_i = i/p), and a
  // clamped spline whose knots are not Bézier but whose abscissae are still equally spaced
  // (degree 2, knots 0 0 0 2 2 4 4 4: ξ = 0, 1, 2, 3, 4 over [0, 4]; degree 1, uniform knots).
  Eigen::VectorXd two_pieces(8);
  two_pieces << 0, 0, 0, 2, 2, 4, 4, 4;
  Eigen::VectorXd linear(8);
  linear << 0, 0, 1, 2, 3, 4, 5, 5;
  const GrevilleGrid grids[] = {
      {greville_of(5, bezier_knots(5)), greville_of(3, bezier_knots(3))},
      {greville_of(2, two_pieces) / 4.0, greville_of(1, linear) / 5.0},
      {greville_of(1, linear) / 5.0, greville_of(4, bezier_knots(4))},
  };
  for (const GrevilleGrid& grid : grids)
    for (const double alpha : {-0.25, -0.1, 0.0, 0.2}) {
      const ControlNet frame = random_frame(grid.m(), grid.n(), 7);
      const NonUniformMaskSystem nonuniform = assemble_nonuniform_mask_system(frame, grid, alpha);
      const MaskSystem uniform = assemble_mask_system(frame, alpha_mask(alpha));
      INFO("m = " << grid.m() << ", n = " << grid.n() << ", alpha = " << alpha);
      REQUIRE(nonuniform.A.rows() == uniform.A.rows());
      CHECK(sparse_distance(nonuniform.A, uniform.A) < 1e-12);
      CHECK((nonuniform.B - uniform.B).cwiseAbs().maxCoeff() < 1e-12);
    }
}

TEST_CASE("assemble_nonuniform_mask_system: symmetric, positive definite for alpha in [-1/4, 0], affine in alpha",
          "[mask][bspline]") {
  const GrevilleGrid grid{greville_of(3, make_random_knots(3, 9, 11)), greville_of(2, make_random_knots(2, 6, 12))};
  const ControlNet frame = random_frame(grid.m(), grid.n(), 13);
  for (const double alpha : {-0.25, -0.2, -0.1, 0.0}) {
    const NonUniformMaskSystem s = assemble_nonuniform_mask_system(frame, grid, alpha);
    const Eigen::MatrixXd A(s.A);
    CHECK((A - A.transpose()).cwiseAbs().maxCoeff() < 1e-12 * A.cwiseAbs().maxCoeff());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
    CHECK(eig.eigenvalues().minCoeff() > 0);
    const NonUniformMaskSystem next = assemble_nonuniform_mask_system(frame, grid, alpha + 0.01);
    CHECK(sparse_distance(next.A, s.A + 0.01 * s.dA) < 1e-12);
    CHECK((next.B - s.B - 0.01 * s.dB).cwiseAbs().maxCoeff() < 1e-12);
  }
}

TEST_CASE("solve_nonuniform_mask_net: alpha = -1/4 reproduces the Greville-weighted Coons net", "[mask][bspline]") {
  auto solver = solvers::make_solver("eigen-ldlt");
  int checked = 0;
  for (int p = 1; p <= 4; ++p)
    for (int q = 1; q <= 3; ++q) {
      const BSplineBoundary b =
          compatible_boundary(make_random_bspline_boundary(p, p + 3 + q, q, q + 5, std::uint32_t(100 + 10 * p + q)));
      const BSplineSurface coons = greville_coons_surface(b);
      const NonUniformSolveResult solved =
          solve_nonuniform_mask_net(bspline_frame(b), greville_grid(b), -0.25, *solver);
      REQUIRE(solved.summary.ok());
      INFO("p = " << p << ", q = " << q);
      CHECK((solved.net.points - coons.net.points).cwiseAbs().maxCoeff() < 1e-10);
      CHECK(nonuniform_mask_residual(coons.net, greville_grid(b), -0.25) < 1e-12);
      ++checked;
    }
  CHECK(checked == 12);
}

TEST_CASE("solve_nonuniform_mask_net: linear precision (bilinear data in the Greville abscissae is reproduced)",
          "[mask][bspline]") {
  // b_ij = c + ξ_i a + η_j d + ξ_i η_j e on the frame: every member of the family keeps it inside,
  // and the surface of the net is then the bilinear function of (u, v) itself.
  const Eigen::VectorXd knots_u = make_random_knots(3, 8, 21), knots_v = make_random_knots(2, 6, 22);
  const GrevilleGrid grid{greville_of(3, knots_u), greville_of(2, knots_v)};
  const Eigen::RowVector3d c(0.3, -1, 2), a(1, 0.5, -0.2), d(-0.4, 1, 0.7), e(0.2, 0.1, 1.5);
  const auto f = [&](double u, double v) -> Eigen::RowVector3d { return c + u * a + v * d + u * v * e; };
  ControlNet exact(grid.m(), grid.n());
  for (int i = 0; i <= grid.m(); ++i)
    for (int j = 0; j <= grid.n(); ++j) exact.at(i, j) = f(grid.xi(i), grid.eta(j));
  auto solver = solvers::make_solver("eigen-lu");
  for (const double alpha : {-0.25, -0.1, 0.0, 0.15}) {
    const NonUniformSolveResult r = solve_nonuniform_mask_net(frame_net(boundary_of(exact)), grid, alpha, *solver);
    REQUIRE(r.summary.ok());
    CHECK((r.net.points - exact.points).cwiseAbs().maxCoeff() < 1e-12);
    const BSplineSurface s{3, 2, knots_u, knots_v, r.net};
    for (const double u : {0.0, 0.13, 0.5, 0.91})
      for (const double v : {0.0, 0.37, 0.77, 1.0}) CHECK((evaluate(s, u, v) - f(u, v)).norm() < 1e-12);
  }
}

TEST_CASE("solve_nonuniform_mask_net: the derivative in alpha matches central differences", "[mask][bspline]") {
  const BSplineBoundary b = compatible_boundary(make_random_bspline_boundary(3, 7, 2, 6, 31));
  const GrevilleGrid grid = greville_grid(b);
  auto solver = solvers::make_solver("eigen-lu");
  const double alpha = -0.12, h = 1e-5;
  const NonUniformSolveResult at = solve_nonuniform_mask_net(bspline_frame(b), grid, alpha, *solver, true);
  const NonUniformSolveResult plus = solve_nonuniform_mask_net(bspline_frame(b), grid, alpha + h, *solver);
  const NonUniformSolveResult minus = solve_nonuniform_mask_net(bspline_frame(b), grid, alpha - h, *solver);
  const Eigen::MatrixX3d central = (plus.net.points - minus.net.points) / (2 * h);
  CHECK(at.derivative.points.cwiseAbs().maxCoeff() > 1e-3);
  CHECK((at.derivative.points - central).cwiseAbs().maxCoeff() < 1e-6);
}

TEST_CASE("nonuniform_mask_residual: on equal spacing is mask_residual, zero for the solved net", "[mask][bspline]") {
  const ControlNet net = make_random_net(4, 6, 41);
  const GrevilleGrid grid{greville_of(4, bezier_knots(4)), greville_of(6, bezier_knots(6))};
  for (const double alpha : {-0.25, 0.0, 0.1})
    CHECK(nonuniform_mask_residual(net, grid, alpha) == Approx(mask_residual(net, alpha_mask(alpha))).epsilon(1e-12));
  const GrevilleGrid uneven{greville_of(3, make_random_knots(3, 7, 42)), greville_of(2, make_random_knots(2, 5, 43))};
  auto solver = solvers::make_solver("eigen-lu");
  const NonUniformSolveResult r = solve_nonuniform_mask_net(random_frame(6, 4, 44), uneven, 0.0, *solver);
  REQUIRE(r.summary.ok());
  CHECK(nonuniform_mask_residual(r.net, uneven, 0.0) < 1e-12);
  CHECK(nonuniform_mask_residual(r.net, uneven, -0.25) > 1e-6);
}

TEST_CASE(
    "nonuniform_mask_residual: each equation divided by its largest weight, so a net correct to rounding reads about "
    "eps on short knot spans",
    "[mask][bspline]") {
  // two knot spans of 2e−9 along u: weights of order 1e17 there
  Eigen::VectorXd knots_u(11);
  knots_u << 0, 0, 0, 0, 2e-9, 4e-9, 0.45, 1, 1, 1, 1;
  const GrevilleGrid grid{greville_of(3, knots_u), greville_of(2, make_random_knots(2, 5, 45))};
  const ControlNet frame = random_frame(int(grid.xi.size()) - 1, int(grid.eta.size()) - 1, 46);
  auto solver = solvers::make_solver("eigen-lu");
  for (const double alpha : {-0.25, 0.0}) {
    CAPTURE(alpha);
    const NonUniformSolveResult r = solve_nonuniform_mask_net(frame, grid, alpha, *solver);
    REQUIRE(r.summary.ok());
    double unscaled = 0, largest_weight = 0;  // the residual without the division, and the weights' size
    for (int i = 1; i < r.net.m; ++i)
      for (int j = 1; j < r.net.n; ++j) {
        const Eigen::Matrix3d w = nonuniform_mask_weights(grid, alpha, i, j);
        largest_weight = std::max(largest_weight, w.cwiseAbs().maxCoeff());
        Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
        for (int k = -1; k <= 1; ++k)
          for (int l = -1; l <= 1; ++l) sum += w(k + 1, l + 1) * r.net.at(i + k, j + l);
        unscaled = std::max(unscaled, sum.cwiseAbs().maxCoeff());
      }
    CHECK(largest_weight > 1e15);
    CHECK(unscaled > 1e-2);  // rounding of the net times weights of 1e17
    CHECK(nonuniform_mask_residual(r.net, grid, alpha) < 1e-13);
  }
}
