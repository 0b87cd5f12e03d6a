// The named stencils: their weights, the C1 family as the Euler–Lagrange operator of its energy
// (from the exact Hessian of the energy, not from the header's algebra), symbols and factors.
#include "coons/mask/stencil.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "mask/stencil_reference.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The energy E of one scalar coordinate is a quadratic form xᵀHx; the Hessian row of the point
// (c, c) of a (2c+1)² net, H(p, q) = E(e_p + e_q) − E(e_p) − E(e_q) (exact for a quadratic form),
// divided by H(p, p): the stencil of the Euler–Lagrange equations at a point far from the edge.
template <class Energy>
Eigen::MatrixXd hessian_stencil(Energy energy, int radius) {
  const int c = 4, size = 2 * c;
  auto unit = [&](int i, int j, int k, int l) {
    ControlNet net(size, size);
    net.at(i, j)(0) += 1;
    net.at(k, l)(0) += 1;
    return net;
  };
  ControlNet single(size, size);
  single.at(c, c)(0) = 1;
  const double diag = energy(single);
  Eigen::MatrixXd W(2 * radius + 1, 2 * radius + 1);
  for (int a = -radius; a <= radius; ++a)
    for (int b = -radius; b <= radius; ++b) {
      if (a == 0 && b == 0) {
        W(radius, radius) = 1;
        continue;
      }
      ControlNet other(size, size);
      other.at(c + a, c + b)(0) = 1;
      const double h = energy(unit(c, c, c + a, c + b)) - diag - energy(other);
      W(radius + a, radius + b) = 0.5 * h / diag;  // E(x) = xᵀ(H/2)x: H(p,q)/H(p,p) = (E(p+q)−E(p)−E(q))/(2E(p))
    }
  return W;
}

}  // namespace

TEST_CASE("c1_family_stencil: is the Euler-Lagrange operator of the blended energy", "[mask]") {
  for (double w : {0.0, 0.2, 0.5, 0.8, 1.0}) {
    INFO("w = " << w);
    const Eigen::MatrixXd H = hessian_stencil([w](const ControlNet& net) { return c1_family_energy(net, w); }, 2);
    const Stencil s = c1_family_stencil(w);
    CHECK((s.weights - H).cwiseAbs().maxCoeff() < 1e-13);
    CHECK(std::abs(weight_sum(s)) < 1e-14);
  }
}

TEST_CASE("c1_family_stencil: w = 1 is c1-coons and w = 0 is biharmonic", "[mask]") {
  Eigen::VectorXd d4(5);
  d4 << 1, -4, 6, -4, 1;
  const Eigen::MatrixXd outer = d4 * d4.transpose();
  Eigen::MatrixXd thirteen = Eigen::MatrixXd::Zero(5, 5);  // centre 20, edges −8, diagonals 2, distance-2 axial 1
  thirteen(2, 2) = 20;
  for (int k : {1, 3}) thirteen(2, k) = thirteen(k, 2) = -8;
  for (int a : {1, 3})
    for (int b : {1, 3}) thirteen(a, b) = 2;
  for (int k : {0, 4}) thirteen(2, k) = thirteen(k, 2) = 1;
  CHECK((c1_coons_stencil().weights - outer / 36).cwiseAbs().maxCoeff() < 1e-16);
  CHECK((biharmonic_stencil().weights - thirteen / 20).cwiseAbs().maxCoeff() < 1e-16);
  CHECK((c1_family_stencil(1).weights - c1_coons_stencil().weights).cwiseAbs().maxCoeff() < 1e-16);
  CHECK((c1_family_stencil(0).weights - biharmonic_stencil().weights).cwiseAbs().maxCoeff() < 1e-16);
  // In between it is neither (the family moves).
  CHECK((c1_family_stencil(0.5).weights - biharmonic_stencil().weights).cwiseAbs().maxCoeff() > 0.05);
  // The closed form of the header.
  const double w = 0.3, c = 20 + 16 * w;
  const Stencil s = c1_family_stencil(w);
  CHECK(s.at(1, 0) == Approx(-(8 + 16 * w) / c));
  CHECK(s.at(1, 1) == Approx((2 + 14 * w) / c));
  CHECK(s.at(0, 2) == Approx((1 + 5 * w) / c));
  CHECK(s.at(2, 1) == Approx(-4 * w / c));
  CHECK(s.at(-2, -2) == Approx(w / c));
}

TEST_CASE("c1_family_stencil_derivative: matches central differences in w", "[mask]") {
  for (double w : {0.0, 0.4, 1.0}) {
    const double h = 1e-5;
    const Eigen::MatrixXd fd = (c1_family_stencil(w + h).weights - c1_family_stencil(w - h).weights) / (2 * h);
    CHECK((c1_family_stencil_derivative(w) - fd).cwiseAbs().maxCoeff() < 1e-9);
  }
}

TEST_CASE("alpha_stencil: the mask equations of the 3x3 family and back to Mask9", "[mask]") {
  const Mask9 mask = anisotropic_mask(4, 7, 2.5);  // e_i ≠ e_j
  const Stencil s = alpha_stencil(mask);
  CHECK(s.radius == 1);
  CHECK(s.at(1, 0) == -mask.edge_i);
  CHECK(s.at(-1, 0) == -mask.edge_i);
  CHECK(s.at(0, 1) == -mask.edge_j);
  CHECK(s.at(1, -1) == -mask.diag);
  CHECK(std::abs(weight_sum(s)) < 1e-15);
  const auto back = to_mask9(s);
  REQUIRE(back);
  CHECK(back->edge_i == mask.edge_i);
  CHECK(back->edge_j == mask.edge_j);
  CHECK(back->diag == mask.diag);
  CHECK_FALSE(to_mask9(c1_coons_stencil()));
  // A 5×5 stencil whose outer ring is zero is a 3×3 one.
  Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(5, 5);
  wide.block(1, 1, 3, 3) = s.weights;
  CHECK(trimmed(make_stencil(wide)).radius == 1);
  CHECK(to_mask9(make_stencil(wide)));
}

TEST_CASE("symbol_nonnegative: exactly the definite alpha range and the whole C1 family", "[mask]") {
  for (double alpha : {-0.25, -0.1, 0.0, 0.25}) CHECK(symbol_nonnegative(alpha_stencil(alpha_mask(alpha))));
  for (double alpha : {-0.3, 0.3, 0.5}) CHECK_FALSE(symbol_nonnegative(alpha_stencil(alpha_mask(alpha))));
  for (double w : {0.0, 0.3, 0.7, 1.0}) CHECK(symbol_nonnegative(c1_family_stencil(w)));
  // σ is the eigenvalue of the wave: at (π, π) the α mask gives 1 + 4β − 4α = 2 − 8α.
  CHECK(stencil_symbol(alpha_stencil(alpha_mask(0.1)), M_PI, M_PI) == Approx(2 - 0.8));
  CHECK(std::abs(stencil_symbol(c1_coons_stencil(), 0, 1.3)) < 1e-15);  // δ⁴ vanishes at θ = 0
}

TEST_CASE("symbol_nonnegative: a dip narrower than the sampling grid is found", "[mask]") {
  // σ(θ) = 1 + 2w₁cos θ + 2w₂cos 2θ, w₁ = −2/3 − e, w₂ = 1/6 + e: σ(0) = 0, and for e > 0 σ dips to
  // about −13.5e² at θ ≈ 3√e, between the samples 0 and 2π/256 where σ ≥ 0 (e = 2.4e-5: a file
  // stencil whose singular system was solved into garbage). e = 0 gives σ = (2/3)(1 − cos θ)² ≥ 0.
  for (double e : {0.0, 1e-5, 2.4e-5}) {
    Eigen::MatrixXd raw = Eigen::MatrixXd::Zero(5, 5);
    raw(2, 2) = 1;
    raw(1, 2) = raw(3, 2) = -2.0 / 3 - e;
    raw(0, 2) = raw(4, 2) = 1.0 / 6 + e;
    const Stencil s = make_stencil(raw);
    INFO("e = " << e);
    CHECK(stencil_symbol(s, 2 * M_PI / 256, 0) > 0);  // the samples around the dip are not negative
    CHECK(symbol_nonnegative(s) == (e == 0));
  }
}

TEST_CASE("separable_factors: c1-coons and the Coons mask are outer products, biharmonic is not", "[mask]") {
  for (const Stencil& s : {c1_coons_stencil(), alpha_stencil(alpha_mask(-0.25))}) {
    const auto uv = separable_factors(s);
    REQUIRE(uv);
    CHECK((uv->first * uv->second.transpose() - s.weights).cwiseAbs().maxCoeff() < 1e-15);
  }
  CHECK_FALSE(separable_factors(biharmonic_stencil()));
  CHECK_FALSE(separable_factors(c1_family_stencil(0.5)));
  CHECK_FALSE(separable_factors(alpha_stencil(alpha_mask(0.0))));
}
