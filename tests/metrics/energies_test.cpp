#include "coons/metrics/energies.h"

#include <catch2/catch.hpp>
#include <random>

#include "coons/io/boundary_io.h"
#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask_residual.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "coons/net/quadrature.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// ∫∫ ‖∂^a_u ∂^b_v p‖² by Gauss–Legendre with enough nodes to be exact, derivatives from the
// textbook Bernstein derivative formula (independent of derivative_net and the Gram matrices).
double quadrature_energy(const ControlNet& net, int a, int b) {
  const QuadratureRule q = gauss_legendre(std::max(net.m, net.n) + 2);
  double e = 0;
  for (int s = 0; s < q.nodes.size(); ++s)
    for (int t = 0; t < q.nodes.size(); ++t) {
      const Eigen::VectorXd bu = bernstein_basis_derivative(net.m, a, q.nodes(s));
      const Eigen::VectorXd bv = bernstein_basis_derivative(net.n, b, q.nodes(t));
      Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
      for (int i = 0; i <= net.m; ++i)
        for (int j = 0; j <= net.n; ++j) d += bu(i) * bv(j) * net.at(i, j);
      e += q.weights(s) * q.weights(t) * d.squaredNorm();
    }
  return e;
}

// The energy as it was computed before the banded products: dense Gram matrices around each
// derivative net, Σ_xyz sum((G_u C G_v) ∘ C).
double dense_gram_energy(const ControlNet& net, int a, int b) {
  if (a > net.m || b > net.n) return 0;
  const ControlNet d = derivative_net(net, a, b);
  const Eigen::MatrixXd Gu = bernstein_gram(d.m), Gv = bernstein_gram(d.n);
  double e = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd C = coordinate_grid(d, c);
    e += ((Gu * C) * Gv).cwiseProduct(C).sum();
  }
  return e;
}

}  // namespace

TEST_CASE("net_metrics: the dense Gram products' energies to 1e-12", "[metrics]") {
  std::uint32_t seed = 21;
  for (auto [m, n] : {std::pair{1, 2}, {3, 3}, {5, 9}, {17, 12}, {40, 33}}) {
    INFO("m = " << m << ", n = " << n);
    const ControlNet net = make_random_net(m, n, seed++);
    const auto E = [&net](int a, int b) { return dense_gram_energy(net, a, b); };
    const NetMetrics metrics = net_metrics(net, alpha_mask(-0.2));
    CHECK(metrics.twist_energy == Approx(E(1, 1)).epsilon(1e-12));
    CHECK(metrics.dirichlet_energy == Approx(E(1, 0) + E(0, 1)).epsilon(1e-12));
    CHECK(metrics.thin_plate_energy == Approx(E(2, 0) + 2 * E(1, 1) + E(0, 2)).epsilon(1e-12));
    CHECK(metrics.e3_energy == Approx(E(3, 0) + 3 * E(2, 1) + 3 * E(1, 2) + E(0, 3)).epsilon(1e-12));
    const ControlNet other = make_random_net(m, n, seed + 100);
    for (int a = 0; a <= 3; ++a)
      for (int b = 0; a + b <= 3; ++b) {
        INFO("a = " << a << ", b = " << b);
        CHECK(surface_energy(net, a, b) == Approx(E(a, b)).epsilon(1e-12).margin(1e-300));
        // the bilinear form: E(X + Y) = E(X) + 2 form(X, Y) + E(Y)
        ControlNet sum = net;
        sum.points += other.points;
        const double form = (dense_gram_energy(sum, a, b) - E(a, b) - dense_gram_energy(other, a, b)) / 2;
        CHECK(surface_energy_form(net, other, a, b) ==
              Approx(form).epsilon(1e-9).margin(1e-9 * (E(a, b) + dense_gram_energy(other, a, b))));
      }
  }
}

TEST_CASE("net_metrics: the same metrics bit for bit on 1, 2 and 3 threads", "[metrics]") {
  // 301 x 281 points: products big enough to be shared out (banded_gram.h)
  const ControlNet net = make_random_net(300, 280, 5);
  const NetMetrics one = net_metrics(net, alpha_mask(-0.1));
  REQUIRE(one.e3_energy > 0);
  for (int threads : {2, 3}) {
    INFO("threads = " << threads);
    const NetMetrics many = net_metrics(net, alpha_mask(-0.1), threads);
    CHECK(many.twist_energy == one.twist_energy);
    CHECK(many.dirichlet_energy == one.dirichlet_energy);
    CHECK(many.thin_plate_energy == one.thin_plate_energy);
    CHECK(many.e3_energy == one.e3_energy);
    CHECK(many.mask_residual == one.mask_residual);
  }
}

TEST_CASE("gauss_legendre: integrates polynomials of degree 2k-1 exactly", "[metrics]") {
  for (int k = 1; k <= 12; ++k) {
    const QuadratureRule q = gauss_legendre(k);
    CHECK(q.weights.sum() == Approx(1).epsilon(1e-14));
    for (int d = 0; d <= 2 * k - 1; ++d) {
      double sum = 0;
      for (int r = 0; r < k; ++r) sum += q.weights(r) * std::pow(q.nodes(r), d);
      CHECK(sum == Approx(1.0 / (d + 1)).epsilon(1e-13));
    }
  }
}

TEST_CASE("surface_energy: equals Gauss-Legendre quadrature for every (a, b)", "[metrics]") {
  std::uint32_t seed = 3;
  for (auto [m, n] : {std::pair{1, 1}, {2, 2}, {3, 5}, {6, 4}, {7, 7}}) {
    const ControlNet net = make_random_net(m, n, seed++);
    for (int a = 0; a <= 3; ++a)
      for (int b = 0; a + b <= 3; ++b) {
        INFO("m = " << m << ", n = " << n << ", a = " << a << ", b = " << b);
        const double exact = surface_energy(net, a, b), quad = quadrature_energy(net, a, b);
        CHECK(exact == Approx(quad).epsilon(1e-11).margin(1e-12));
      }
    const NetMetrics metrics = net_metrics(net, alpha_mask(-0.25));
    CHECK(metrics.twist_energy == Approx(quadrature_energy(net, 1, 1)).epsilon(1e-11).margin(1e-12));
    CHECK(metrics.dirichlet_energy ==
          Approx(quadrature_energy(net, 1, 0) + quadrature_energy(net, 0, 1)).epsilon(1e-11));
    CHECK(metrics.thin_plate_energy ==
          Approx(quadrature_energy(net, 2, 0) + 2 * quadrature_energy(net, 1, 1) + quadrature_energy(net, 0, 2))
              .epsilon(1e-11)
              .margin(1e-12));
    CHECK(metrics.e3_energy == Approx(quadrature_energy(net, 3, 0) + 3 * quadrature_energy(net, 2, 1) +
                                      3 * quadrature_energy(net, 1, 2) + quadrature_energy(net, 0, 3))
                                   .epsilon(1e-11)
                                   .margin(1e-12));
    CHECK(metrics.twist_energy == twist_energy(net));
    CHECK(metrics.thin_plate_energy == Approx(thin_plate_energy(net)).epsilon(1e-15));
    CHECK(metrics.e3_energy == Approx(e3_energy(net)).epsilon(1e-15));
    CHECK(metrics.dirichlet_energy == Approx(dirichlet_energy(net)).epsilon(1e-15));
  }
}

TEST_CASE("bernstein_gram: exact at low degree, consistent at high degree", "[metrics]") {
  // G^1 = [[1/3, 1/6], [1/6, 1/3]]; rows of G^k sum to 1/(k+1).
  const Eigen::MatrixXd G1 = bernstein_gram(1);
  CHECK(G1(0, 0) == 1.0 / 3);
  CHECK(G1(0, 1) == 1.0 / 6);
  for (int k : {5, 30, 31, 200, 510, 511, 1200}) {
    const Eigen::MatrixXd G = bernstein_gram(k);
    INFO("k = " << k);
    const double tolerance = k <= 510 ? 1e-13 : 1e-11;  // Pascal's rule, then log-binomials
    CHECK((G.rowwise().sum().array() - 1.0 / (k + 1)).abs().maxCoeff() < tolerance / (k + 1));
    CHECK((G - G.transpose()).cwiseAbs().maxCoeff() == 0);
  }
}

TEST_CASE("net_metrics: seed example 1 reference values (twist 0, Dirichlet 20/3, thin plate 8)", "[metrics][seed]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/seed_example1.json").boundary;
  const NetMetrics metrics = net_metrics(discrete_coons_net(b), alpha_mask(-0.25));
  CHECK(metrics.twist_energy == Approx(0).margin(1e-14));
  CHECK(metrics.dirichlet_energy == Approx(20.0 / 3).epsilon(1e-14));
  CHECK(metrics.thin_plate_energy == Approx(8).epsilon(1e-14));
  CHECK(metrics.mask_residual < 1e-15);
}

TEST_CASE("net_metrics: the dome table of docs/math.md §7", "[metrics][seed]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/dome.json").boundary;
  struct Row {
    double alpha, thin_plate, dirichlet;
  };
  for (const Row& row :
       {Row{-0.25, 24.787, 9.877}, Row{-0.20, 18.320, 9.320}, Row{-0.10, 13.990, 8.794}, Row{0.0, 13.444, 8.571}}) {
    const MaskSolveResult r = solve_mask_net(b, alpha_mask(row.alpha), backend("eigen-ldlt"));
    INFO("alpha = " << row.alpha);
    CHECK(thin_plate_energy(r.net) == Approx(row.thin_plate).margin(5e-4));
    CHECK(dirichlet_energy(r.net) == Approx(row.dirichlet).margin(5e-4));
  }
}

TEST_CASE("discrete_coons_net: smallest discrete and continuous twist among perturbations", "[metrics]") {
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0, 1);
  for (auto [m, n] : {std::pair{3, 3}, {4, 6}, {8, 5}}) {
    const ControlNet coons = discrete_coons_net(make_random_boundary(m, n, 23));
    const double td = discrete_twist_energy(coons), tc = twist_energy(coons);
    for (int trial = 0; trial < 50; ++trial) {
      Eigen::MatrixX3d X = interior_of(coons);
      const double scale = std::pow(10.0, -trial % 6);
      for (Eigen::Index r = 0; r < X.rows(); ++r)
        for (int c = 0; c < 3; ++c) X(r, c) += scale * noise(rng);
      const ControlNet perturbed = fill_interior(coons, X);
      INFO("m = " << m << ", n = " << n << ", trial " << trial);
      CHECK(discrete_twist_energy(perturbed) > td);
      CHECK(twist_energy(perturbed) > tc);
    }
  }
}

TEST_CASE("mask_residual: zero for the solved mask, non-zero for another", "[metrics]") {
  const Boundary b = make_random_boundary(6, 6, 8);
  const ControlNet net = solve_mask_net(b, alpha_mask(-0.1), backend("eigen-ldlt")).net;
  CHECK(mask_residual(net, alpha_mask(-0.1)) < 1e-14);
  CHECK(mask_residual(net, alpha_mask(0.1)) > 1e-3);
}

TEST_CASE("discrete energies: a blend w*T_d + (1-w)*D_d is minimised by alpha = -w/4", "[metrics]") {
  const Boundary b = make_random_boundary(5, 7, 31);
  for (double w : {0.0, 0.4, 1.0}) {
    const ControlNet best = solve_mask_net(b, alpha_mask(-w / 4), backend("eigen-ldlt")).net;
    auto energy = [&](const ControlNet& net) {
      return w * discrete_twist_energy(net) + (1 - w) * discrete_dirichlet_energy(net);
    };
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0, 1e-3);
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::MatrixX3d X = interior_of(best);
      for (Eigen::Index r = 0; r < X.rows(); ++r)
        for (int c = 0; c < 3; ++c) X(r, c) += noise(rng);
      CHECK(energy(fill_interior(best, X)) > energy(best));
    }
  }
}

TEST_CASE("difference_terms: sum to discrete_energy_form", "[metrics]") {
  for (auto [m, n] : {std::pair{1, 1}, {2, 5}, {6, 4}, {9, 9}}) {
    const ControlNet X = make_random_net(m, n, 3), Y = make_random_net(m, n, 4);
    for (DiscreteEnergy kind : {DiscreteEnergy::kTwist, DiscreteEnergy::kDirichlet, DiscreteEnergy::kThinPlate}) {
      double e = 0;  // Σ w Σ (Δ_i^a Δ_j^b X)·(Δ_i^a Δ_j^b Y), by loops over the whole grid
      for (const DifferenceTerm& t : difference_terms(kind))
        for (int i = 0; i + t.i_order <= m; ++i)
          for (int j = 0; j + t.j_order <= n; ++j) {
            auto difference = [&](const ControlNet& N) {
              static const double c[3][3] = {{1, 0, 0}, {-1, 1, 0}, {1, -2, 1}};  // Δ^0, Δ^1, Δ^2
              Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
              for (int a = 0; a <= t.i_order; ++a)
                for (int b = 0; b <= t.j_order; ++b) d += c[t.i_order][a] * c[t.j_order][b] * N.at(i + a, j + b);
              return d;
            };
            e += t.weight * difference(X).dot(difference(Y));
          }
      INFO(m << "x" << n << " kind " << int(kind));
      CHECK(e == Approx(discrete_energy_form(X, Y, kind)).epsilon(1e-12).margin(1e-12));
    }
  }
}

TEST_CASE("surface_energy: never below 0 where it is 0 in exact arithmetic (bilinear nets, the pillow's Coons net)",
          "[metrics]") {
  // Every E(a, b) with a ≥ 2 or b ≥ 2 of a bilinear net is 0; its points are rounded, so the
  // computed energies are rounding noise of either sign before the clamp (−2.6e-32 for
  // E(2,0) + E(0,2) at degree (4, 2), seed 1).
  const std::vector<std::pair<int, int>> zero_pairs = {{2, 0}, {0, 2}, {3, 0}, {2, 1}, {1, 2}, {0, 3}};
  for (int m = 2; m < 12; ++m)
    for (int n = 2; n < 12; ++n)
      for (std::uint32_t seed = 0; seed < 5; ++seed) {
        const ControlNet net = make_bilinear_net(m, n, seed);
        INFO("degree " << m << "x" << n << ", seed " << seed);
        for (const auto& [a, b] : zero_pairs) {
          const double e = surface_energy(net, a, b);
          CHECK(e >= 0);
          CHECK(e < 1e-20);
        }
        CHECK(e3_energy(net) >= 0);
        CHECK(net_metrics(net, alpha_mask(-0.25)).e3_energy >= 0);
      }
  // The pillow's sides are cubic arcs of a quadratic surface: its Coons net has e3 = 0 (the study
  // printed −5.5e-32 for it at α = −1/4 before the clamp).
  const Boundary pillow = read_boundary_file(COONS_DATA_DIR "/boundaries/pillow.json").boundary;
  for (const char* name : {"eigen-ldlt", "eigen-lu", "fast", "dst"}) {
    if (!solvers::find_solver(name)) continue;
    const ControlNet net = solve_mask_net(pillow, alpha_mask(-0.25), backend(name)).net;
    INFO(name);
    CHECK(e3_energy(net) >= 0);
    CHECK(e3_energy(net) < 1e-20);
    CHECK(combined_energy(net, e3_terms()) >= 0);
  }
}

TEST_CASE("e3_energy: exactly 0 for a net with exact points and zero energy", "[metrics]") {
  // A bilinear net over integer corners at degree (4, 8): every point is a dyadic rational.
  ControlNet net(4, 8);
  const Eigen::RowVector3d p00(0, 0, 0), p10(4, 0, 1), p01(0, 8, -2), p11(4, 8, 3);
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 8; ++j) {
      const double u = i / 4.0, v = j / 8.0;
      net.at(i, j) = (1 - u) * (1 - v) * p00 + u * (1 - v) * p10 + (1 - u) * v * p01 + u * v * p11;
    }
  CHECK(e3_energy(net) == 0.0);
  CHECK(surface_energy(net, 2, 0) == 0.0);
  CHECK(surface_energy(net, 0, 2) == 0.0);
  CHECK(twist_energy(net) > 0);  // the twist of a hyperbolic paraboloid is not
}

TEST_CASE("clamp_rounding_negative: zeroes only a negative value within the bound", "[metrics]") {
  CHECK(clamp_rounding_negative(-1e-30, 1e-20) == 0.0);
  CHECK(clamp_rounding_negative(-1e-20, 1e-20) == 0.0);
  CHECK(clamp_rounding_negative(-1e-3, 1e-20) == -1e-3);  // a wrong sign still shows
  CHECK(clamp_rounding_negative(-1e-30, 0) == -1e-30);
  CHECK(clamp_rounding_negative(2.5, 1e-20) == 2.5);
  CHECK(clamp_rounding_negative(1e-30, 1.0) == 1e-30);
  // The clamp is applied to each E(a, b) of one net, not to a weighted sum: a negative weight shows.
  const ControlNet net = make_random_net(5, 4, 3);
  const double twist = twist_energy(net);
  REQUIRE(twist > 1);
  CHECK(combined_energy(net, {{1, 1, -1.0}}) == Approx(-twist).epsilon(1e-14));
}

TEST_CASE("net_metrics: a model of 2^-532 (about 1e-160) or 2^400 has its energies times exactly 4^k", "[metrics]") {
  // At 1e-160 the products of the energies were subnormal: the twist energy came out 1.6 % off.
  const ControlNet net = make_random_net(4, 5, 77);
  const Mask9 mask = alpha_mask(-0.1);
  const NetMetrics unit = net_metrics(net, mask);
  for (const int k : {-532, -520, 400}) {
    ControlNet scaled = net;
    for (Eigen::Index q = 0; q < scaled.points.size(); ++q)
      scaled.points.data()[q] = std::ldexp(scaled.points.data()[q], k);
    INFO("k = " << k);
    const NetMetrics s = net_metrics(scaled, mask);
    CHECK(s.twist_energy == std::ldexp(unit.twist_energy, 2 * k));
    CHECK(s.thin_plate_energy == std::ldexp(unit.thin_plate_energy, 2 * k));
    CHECK(s.dirichlet_energy == std::ldexp(unit.dirichlet_energy, 2 * k));
    CHECK(s.e3_energy == std::ldexp(unit.e3_energy, 2 * k));
    CHECK(s.discrete_twist_energy == std::ldexp(unit.discrete_twist_energy, 2 * k));
    CHECK(s.discrete_dirichlet_energy == std::ldexp(unit.discrete_dirichlet_energy, 2 * k));
    CHECK(twist_energy(scaled) == std::ldexp(twist_energy(net), 2 * k));
    CHECK(surface_energy(scaled, 2, 1) == std::ldexp(surface_energy(net, 2, 1), 2 * k));
    CHECK(discrete_thin_plate_energy(scaled) == std::ldexp(discrete_thin_plate_energy(net), 2 * k));
    // a form of two nets of different scales: 2^k from one, 2^0 from the other
    const ControlNet other = make_random_net(4, 5, 78);
    CHECK(surface_energy_form(scaled, other, 1, 1) == std::ldexp(surface_energy_form(net, other, 1, 1), k));
    CHECK(combined_energy_form(other, scaled, e3_terms()) ==
          std::ldexp(combined_energy_form(other, net, e3_terms()), k));
    CHECK(discrete_energy_form(scaled, other, DiscreteEnergy::kDirichlet) ==
          std::ldexp(discrete_energy_form(net, other, DiscreteEnergy::kDirichlet), k));
  }
}
