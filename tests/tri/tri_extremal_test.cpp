#include "coons/tri/tri_extremal.h"

#include <catch2/catch.hpp>

#include "coons/tri/tri_energy.h"
#include "coons/tri/tri_solve.h"
#include "tri/tri_fixtures.h"

using namespace coons::tri;
using namespace coons::tri_test;

namespace {

constexpr TriEnergy kKinds[] = {TriEnergy::kDirichlet, TriEnergy::kThinPlate, TriEnergy::kTwist};

double energy(const TriNet& net, const Eigen::MatrixXd& K) { return (net.points.transpose() * K * net.points).trace(); }

}  // namespace

TEST_CASE("tri_energy_hessian: P^T K P is the exact energy of tri_energy.h", "[tri]") {
  for (int n = 1; n <= 8; ++n) {
    const TriNet net = random_tri_net(n, 1900 + n);
    REQUIRE(energy(net, tri_energy_hessian(n, TriEnergy::kDirichlet)) ==
            Approx(tri_dirichlet_energy(net)).epsilon(1e-12));
    REQUIRE(energy(net, tri_energy_hessian(n, TriEnergy::kThinPlate)) ==
            Approx(tri_thin_plate_energy(net)).epsilon(1e-12).margin(1e-14));
    REQUIRE(energy(net, tri_energy_hessian(n, TriEnergy::kTwist)) ==
            Approx(tri_twist_energy(net)).epsilon(1e-12).margin(1e-14));
  }
}

TEST_CASE("TriDomain: the equilateral domain makes Dirichlet and thin plate symmetric in i, j, k", "[tri]") {
  const TriDomain eq = TriDomain::equilateral();
  REQUIRE(eq.area() == Approx(std::sqrt(3.0) / 4));
  const TriNet net = random_tri_net(5, 1950);
  for (const TriEnergy kind : {TriEnergy::kDirichlet, TriEnergy::kThinPlate}) {
    const Eigen::MatrixXd K = tri_energy_hessian(5, kind, eq), Kr = tri_energy_hessian(5, kind);
    bool right_changes = false;
    for (const auto& perm : all_permutations()) {
      REQUIRE(energy(permuted(net, perm), K) == Approx(energy(net, K)).epsilon(1e-12));
      if (std::abs(energy(permuted(net, perm), Kr) - energy(net, Kr)) > 1e-6 * energy(net, Kr)) right_changes = true;
    }
    REQUIRE(right_changes);
  }
}

TEST_CASE("minimize_tri_energy: the interior gradient vanishes and any change of the interior costs energy", "[tri]") {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (const TriEnergy kind : kKinds)
    for (const int n : {3, 5, 9}) {
      const TriNet net = random_tri_net(n, 2000 + n);
      const TriNet best = minimize_tri_energy(net, kind);
      REQUIRE(max_abs_difference(frame_net(boundary_of(best)), frame_net(boundary_of(net))) == 0.0);
      const Eigen::MatrixXd K = tri_energy_hessian(n, kind);
      const Eigen::MatrixX3d gradient = K * best.points;
      for (int k = 1; k <= n - 2; ++k)
        for (int j = 1; j <= n - 1 - k; ++j) REQUIRE(gradient.row(net_index(n, j, k)).norm() < 1e-9 * (1 + K.norm()));
      for (int trial = 0; trial < 5; ++trial) {
        Eigen::MatrixX3d D(interior_size(n), 3);
        for (Eigen::Index r = 0; r < D.size(); ++r) D.data()[r] = 1e-3 * normal(rng);
        REQUIRE(energy(fill_interior(best, interior_of(best) + D), K) > energy(best, K));
      }
    }
}

TEST_CASE("fit_tri_mask: finds the c of a solved net and -1/6 for a quadratic net", "[tri]") {
  for (const double c : {-0.16, 0.0, 0.2})
    for (const int n : {4, 9, 15}) {
      TriSolveOptions options;
      options.mask.c = c;
      const TriNet solved = solve_tri_net(boundary_of(random_tri_net(n, 2100 + n)), options).net;
      const TriMaskFit fit = fit_tri_mask(solved);
      REQUIRE(fit.determined);
      REQUIRE(fit.c == Approx(c).margin(1e-10));
      REQUIRE(fit.residual < 1e-10);
    }
  const TriMaskFit q = fit_tri_mask(elevated_quadratic(10, 4));
  REQUIRE(q.c == Approx(-1.0 / 6).margin(1e-12));
  REQUIRE(q.residual < 1e-13);
  REQUIRE(fit_tri_mask(random_tri_net(8, 5)).residual > 1e-2);
  REQUIRE_FALSE(fit_tri_mask(elevated_linear(6, 1)).determined);
}

TEST_CASE("minimize_tri_energy: equilateral cubic extremals are members c = 1/3, 1/12, 0, degree 4 and up are not",
          "[tri]") {
  // On the equilateral domain the cubic's centre of the Dirichlet extremal is (1/3)Σ corners (c = 1/3),
  // of the thin-plate one (1/8)Σ edges + (1/12)Σ corners (c = 1/12), of the twist (1/6)Σ edges (c = 0,
  // any domain). From degree 4 on no member of the family is an energy extremal.
  const TriDomain eq = TriDomain::equilateral();
  const double expected[] = {1.0 / 3, 1.0 / 12, 0.0};
  for (int q = 0; q < 3; ++q)
    for (std::uint32_t seed = 1; seed <= 5; ++seed) {
      const TriNet best = minimize_tri_energy(random_tri_net(3, 2200 + seed), kKinds[q], eq);
      const TriMaskFit fit = fit_tri_mask(best);
      REQUIRE(fit.c == Approx(expected[q]).margin(1e-10));
      REQUIRE(fit.residual < 1e-12);
    }
  for (const TriEnergy kind : kKinds)
    for (const int n : {4, 6, 10}) {
      const TriMaskFit fit = fit_tri_mask(minimize_tri_energy(random_tri_net(n, 2300 + n), kind, eq));
      INFO("n = " << n << ", best c = " << fit.c << ", residual " << fit.residual);
      REQUIRE(fit.residual > 1e-2);
    }
}

TEST_CASE(
    "minimize_tri_energy: none of the extremals has quadratic precision, the Dirichlet one has harmonic precision",
    "[tri]") {
  // (x² − y², 2xy, x + y) on the reference triangle: harmonic in every coordinate.
  TriNet harmonic(2);
  harmonic.at(2, 0, 0) = Eigen::RowVector3d(1, 0, 1);
  harmonic.at(0, 2, 0) = Eigen::RowVector3d(-1, 0, 1);
  harmonic.at(1, 1, 0) = Eigen::RowVector3d(0, 1, 1);
  harmonic.at(1, 0, 1) = Eigen::RowVector3d(0, 0, 0.5);
  harmonic.at(0, 1, 1) = Eigen::RowVector3d(0, 0, 0.5);
  const double x = 0.3, y = 0.5;
  REQUIRE((evaluate(harmonic, {x, y, 1 - x - y}) - Eigen::RowVector3d(x * x - y * y, 2 * x * y, x + y)).norm() < 1e-15);
  for (const int n : {3, 7, 12}) {
    const TriNet h = elevate_degree(harmonic, n - 2);
    REQUIRE(max_abs_difference(minimize_tri_energy(h, TriEnergy::kDirichlet), h) < 1e-10);
    const TriNet q = elevated_quadratic(n, 2400 + n);
    for (const TriEnergy kind : kKinds) REQUIRE(max_abs_difference(minimize_tri_energy(q, kind), q) > 1e-3);
  }
}
