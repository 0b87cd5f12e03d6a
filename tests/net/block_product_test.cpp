#include "coons/net/block_product.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace coons;

namespace {

// A matrix inside a larger one (column stride `pad` more than its rows), entries in [−1, 1].
struct Strided {
  Eigen::MatrixXd storage;
  Eigen::Index rows, cols;
  Strided(Eigen::Index r, Eigen::Index c, Eigen::Index pad, unsigned seed) : storage(r + pad, c), rows(r), cols(c) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (Eigen::Index k = 0; k < storage.size(); ++k) storage.data()[k] = u(rng);
  }
  [[nodiscard]] ConstBlockView view() const { return {storage.data(), rows, cols, storage.rows()}; }
  [[nodiscard]] Eigen::MatrixXd dense() const { return storage.topRows(rows); }
};

// the product in long double, one entry at a time
Eigen::MatrixXd reference_product(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  Eigen::MatrixXd C(A.rows(), B.cols());
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < B.cols(); ++j) {
      long double s = 0;
      for (Eigen::Index k = 0; k < A.cols(); ++k) s += static_cast<long double>(A(i, k)) * B(k, j);
      C(i, j) = static_cast<double>(s);
    }
  return C;
}

double max_abs(const Eigen::MatrixXd& M) { return M.size() == 0 ? 0.0 : M.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("block_product: every instruction set this CPU runs gives the product to rounding", "[net]") {
  const std::vector<InstructionSet> sets = available_instruction_sets();
  REQUIRE(sets.front() == InstructionSet::kBaseline);
  CHECK(sets.back() == widest_instruction_set());
  // sizes around the packet widths (2, 4, 8) and GEMM's register blocks, and one of BandedGram's
  for (const auto& [m, inner, n] : std::vector<std::array<Eigen::Index, 3>>{
           {1, 1, 1}, {3, 5, 7}, {8, 16, 9}, {13, 31, 17}, {32, 330, 257}, {0, 4, 3}, {5, 0, 4}}) {
    const Strided A(m, inner, 3, 1), B(inner, n, 2, 2), Bt(n, inner, 5, 3);
    const Eigen::MatrixXd expected = reference_product(A.dense(), B.dense());
    const Eigen::MatrixXd expected_t = reference_product(A.dense(), Bt.dense().transpose());
    for (InstructionSet set : sets) {
      INFO(instruction_set_name(set) << ": " << m << " × " << inner << " by " << n);
      Eigen::MatrixXd out = Eigen::MatrixXd::Constant(m + 4, n, 7.0);  // stride m + 4; the padding must stay
      block_product(A.view(), B.view(), false, {out.data(), m, n, out.rows()}, set);
      const double tolerance = 4 * std::numeric_limits<double>::epsilon() * double(inner + 1);
      CHECK(max_abs(out.topRows(m) - expected) <= tolerance);
      CHECK((out.bottomRows(4).array() == 7.0).all());
      block_product(A.view(), Bt.view(), true, {out.data(), m, n, out.rows()}, set);
      CHECK(max_abs(out.topRows(m) - expected_t) <= tolerance);
      CHECK((out.bottomRows(4).array() == 7.0).all());
    }
  }
}

TEST_CASE("block_product: the same bits wherever the blocks lie in memory", "[net]") {
  // Each operand and the result shifted by 0 to 7 doubles from a 64-byte boundary (malloc's blocks
  // lie on 16), for a small product (which Eigen would evaluate coefficient by coefficient) and a
  // GEMM-sized one, in both forms.
  for (const auto& [m, inner, n] : std::vector<std::array<Eigen::Index, 3>>{
           {3, 5, 7}, {4, 4, 4}, {8, 4, 6}, {6, 6, 6}, {9, 3, 5}, {4, 8, 4}, {13, 31, 17}, {32, 100, 41}}) {
    const Strided A(m, inner, 0, 11), B(inner, n, 0, 12), Bt(n, inner, 0, 13);
    for (InstructionSet set : available_instruction_sets())
      for (bool transpose_b : {false, true}) {
        INFO(instruction_set_name(set) << ": " << m << " × " << inner << " by " << n << (transpose_b ? ", bᵀ" : ""));
        const Strided& right = transpose_b ? Bt : B;
        Eigen::MatrixXd first;
        for (Eigen::Index shift = 0; shift < 8; ++shift) {
          // room to shift by up to 7 doubles past a 64-byte boundary
          std::vector<double> a_store(A.storage.size() + 16), b_store(right.storage.size() + 16), out_store(m * n + 16);
          const auto at = [shift](std::vector<double>& v) {
            auto p = reinterpret_cast<std::uintptr_t>(v.data());
            const std::size_t skip = ((64 - p % 64) % 64) / sizeof(double);
            return v.data() + skip + shift;
          };
          double* a_data = at(a_store);
          double* b_data = at(b_store);
          double* out_data = at(out_store);
          std::copy(A.storage.data(), A.storage.data() + A.storage.size(), a_data);
          std::copy(right.storage.data(), right.storage.data() + right.storage.size(), b_data);
          block_product({a_data, m, inner, m}, {b_data, right.rows, right.cols, right.rows}, transpose_b,
                        {out_data, m, n, m}, set);
          const Eigen::MatrixXd out = Eigen::Map<const Eigen::MatrixXd>(out_data, m, n);
          if (shift == 0) {
            first = out;
          } else {
            INFO("shift " << shift);
            CHECK(out == first);
          }
        }
      }
  }
}

TEST_CASE("instruction_set_name: the names of the three sets", "[net]") {
  CHECK(instruction_set_name(InstructionSet::kBaseline) == "baseline");
  CHECK(instruction_set_name(InstructionSet::kAvx2) == "avx2");
  CHECK(instruction_set_name(InstructionSet::kAvx512) == "avx512");
}
