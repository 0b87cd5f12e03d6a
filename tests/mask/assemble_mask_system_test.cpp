#include "coons/mask/assemble_mask_system.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "coons/mask/mask_families.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

// The reference: the mask equations written out densely, entry by entry.
void dense_reference(const ControlNet& net, const Mask9& mask, Eigen::MatrixXd& A, Eigen::MatrixX3d& B) {
  const int m = net.m, n = net.n, cols = n - 1;
  const int N = (m - 1) * (n - 1);
  A = Eigen::MatrixXd::Zero(N, N);
  B = Eigen::MatrixX3d::Zero(N, 3);
  for (int i = 1; i < m; ++i)
    for (int j = 1; j < n; ++j) {
      const int row = (i - 1) * cols + (j - 1);
      A(row, row) = 1;
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          if (!di && !dj) continue;
          const double w = di == 0 ? mask.edge_j : (dj == 0 ? mask.edge_i : mask.diag);
          const int ii = i + di, jj = j + dj;
          if (ii == 0 || ii == m || jj == 0 || jj == n)
            B.row(row) += w * net.at(ii, jj);
          else
            A(row, (ii - 1) * cols + (jj - 1)) -= w;
        }
    }
}

}  // namespace

TEST_CASE("assemble_mask_system: matrix and right-hand side equal the dense reference", "[mask]") {
  std::uint32_t seed = 1;
  for (auto [m, n] : {std::pair{2, 2}, {3, 3}, {2, 6}, {7, 2}, {5, 8}, {9, 4}}) {
    const ControlNet net = make_random_net(m, n, seed++);
    for (const Mask9& mask : {alpha_mask(-0.25), alpha_mask(0.0), alpha_mask(0.2), anisotropic_mask(m, n, 3.0)}) {
      const MaskSystem s = assemble_mask_system(net, mask);
      Eigen::MatrixXd A;
      Eigen::MatrixX3d B;
      dense_reference(net, mask, A, B);
      INFO("m = " << m << ", n = " << n);
      CHECK((Eigen::MatrixXd(s.A) - A).cwiseAbs().maxCoeff() == 0);
      CHECK((s.B - B).cwiseAbs().maxCoeff() < 1e-15);
      CHECK(s.A.isCompressed());
    }
  }
}

TEST_CASE("assemble_mask_system: the matrix is symmetric and its pattern independent of alpha", "[mask]") {
  const ControlNet net = make_random_net(6, 9, 4);
  const MaskSystem a = assemble_mask_system(net, alpha_mask(-0.25));
  const MaskSystem b = assemble_mask_system(net, alpha_mask(0.0));
  CHECK((Eigen::MatrixXd(a.A) - Eigen::MatrixXd(a.A).transpose()).norm() == 0);
  REQUIRE(a.A.nonZeros() == b.A.nonZeros());
  for (Eigen::Index k = 0; k < a.A.nonZeros(); ++k) CHECK(a.A.innerIndexPtr()[k] == b.A.innerIndexPtr()[k]);
  Eigen::SparseMatrix<double> refilled = a.A;
  solvers::refill_stencil_matrix(b.stencil, refilled);
  CHECK((Eigen::MatrixXd(refilled) - Eigen::MatrixXd(b.A)).norm() == 0);
}

TEST_CASE("assemble_mask_system: degenerate sizes have no unknowns", "[mask]") {
  for (auto [m, n] : {std::pair{1, 1}, {1, 5}, {4, 1}}) {
    const MaskSystem s = assemble_mask_system(make_random_net(m, n, 9), alpha_mask(-0.1));
    CHECK(s.A.rows() == 0);
    CHECK(s.B.rows() == 0);
  }
}

TEST_CASE("fill_interior: inverse of interior_of", "[mask]") {
  const ControlNet net = make_random_net(5, 7, 2);
  CHECK(max_difference(fill_interior(net, interior_of(net)), net) == 0);
}

TEST_CASE("anisotropic_mask: affine invariant, and isotropic alpha(mu) when m = n", "[mask]") {
  for (auto [m, n] : {std::pair{4, 4}, {3, 9}, {12, 5}})
    for (double mu : {0.0, 1.0, 10.0, 1e3}) {
      const Mask9 mask = anisotropic_mask(m, n, mu);
      CHECK(std::abs(mask.affine_defect()) < 1e-15);
      if (m == n) {
        CHECK(mask.diag == Approx(alpha_from_mu(n, mu)).epsilon(1e-14));
        CHECK(mask.edge_i == Approx(0.25 - mask.diag).epsilon(1e-14));
      }
    }
  for (int n : {3, 8, 16})
    for (double alpha : {-0.24, -0.2, -0.1, -0.01})
      CHECK(alpha_from_mu(n, mu_from_alpha(n, alpha)) == Approx(alpha).epsilon(1e-13));
}

TEST_CASE("anisotropic_mask: finite and affine invariant up to the largest double", "[mask]") {
  // 4mn + 2μ(m/n + n/m) overflows above about 4.5e307 at degree (2, 3)
  for (double mu : {1e307, 1e308, 1.7e308, std::numeric_limits<double>::max()}) {
    const Mask9 mask = anisotropic_mask(2, 3, mu);
    INFO("mu = " << mu);
    CHECK(std::isfinite(mask.edge_i));
    CHECK(std::isfinite(mask.diag));
    CHECK(std::abs(mask.affine_defect()) < 1e-15);
    // the limit μ → ∞: e_i = (m/n) / (2(m/n + n/m)), no diagonal weight
    CHECK(mask.edge_i == Approx((2.0 / 3) / (2 * (2.0 / 3 + 1.5))).epsilon(1e-12));
    CHECK(std::abs(mask.diag) < 1e-300);
    const MaskPoint p = mu_family(2, 3, mu);
    CHECK(std::isfinite(p.derivative.edge_i));
    CHECK(std::isfinite(p.derivative.edge_j));
    CHECK(std::isfinite(p.derivative.diag));
  }
}

TEST_CASE("alpha_family_singular_alphas: each one makes the system singular, once, and none is definite", "[mask]") {
  // degree (3, 3): eigenvalues 1/2 + α, 1 + α, 3/2 − 3α
  const std::vector<double> three = alpha_family_singular_alphas(3, 3, -2, 2);
  REQUIRE(three.size() == 3);
  CHECK(three[0] == Approx(-1).epsilon(1e-15));
  CHECK(three[1] == Approx(-0.5).epsilon(1e-15));
  CHECK(three[2] == Approx(0.5).epsilon(1e-15));
  CHECK(alpha_family_singular_alphas(3, 3, -0.49, 0.49).empty());
  // a singular bound is not inside, though its α is computed an ulp inside it
  CHECK(alpha_family_singular_alphas(3, 3, -1, 0.5) == std::vector<double>{three[1]});
  // a slope that is 0 but for rounding is no pole (2 × 2: λ = 1 for every α; it gave one at 8.8e14)
  CHECK(alpha_family_singular_alphas(2, 2, -1e60, 1e60).empty());
  for (const auto& [m, n] : {std::pair{5, 3}, std::pair{6, 6}, std::pair{4, 9}}) {
    INFO(m << "x" << n);
    CHECK(alpha_family_singular_alphas(m, n, -0.25, 0.25).empty());
    const std::vector<double> alphas = alpha_family_singular_alphas(m, n, -10, 10);
    REQUIRE(!alphas.empty());
    for (std::size_t k = 0; k < alphas.size(); ++k) {
      CHECK(mask9_eigenvalue_ratio(alpha_mask(alphas[k]), m, n) < 1e-14);
      if (k > 0) {  // increasing, and regular between two of them: each pole is listed once
        CHECK(alphas[k] > alphas[k - 1]);
        CHECK(mask9_eigenvalue_ratio(alpha_mask(0.5 * (alphas[k - 1] + alphas[k])), m, n) > 1e-6);
      }
    }
  }
}

TEST_CASE("mask9_eigenvalue_ratio: equals the dense eigenvalues of the mask system and is 0 at a singular alpha",
          "[mask]") {
  for (const auto& [m, n] : {std::pair{3, 3}, std::pair{5, 4}, std::pair{7, 11}, std::pair{2, 9}}) {
    for (const Mask9& mask :
         {alpha_mask(-0.25), alpha_mask(0.1), alpha_mask(-0.45), alpha_mask(0.6), anisotropic_mask(m, n, 2.5)}) {
      const MaskSystem s = assemble_mask_system(make_random_net(m, n, 3), mask);
      const Eigen::VectorXd lambda = Eigen::MatrixXd(s.A).eigenvalues().cwiseAbs();  // symmetric: real
      INFO(m << "x" << n << " edge " << mask.edge_i << " " << mask.edge_j << " diag " << mask.diag);
      CHECK(mask9_eigenvalue_ratio(mask, m, n) ==
            Approx(lambda.minCoeff() / lambda.maxCoeff()).margin(1e-12).epsilon(1e-9));
    }
  }
  // degree (3, 3): eigenvalues 1/2 + α, 1 + α, 3/2 − 3α, so α = ±1/2 are singular
  CHECK(mask9_eigenvalue_ratio(alpha_mask(-0.5), 3, 3) < 1e-15);
  CHECK(mask9_eigenvalue_ratio(alpha_mask(0.5), 3, 3) < 1e-15);
  CHECK(mask9_eigenvalue_ratio(alpha_mask(0.3), 3, 3) > 0.1);
  CHECK(mask9_eigenvalue_ratio(alpha_mask(0.3), 1, 5) == 1);  // no interior
}
