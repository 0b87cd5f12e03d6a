#include "coons/tri/tri_energy.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "coons/tri/tri_solve.h"
#include "tri/tri_fixtures.h"

using namespace coons::tri;
using namespace coons::tri_test;

namespace {

double bernstein(int n, int i, int j, double x, double y) {
  const int k = n - i - j;
  return factorial(n) / (factorial(i) * factorial(j) * factorial(k)) * std::pow(x, i) * std::pow(y, j) *
         std::pow(1 - x - y, k);
}

// ∫_T f by the Duffy rule with enough nodes for degree `degree`.
template <class F>
double integrate(int degree, F&& f) {
  const TriQuadratureRule rule = duffy_gauss_legendre(degree / 2 + 2);
  double sum = 0;
  for (Eigen::Index q = 0; q < rule.weights.size(); ++q) sum += rule.weights(q) * f(rule.xy(q, 0), rule.xy(q, 1));
  return sum;
}

Eigen::Vector3d at(double x, double y) { return {x, y, 1 - x - y}; }

// ∂/∂x and ∂/∂y on the reference triangle, written out here independently of the library.
Eigen::Vector3d ex_minus_ez() { return {1, 0, -1}; }
Eigen::Vector3d ey_minus_ez() { return {0, 1, -1}; }

}  // namespace

TEST_CASE("duffy_gauss_legendre: integrates monomials exactly", "[tri]") {
  // ∫_T x^a y^b = a! b! / (a + b + 2)!
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; b <= 8 - a; ++b) {
      const double exact = factorial(a) * factorial(b) / factorial(a + b + 2);
      const TriQuadratureRule rule = duffy_gauss_legendre(5);  // exact to degree 8
      double sum = 0;
      for (Eigen::Index q = 0; q < rule.weights.size(); ++q)
        sum += rule.weights(q) * std::pow(rule.xy(q, 0), a) * std::pow(rule.xy(q, 1), b);
      REQUIRE(sum == Approx(exact).epsilon(1e-13));
    }
}

TEST_CASE("tri_bernstein_gram: equals quadrature of B_a B_b over the triangle", "[tri]") {
  for (int n = 0; n <= 10; ++n) {
    const Eigen::MatrixXd G = tri_bernstein_gram(n);
    REQUIRE((G - G.transpose()).norm() == 0.0);
    // Σ_β G_αβ = ∫ B_α = (1/2) / #points
    REQUIRE((G.rowwise().sum().array() - 0.5 / net_size(n)).abs().maxCoeff() < 1e-15);
    for (int k1 = 0; k1 <= n; ++k1)
      for (int j1 = 0; j1 <= n - k1; ++j1)
        for (int k2 = 0; k2 <= n; k2 += 2)
          for (int j2 = 0; j2 <= n - k2; ++j2) {
            const double q = integrate(2 * n, [&](double x, double y) {
              return bernstein(n, n - k1 - j1, j1, x, y) * bernstein(n, n - k2 - j2, j2, x, y);
            });
            REQUIRE(std::abs(G(net_index(n, j1, k1), net_index(n, j2, k2)) - q) < 1e-14);
          }
  }
}

TEST_CASE("tri energies: Dirichlet, thin plate and twist equal quadrature to 1e-11", "[tri]") {
  for (int n = 1; n <= 12; ++n) {
    const TriNet net = random_tri_net(n, 1500 + n);
    const double dirichlet = integrate(2 * n, [&](double x, double y) {
      return directional_derivative(net, at(x, y), ex_minus_ez()).squaredNorm() +
             directional_derivative(net, at(x, y), ey_minus_ez()).squaredNorm();
    });
    const double thin_plate = integrate(2 * n, [&](double x, double y) {
      return second_directional_derivative(net, at(x, y), ex_minus_ez(), ex_minus_ez()).squaredNorm() +
             2 * second_directional_derivative(net, at(x, y), ex_minus_ez(), ey_minus_ez()).squaredNorm() +
             second_directional_derivative(net, at(x, y), ey_minus_ez(), ey_minus_ez()).squaredNorm();
    });
    const Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
    const double twist = integrate(2 * n, [&](double x, double y) {
      double s = 0;
      for (int m = 0; m < 3; ++m)
        s += second_directional_derivative(net, at(x, y), e.col((m + 1) % 3) - e.col(m), e.col((m + 2) % 3) - e.col(m))
                 .squaredNorm();
      return s / 3;
    });
    const double pxy = integrate(2 * n, [&](double x, double y) {
      return second_directional_derivative(net, at(x, y), ex_minus_ez(), ey_minus_ez()).squaredNorm();
    });
    INFO("n = " << n);
    REQUIRE(std::abs(tri_dirichlet_energy(net) - dirichlet) < 1e-11 * (1 + dirichlet));
    REQUIRE(std::abs(tri_thin_plate_energy(net) - thin_plate) < 1e-11 * (1 + thin_plate));
    REQUIRE(std::abs(tri_twist_energy(net) - twist) < 1e-11 * (1 + twist));
    if (n >= 2) REQUIRE(std::abs(tri_twist_energy(net) - pxy) > 1e-6 * pxy);  // the symmetric twist is not ∫‖p_xy‖²
  }
}

TEST_CASE("tri_e3_energy: equals the exact integral of a random polynomial's third derivatives", "[tri]") {
  // p(x, y) = Σ_{a+b≤d} c_ab x^a y^b per coordinate, written at degree n ≥ d through the Bernstein
  // coefficients of a monomial, x^a y^b = Σ_α i!/(i−a)! · j!/(j−b)! · (n−a−b)!/n! B^n_α (zero unless
  // i ≥ a, j ≥ b), and E3 = ∫_T ‖p_xxx‖² + 3‖p_xxy‖² + 3‖p_xyy‖² + ‖p_yyy‖² from the monomials'
  // derivatives and ∫_T x^p y^q = p! q! / (p + q + 2)!: no derivative net and no Gram matrix.
  auto falling = [](int i, int a) { return a > i ? 0.0 : factorial(i) / factorial(i - a); };
  std::mt19937 rng(2100);
  std::uniform_real_distribution<double> dist(-1, 1);
  for (int d = 0; d <= 7; ++d)
    for (const int n : {std::max(d, 1), d + 2}) {
      std::vector<std::array<int, 2>> exponents;
      for (int a = 0; a <= d; ++a)
        for (int b = 0; a + b <= d; ++b) exponents.push_back({a, b});
      Eigen::MatrixX3d c(exponents.size(), 3);
      for (Eigen::Index r = 0; r < c.rows(); ++r)
        for (int q = 0; q < 3; ++q) c(r, q) = dist(rng);
      TriNet net(n);
      for (int k = 0; k <= n; ++k)
        for (int j = 0; j <= n - k; ++j)
          for (std::size_t e = 0; e < exponents.size(); ++e) {
            const auto [a, b] = exponents[e];
            const double w = falling(n - k - j, a) * falling(j, b) * factorial(n - a - b) / factorial(n);
            net.points.row(net_index(n, j, k)) += w * c.row(Eigen::Index(e));
          }
      // ∂x^r ∂y^s of x^a y^b = falling(a, r) falling(b, s) x^(a−r) y^(b−s)
      double exact = 0;
      for (const auto& [r, s, weight] : {std::tuple{3, 0, 1.0}, {2, 1, 3.0}, {1, 2, 3.0}, {0, 3, 1.0}})
        for (std::size_t e1 = 0; e1 < exponents.size(); ++e1)
          for (std::size_t e2 = 0; e2 < exponents.size(); ++e2) {
            const auto [a1, b1] = exponents[e1];
            const auto [a2, b2] = exponents[e2];
            const double f = falling(a1, r) * falling(b1, s) * falling(a2, r) * falling(b2, s);
            if (f == 0) continue;
            const int px = a1 + a2 - 2 * r, py = b1 + b2 - 2 * s;
            exact += weight * f * factorial(px) * factorial(py) / factorial(px + py + 2) *
                     c.row(Eigen::Index(e1)).dot(c.row(Eigen::Index(e2)));
          }
      INFO("polynomial degree " << d << ", net degree " << n);
      if (d < 3) {
        REQUIRE(exact == 0.0);
        REQUIRE(std::abs(tri_e3_energy(net)) < 1e-20 + 1e-12 * n * n);
      } else {
        REQUIRE(exact > 1);
        REQUIRE(tri_e3_energy(net) == Approx(exact).epsilon(1e-11));
      }
    }
}

TEST_CASE("tri_twist_energy: invariant under permutations of i, j, k (thin plate is not)", "[tri]") {
  const TriNet net = random_tri_net(6, 1600);
  bool thin_plate_changes = false;
  for (const auto& perm : all_permutations()) {
    const TriNet q = permuted(net, perm);
    REQUIRE(tri_twist_energy(q) == Approx(tri_twist_energy(net)).epsilon(1e-12));
    REQUIRE(tri_discrete_twist_energy(q) == Approx(tri_discrete_twist_energy(net)).epsilon(1e-12));
    if (std::abs(tri_thin_plate_energy(q) - tri_thin_plate_energy(net)) > 1e-6 * tri_thin_plate_energy(net))
      thin_plate_changes = true;
  }
  REQUIRE(thin_plate_changes);
}

TEST_CASE("tri energies: second-order energies vanish on affine patches, Dirichlet is the area term", "[tri]") {
  for (int n = 1; n <= 10; ++n) {
    const TriNet l = elevated_linear(n, 1700 + n);
    const TriNet base = random_tri_net(1, 1700 + n);
    const Eigen::RowVector3d px = base.at(1, 0, 0) - base.at(0, 0, 1), py = base.at(0, 1, 0) - base.at(0, 0, 1);
    REQUIRE(tri_dirichlet_energy(l) == Approx(0.5 * (px.squaredNorm() + py.squaredNorm())).epsilon(1e-12));
    REQUIRE(tri_discrete_dirichlet_energy(l) ==
            Approx(n * (n + 1) / 2.0 * (px.squaredNorm() + py.squaredNorm()) / (n * n)).epsilon(1e-12));
    REQUIRE(std::abs(tri_thin_plate_energy(l)) < 1e-20 + 1e-12 * n * n);
    REQUIRE(std::abs(tri_twist_energy(l)) < 1e-12 * n * n);
    REQUIRE(std::abs(tri_discrete_thin_plate_energy(l)) < 1e-24 + 1e-26 * n);
    REQUIRE(std::abs(tri_discrete_twist_energy(l)) < 1e-24 + 1e-26 * n);
    const TriNet r = random_tri_net(n + 1, 1750 + n);
    REQUIRE(tri_discrete_thin_plate_energy(r) > 1e-3);
  }
}

TEST_CASE("tri_net_metrics: the mask residual of a solved net is zero, of a random one not", "[tri]") {
  const TriNet net = random_tri_net(10, 1800);
  TriSolveOptions options;
  const TriNet solved = solve_tri_net(boundary_of(net), options).net;
  const TriNetMetrics m = tri_net_metrics(solved, options.mask);
  REQUIRE(m.mask_residual < 1e-12);
  REQUIRE(m.thin_plate_energy == Approx(tri_thin_plate_energy(solved)));
  REQUIRE(m.discrete_dirichlet_energy == Approx(tri_discrete_dirichlet_energy(solved)));
  REQUIRE(tri_net_metrics(net, options.mask).mask_residual > 1e-2);
}

TEST_CASE("tri energies: a model of 2^-532 (about 1e-160) or 2^400 has its energies times exactly 4^k", "[tri]") {
  // the products of a model of 1e-160 are subnormal (scaled_energy.h)
  const TriNet net = random_tri_net(5, 1601);
  for (const int k : {-532, 400}) {
    TriNet scaled = net;
    for (Eigen::Index q = 0; q < scaled.points.size(); ++q)
      scaled.points.data()[q] = std::ldexp(scaled.points.data()[q], k);
    INFO("k = " << k);
    CHECK(tri_dirichlet_energy(scaled) == std::ldexp(tri_dirichlet_energy(net), 2 * k));
    CHECK(tri_thin_plate_energy(scaled) == std::ldexp(tri_thin_plate_energy(net), 2 * k));
    CHECK(tri_twist_energy(scaled) == std::ldexp(tri_twist_energy(net), 2 * k));
    CHECK(tri_e3_energy(scaled) == std::ldexp(tri_e3_energy(net), 2 * k));
    CHECK(tri_discrete_dirichlet_energy(scaled) == std::ldexp(tri_discrete_dirichlet_energy(net), 2 * k));
    CHECK(tri_discrete_thin_plate_energy(scaled) == std::ldexp(tri_discrete_thin_plate_energy(net), 2 * k));
    CHECK(tri_discrete_twist_energy(scaled) == std::ldexp(tri_discrete_twist_energy(net), 2 * k));
    CHECK(tri_inner_product(scaled, net) == std::ldexp(tri_inner_product(net, net), k));
  }
}
