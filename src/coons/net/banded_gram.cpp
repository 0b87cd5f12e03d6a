#include "banded_gram.h"

#include <algorithm>
#include <cassert>

#include "coons/net/bernstein.h"

namespace coons {

BandedGram::BandedGram(int k) : k_(k) {
  const BernsteinGramEntries entry(k);
  const double threshold = kDropBelow / (k + 1);
  // Row i of G is unimodal with its peak at l = i (the ratio G[i][l+1]/G[i][l] falls with l and
  // crosses 1 between i−1 and i): its kept entries are one interval around the diagonal.
  for (int row = 0; row <= k; row += kBlockRows) {
    const int rows = std::min(kBlockRows, k + 1 - row);
    int first = row, last = row + rows - 1;
    for (int i = row; i < row + rows; ++i) {
      int lo = i, hi = i;
      while (lo > 0 && entry(i, lo - 1) >= threshold) --lo;
      while (hi < k && entry(i, hi + 1) >= threshold) ++hi;
      first = std::min(first, lo);
      last = std::max(last, hi);
    }
    Block block;
    block.row = row;
    block.col = first;
    block.entries.resize(rows, last - first + 1);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c <= last - first; ++c) block.entries(r, c) = entry(row + r, first + c);
    blocks_.push_back(std::move(block));
  }
}

Eigen::MatrixXd BandedGram::left(const Eigen::Ref<const Eigen::MatrixXd>& C) const {
  assert(C.rows() == k_ + 1);
  Eigen::MatrixXd out(k_ + 1, C.cols());
  for (const Block& b : blocks_)
    out.middleRows(b.row, b.entries.rows()).noalias() = b.entries * C.middleRows(b.col, b.entries.cols());
  return out;
}

Eigen::MatrixXd BandedGram::right(const Eigen::Ref<const Eigen::MatrixXd>& C) const {
  assert(C.cols() == k_ + 1);
  Eigen::MatrixXd out(C.rows(), k_ + 1);
  for (const Block& b : blocks_)
    out.middleCols(b.row, b.entries.rows()).noalias() = C.middleCols(b.col, b.entries.cols()) * b.entries.transpose();
  return out;
}

Eigen::MatrixXd BandedGram::dense() const {
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(k_ + 1, k_ + 1);
  for (const Block& b : blocks_) G.block(b.row, b.col, b.entries.rows(), b.entries.cols()) = b.entries;
  return G;
}

double BandedGram::stored_fraction() const {
  double held = 0;
  for (const Block& b : blocks_) held += double(b.entries.size());
  return held / ((double(k_) + 1) * (double(k_) + 1));
}

}  // namespace coons
