#include "matrix_market.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unsupported/Eigen/SparseExtra>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/write_files.h"

namespace coons {

void write_matrix_market(std::ostream& out, const Eigen::SparseMatrix<double>& A) {
  // Byte for byte as Eigen's saveMarket (its header with two spaces, column by column, scientific
  // notation with 17 decimals), but through a stream the caller checks.
  fmt::print(out, "%%MatrixMarket matrix coordinate  real general\n{} {} {}\n", A.rows(), A.cols(), A.nonZeros());
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      fmt::print(out, "{} {} {:.17e}\n", it.row() + 1, it.col() + 1, it.value());
}

void write_dense_matrix_market(std::ostream& out, const Eigen::MatrixXd& B) {
  fmt::print(out, "%%MatrixMarket matrix array real general\n{} {}\n", B.rows(), B.cols());
  for (Eigen::Index c = 0; c < B.cols(); ++c)
    for (Eigen::Index r = 0; r < B.rows(); ++r) fmt::print(out, "{}\n", B(r, c));
}

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A) {
  write_file_atomically(path, [&](std::ostream& out) { write_matrix_market(out, A); });
}

void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& B) {
  write_file_atomically(path, [&](std::ostream& out) { write_dense_matrix_market(out, B); });
}

namespace {

// The readers check every size against the bytes of the file before taking memory, and every
// index and value before use (Eigen's loadMarket does neither: huge sizes abort with bad_alloc,
// bad lines are dropped with a message on std::cerr); found by tests/fuzz/fuzz_matrix_market.
constexpr std::uintmax_t kMaxMarketBytes = std::uintmax_t{1} << 30;  // 1 GiB
constexpr long long kMaxMarketDimension = 1LL << 26;                 // rows or columns

// The whole file, refused above kMaxMarketBytes.
std::string read_market_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxMarketBytes)
      throw InputError(path, "", fmt::format("more than the limit of {} bytes", kMaxMarketBytes));
  }
  return text;
}

// The banner's words, e.g. "%%MatrixMarket matrix coordinate real general" (any spacing).
std::string normalised_words(const std::string& line) {
  std::istringstream words(line);
  std::string word, out;
  while (words >> word) out += (out.empty() ? "" : " ") + word;
  return out;
}

// Reads the lines after the banner, skipping comments and blank lines.
class MarketLines {
 public:
  MarketLines(const std::string& path, const std::string& text, const char* banner) : in_(text) {
    std::string first;
    std::getline(in_, first);
    if (normalised_words(first) != banner) throw InputError(path, "header", fmt::format("expected '{}'", banner));
  }
  bool next(std::string& line) {
    while (std::getline(in_, line)) {
      ++number_;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '%') continue;
      return true;
    }
    return false;
  }
  [[nodiscard]] int number() const { return number_ + 1; }  // of the line last read, counting the banner

 private:
  std::istringstream in_;
  int number_ = 0;
};

// The integers of a size line, rows and columns within kMaxMarketDimension, nothing else on the line.
std::vector<long long> size_line(const std::string& path, const std::string& line, int count) {
  constexpr long long kHi = 1LL << 62;
  std::istringstream words(line);
  std::vector<long long> out(count);
  for (auto& v : out)
    if (!(words >> v) || v < 0 || v > kHi)
      throw InputError(path, "size line", fmt::format("expected {} integers in [0, {}]", count, kHi));
  std::string rest;
  if (words >> rest) throw InputError(path, "size line", fmt::format("unexpected '{}' after {} integers", rest, count));
  if (out[0] > kMaxMarketDimension || out[1] > kMaxMarketDimension)
    throw InputError(
        path, "size line",
        fmt::format("{} by {} is beyond the limit of {} rows or columns", out[0], out[1], kMaxMarketDimension));
  return out;
}

}  // namespace

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  const std::string text = read_market_text(path);
  MarketLines lines(path, text, "%%MatrixMarket matrix coordinate real general");
  std::string line;
  if (!lines.next(line)) throw InputError(path, "size line", "missing");
  const std::vector<long long> size = size_line(path, line, 3);
  const long long rows = size[0], cols = size[1], nnz = size[2];
  if (rows < 1 || cols < 1) throw InputError(path, "size line", "rows and columns must be at least 1");
  // An entry takes at least 6 bytes ("1 1 1\n"): a larger count cannot be in the file.
  if (nnz > rows * cols || nnz > static_cast<long long>(text.size() / 6))
    throw InputError(
        path, "size line",
        fmt::format("{} entries do not fit a {} by {} matrix in a file of {} bytes", nnz, rows, cols, text.size()));
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(nnz));
  while (lines.next(line)) {
    const std::string field = fmt::format("line {}", lines.number());
    if (static_cast<long long>(entries.size()) == nnz)
      throw InputError(path, field, fmt::format("more entries than the {} of the size line", nnz));
    std::istringstream words(line);
    long long i = 0, j = 0;
    double value = 0;
    std::string rest;
    if (!(words >> i >> j >> value) || (words >> rest)) throw InputError(path, field, "expected 'row column value'");
    if (i < 1 || i > rows || j < 1 || j > cols)
      throw InputError(path, field, fmt::format("entry ({}, {}) outside the {} by {} matrix", i, j, rows, cols));
    if (!std::isfinite(value)) throw InputError(path, field, "the value is not finite");
    entries.emplace_back(static_cast<int>(i - 1), static_cast<int>(j - 1), value);
  }
  if (static_cast<long long>(entries.size()) != nnz)
    throw InputError(path, "size line", fmt::format("promises {} entries, the file holds {}", nnz, entries.size()));
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

Eigen::MatrixXd read_dense_matrix_market(const std::string& path) {
  const std::string text = read_market_text(path);
  MarketLines lines(path, text, "%%MatrixMarket matrix array real general");
  std::string line;
  if (!lines.next(line)) throw InputError(path, "size line", "missing");
  const std::vector<long long> size = size_line(path, line, 2);
  const long long rows = size[0], cols = size[1];
  // A value takes at least 2 bytes ("1\n"): a larger matrix cannot be in the file.
  if (rows * cols > static_cast<long long>(text.size() / 2))
    throw InputError(path, "size line",
                     fmt::format("a {} by {} matrix does not fit in a file of {} bytes", rows, cols, text.size()));
  Eigen::MatrixXd B(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  Eigen::Index k = 0;
  while (lines.next(line)) {
    std::istringstream words(line);
    std::string word;
    while (words >> word) {
      if (k == B.size())
        throw InputError(path, fmt::format("line {}", lines.number()), "more values than the size line says");
      const std::string field = fmt::format("entry ({}, {})", k % rows + 1, k / rows + 1);
      std::istringstream number(word);
      double v = 0;
      std::string rest;
      if (!(number >> v) || (number >> rest)) throw InputError(path, field, "not a number");
      if (!std::isfinite(v)) throw InputError(path, field, "not finite");
      B(k % rows, k / rows) = v;
      ++k;
    }
  }
  if (k != B.size())
    throw InputError(path, fmt::format("entry ({}, {})", k % std::max(rows, 1LL) + 1, k / std::max(rows, 1LL) + 1),
                     "missing");
  return B;
}

}  // namespace coons
