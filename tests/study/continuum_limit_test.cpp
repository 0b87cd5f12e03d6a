// The Ritz minimisers of ∫∫‖p_uv‖² + μ∫∫‖∇p‖² and the optimal μ of the continuum problem
// (coons/study/continuum_limit.h).
#include "coons/study/continuum_limit.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/metrics/energies.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "support/fixtures.h"

using namespace coons;
using coons::test::make_random_net;
using coons::test::make_smooth_boundary;

namespace {

double binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  double c = 1;
  for (int r = 1; r <= k; ++r) c = c * (n - k + r) / r;
  return c;
}

//! The degree-(N, N) net of the surface (u, v, Σ c_kl u^k v^l), by u^k = Σ_i C(i,k)/C(N,k) B_i^N(u).
ControlNet polynomial_net(int N, const std::vector<std::tuple<int, int, double>>& z) {
  ControlNet net(N, N);
  for (int i = 0; i <= N; ++i)
    for (int j = 0; j <= N; ++j) {
      double h = 0;
      for (auto [k, l, c] : z) h += c * binomial(i, k) / binomial(N, k) * binomial(j, l) / binomial(N, l);
      net.at(i, j) = Eigen::RowVector3d(double(i) / N, double(j) / N, h);
    }
  return net;
}

}  // namespace

TEST_CASE("ContinuumProblem: reproduces a polynomial minimiser of the Euler-Lagrange equation", "[study]") {
  // z = u²v² − (u⁴ + v⁴)/6 + 2u²/μ0 satisfies z_uuvv = μ0·Δz = 4, and x = u, y = v are
  // harmonic with vanishing twist: the surface is the minimiser for μ = μ0 of its own boundary.
  const double mu0 = 3.0;
  for (int N : {4, 7, 12}) {
    const ControlNet exact = polynomial_net(N, {{2, 2, 1.0}, {4, 0, -1.0 / 6}, {0, 4, -1.0 / 6}, {2, 0, 2 / mu0}});
    const ContinuumProblem problem(boundary_of(exact));
    for (double u : {0.1, 0.37, 0.5, 0.8})
      for (double v : {0.2, 0.5, 0.9}) {
        const Eigen::RowVector3d d = problem.evaluate(mu0, u, v) - evaluate(exact, u, v);
        CHECK(d.norm() < 1e-11);
      }
    // and no other μ gives this surface: at μ = 10·μ0 the minimiser differs
    CHECK((problem.evaluate(10 * mu0, 0.5, 0.5) - evaluate(exact, 0.5, 0.5)).norm() > 1e-3);
  }
}

TEST_CASE("ContinuumProblem: the energies of the minimiser are the exact energies of its net", "[study]") {
  // With μ0 as above the minimiser is the polynomial net itself, whose exact energies coons
  // computes by Bernstein Gram matrices.
  const ControlNet exact = polynomial_net(6, {{2, 2, 1.0}, {4, 0, -1.0 / 6}, {0, 4, -1.0 / 6}, {2, 0, 1.0}});
  const ContinuumProblem problem(boundary_of(exact));
  CHECK(problem.energy(2.0, thin_plate_terms()) == Approx(thin_plate_energy(exact)).epsilon(1e-11));
  CHECK(problem.energy(2.0, e3_terms()) == Approx(e3_energy(exact)).epsilon(1e-10));
  CHECK(problem.energy(2.0, twist_terms()) == Approx(twist_energy(exact)).epsilon(1e-11));
}

TEST_CASE("ContinuumProblem: mu = 0 gives the bilinearly blended Coons patch, the twist minimiser", "[study]") {
  const Boundary b = make_smooth_boundary(6, 6, 3);
  const ContinuumProblem problem(b);
  const ControlNet coons = discrete_coons_net(b);
  for (double u : {0.15, 0.5, 0.7})
    for (double v : {0.3, 0.6}) CHECK((problem.evaluate(0, u, v) - evaluate(coons, u, v)).norm() < 1e-12);
  CHECK(problem.energy(0, twist_terms()) == Approx(twist_energy(coons)).epsilon(1e-12));
  CHECK(problem.energy(0, twist_terms()) < problem.energy(5, twist_terms()));
  CHECK(problem.energy(50, dirichlet_terms()) < problem.energy(0, dirichlet_terms()));
}

TEST_CASE("continuum_optimum: a boundary whose minimiser does not depend on μ is flat", "[study]") {
  // (u, v, u² − v²): harmonic and of vanishing twist, the minimiser for every μ
  const ControlNet saddle = polynomial_net(5, {{2, 0, 1.0}, {0, 2, -1.0}});
  const ContinuumOptimum o = continuum_optimum(ContinuumProblem(boundary_of(saddle)), thin_plate_terms());
  CHECK(o.status == ContinuumStatus::kFlat);
  CHECK(!o.mu);
}

TEST_CASE("continuum_optimum: the optimum is the least energy of a fine scan and converges in N", "[study]") {
  // a dome-like boundary: the frame of z = u(1−u)v(1−v)·(1 + u), elevated to each N
  std::vector<double> optima;
  for (int N : {8, 12, 16}) {
    const ControlNet net = polynomial_net(N, {{1, 1, 1.0}, {2, 1, -1.0}, {1, 2, -1.0}, {2, 2, 1.0}, {3, 3, 2.0}});
    const ContinuumProblem problem(boundary_of(net));
    const ContinuumOptimum o = continuum_optimum(problem, thin_plate_terms());
    REQUIRE(o.status == ContinuumStatus::kSuccess);
    REQUIRE(o.mu);
    for (double f : {0.9, 0.99, 1.01, 1.1}) CHECK(problem.energy(*o.mu * f, thin_plate_terms()) >= o.value);
    optima.push_back(*o.mu);
  }
  CHECK(std::abs(optima[2] - optima[1]) <= std::abs(optima[1] - optima[0]) + 1e-9 * optima[2]);
  CHECK(std::abs(optima[2] - optima[1]) < 1e-3 * optima[2]);
}

TEST_CASE("continuum_optimum: the weights of the energy do not change the optimum", "[study]") {
  // w·E has the optimum of E, for every weight of an objective (1e-60 … 1e60): the flatness floor
  // was in units of the boundary only, so 1e-20*thin_plate was called flat (degree-limit printed
  // mu_continuum null for the dome).
  const ControlNet net = polynomial_net(8, {{1, 1, 1.0}, {2, 1, -1.0}, {1, 2, -1.0}, {2, 2, 1.0}, {3, 3, 2.0}});
  const ContinuumProblem problem(boundary_of(net));
  const ContinuumOptimum one = continuum_optimum(problem, thin_plate_terms());
  REQUIRE(one.status == ContinuumStatus::kSuccess);
  for (const double w : {1e-60, 1e-20, 1e20, 1e60}) {
    INFO("weight " << w);
    std::vector<EnergyTerm> terms = thin_plate_terms();
    for (EnergyTerm& t : terms) t.weight *= w;
    const ContinuumOptimum o = continuum_optimum(problem, terms);
    CHECK(o.status == ContinuumStatus::kSuccess);
    REQUIRE(o.mu);
    CHECK(*o.mu == Approx(*one.mu).epsilon(1e-6));
    CHECK(o.value == Approx(one.value * w).epsilon(1e-12));
  }
}

TEST_CASE("exact_energy_mu: agrees with the exact gradients of the energies' bilinear forms", "[study]") {
  const ControlNet net = make_random_net(5, 4, 11);
  const auto mu = exact_energy_mu(net);
  REQUIRE(mu);
  // g_tw + μ g_D ⟂ g_D on the interior, with g(i, j, c) = 2·form(net, unit net at (i, j, c))
  double dot = 0;
  for (int i = 1; i < 5; ++i)
    for (int j = 1; j < 4; ++j)
      for (int c = 0; c < 3; ++c) {
        ControlNet e(5, 4);
        e.at(i, j)(c) = 1;
        const double gt = 2 * surface_energy_form(net, e, 1, 1);
        const double gd = 2 * (surface_energy_form(net, e, 1, 0) + surface_energy_form(net, e, 0, 1));
        dot += (gt + *mu * gd) * gd;
      }
  CHECK(std::abs(dot) < 1e-8);
  CHECK(!exact_energy_mu(ControlNet(1, 4)));
}
