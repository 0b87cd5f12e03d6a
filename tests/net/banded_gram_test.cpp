#include "coons/net/banded_gram.h"

#include <catch2/catch.hpp>
#include <random>

#include "coons/net/bernstein.h"

using namespace coons;

namespace {
Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd M(rows, cols);
  for (Eigen::Index k = 0; k < M.size(); ++k) M.data()[k] = u(rng);
  return M;
}
}  // namespace

TEST_CASE("BandedGram: products equal those of the dense Gram matrix", "[net]") {
  for (int k : {0, 1, 3, 17, 64, 300, 700}) {
    INFO("k = " << k);
    const BandedGram banded(k);
    const Eigen::MatrixXd G = bernstein_gram(k);
    const Eigen::MatrixXd C = random_matrix(k + 1, 5, unsigned(k) + 1), D = random_matrix(4, k + 1, unsigned(k) + 2);
    const double scale = G.cwiseAbs().rowwise().sum().maxCoeff();  // = 1/(k+1)
    CHECK((banded.left(C) - G * C).cwiseAbs().maxCoeff() <= 1e-14 * scale);
    CHECK((banded.right(D) - D * G).cwiseAbs().maxCoeff() <= 1e-14 * scale);
    // the entries held are those of bernstein_gram, bit for bit; the rest are negligible
    const Eigen::MatrixXd kept = banded.dense();
    for (int i = 0; i <= k; ++i)
      for (int l = 0; l <= k; ++l)
        if (kept(i, l) != 0) {
          REQUIRE(kept(i, l) == G(i, l));
        } else {
          REQUIRE(G(i, l) < BandedGram::kDropBelow / (k + 1));
        }
  }
}

TEST_CASE("BandedGram: products on several threads equal the one-thread ones bit for bit", "[net]") {
  // large enough that 2 and 3 threads are used (a product of a few million multiply-adds stays on one)
  const int k = 300;
  const BandedGram banded(k);
  const Eigen::MatrixXd G = bernstein_gram(k);
  const Eigen::MatrixXd C = random_matrix(k + 1, k + 1, 7), D = random_matrix(k + 1, k + 1, 8);
  const Eigen::MatrixXd left = banded.left(C), right = banded.right(D);
  CHECK((left - G * C).cwiseAbs().maxCoeff() <= 1e-14 / (k + 1));
  CHECK((right - D * G).cwiseAbs().maxCoeff() <= 1e-14 / (k + 1));
  for (int threads : {2, 3, 0}) {
    INFO("threads = " << threads);
    CHECK(banded.left(C, threads) == left);
    CHECK(banded.right(D, threads) == right);
  }
}

TEST_CASE("BandedGram: holds a band that narrows relative to the degree", "[net]") {
  CHECK(BandedGram(40).stored_fraction() == 1.0);
  const double at_300 = BandedGram(300).stored_fraction(), at_1000 = BandedGram(1000).stored_fraction();
  CHECK(at_300 < 0.75);
  CHECK(at_1000 < 0.45);
  CHECK(at_1000 < at_300);
}

TEST_CASE("BernsteinGramEntries: the entries of bernstein_gram, bit for bit", "[net]") {
  for (int k : {2, 30, 510, 511, 900}) {
    const BernsteinGramEntries entry(k);
    const Eigen::MatrixXd G = bernstein_gram(k);
    for (int i = 0; i <= k; i += std::max(1, k / 37))
      for (int l = 0; l <= k; l += std::max(1, k / 41)) REQUIRE(entry(i, l) == G(i, l));
  }
}
