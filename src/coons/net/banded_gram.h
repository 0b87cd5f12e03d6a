// The Bernstein Gram matrix G^k (bernstein.h, #k+1 by #k+1) applied without its negligible
// entries. G[i][l] peaks at l = i and falls off like exp(−(i−l)²/(4k·t(1−t))), t = i/k, and every
// row sums to ∫B_i^k = 1/(k+1); entries below 1e-20/(k+1) are dropped, which moves no product by
// more than its rounding does. Rows are kept in blocks of 32 with the column range of their kept
// entries, so G·C and C·G are dense products of those blocks (Eigen's GEMM on the widest instruction set
// of the CPU: block_product.h): about 0.32 of the
// full product's work at k = 1000 (the band grows like √k), all of it below k ≈ 60. With threads > 1
// the blocks are shared out between that many threads (0: every core); each block is computed alike
// whichever thread takes it, so the product is the same bit for bit for every count.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), ch. 5 (the Gram entries).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace coons {

class BandedGram {
 public:
  static constexpr double kDropBelow = 1e-20;  //!< times the row sum 1/(k+1)
  static constexpr int kBlockRows = 32;

  explicit BandedGram(int k);

  [[nodiscard]] int degree() const { return k_; }
  //! G·C, C with k+1 rows.
  [[nodiscard]] Eigen::MatrixXd left(const Eigen::Ref<const Eigen::MatrixXd>& C, int threads = 1) const;
  //! C·G, C with k+1 columns.
  [[nodiscard]] Eigen::MatrixXd right(const Eigen::Ref<const Eigen::MatrixXd>& C, int threads = 1) const;
  //! The kept entries as a dense matrix, zeros elsewhere.
  [[nodiscard]] Eigen::MatrixXd dense() const;
  //! The fraction of the (k+1)² entries held.
  [[nodiscard]] double stored_fraction() const;

 private:
  struct Block {
    int row = 0, col = 0;     //!< first row and first column in G
    Eigen::MatrixXd entries;  //!< G(row.., col..)
  };
  int k_;
  std::vector<Block> blocks_;
};

}  // namespace coons
