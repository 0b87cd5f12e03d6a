#include "banded_gram.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <thread>
#include <vector>

#include "coons/net/bernstein.h"
#include "coons/net/block_product.h"

namespace coons {

namespace {

// body(b) for every block b, on `threads` threads (0: every core) taking blocks in turn; the
// calling thread is one of them. Small products stay on one thread (a thread costs more than them).
template <class Body>
void for_each_block(std::size_t blocks, std::size_t work, int threads, const Body& body) {
  constexpr std::size_t kWorkPerThread = std::size_t(1) << 22;  // multiply-adds
  std::size_t count = threads > 0 ? std::size_t(threads) : std::max(1U, std::thread::hardware_concurrency());
  count = std::min({count, blocks, std::max<std::size_t>(1, work / kWorkPerThread)});
  if (count <= 1) {
    for (std::size_t b = 0; b < blocks; ++b) body(b);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    for (std::size_t b = next++; b < blocks; b = next++) body(b);
  };
  std::vector<std::thread> pool;
  pool.reserve(count - 1);
  for (std::size_t t = 1; t < count; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

}  // namespace

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

Eigen::MatrixXd BandedGram::left(const Eigen::Ref<const Eigen::MatrixXd>& C, int threads) const {
  assert(C.rows() == k_ + 1);
  Eigen::MatrixXd out(k_ + 1, C.cols());
  for_each_block(
      blocks_.size(), std::size_t(stored_fraction() * (k_ + 1.0) * (k_ + 1.0)) * C.cols(), threads, [&](std::size_t i) {
        const Block& b = blocks_[i];  // out.middleRows(b.row, ·) = b.entries · C.middleRows(b.col, ·)
        const Eigen::Index rows = b.entries.rows(), width = b.entries.cols();
        block_product({b.entries.data(), rows, width, rows}, {C.data() + b.col, width, C.cols(), C.outerStride()},
                      false, {out.data() + b.row, rows, C.cols(), out.outerStride()});
      });
  return out;
}

Eigen::MatrixXd BandedGram::right(const Eigen::Ref<const Eigen::MatrixXd>& C, int threads) const {
  assert(C.cols() == k_ + 1);
  Eigen::MatrixXd out(C.rows(), k_ + 1);
  for_each_block(blocks_.size(), std::size_t(stored_fraction() * (k_ + 1.0) * (k_ + 1.0)) * C.rows(), threads,
                 [&](std::size_t i) {
                   const Block& b = blocks_[i];  // out.middleCols(b.row, ·) = C.middleCols(b.col, ·) · b.entriesᵀ
                   const Eigen::Index rows = b.entries.rows(), width = b.entries.cols();
                   block_product({C.data() + b.col * C.outerStride(), C.rows(), width, C.outerStride()},
                                 {b.entries.data(), rows, width, rows}, true,
                                 {out.data() + b.row * out.outerStride(), C.rows(), rows, out.outerStride()});
                 });
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
