#include "matrix_market.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
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

// Throws the reader's error for a first line that is not its banner.
using BannerCheck = std::function<void(const std::string& first_line)>;

// The whole file, refused above kMaxMarketBytes. The banner is checked on the first 64 KiB, before
// the rest is read: a file that is not Matrix Market is refused at once, whatever its size.
std::string read_market_text(const std::string& path, const BannerCheck& check_banner) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::string text;
  char chunk[1 << 16];
  bool checked = false;
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (!checked) {
      std::string first = text.substr(0, text.find('\n'));
      if (!first.empty() && first.back() == '\r') first.pop_back();
      check_banner(first);
      checked = true;
    }
    if (text.size() > kMaxMarketBytes)
      throw InputError(path, "", fmt::format("more than the limit of {} bytes", kMaxMarketBytes));
  }
  if (!checked) check_banner("");
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
  explicit MarketLines(const std::string& text) : in_(text) {
    std::getline(in_, banner_);
    if (!banner_.empty() && banner_.back() == '\r') banner_.pop_back();
  }
  [[nodiscard]] const std::string& banner() const { return banner_; }
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
  std::string banner_;
  int number_ = 0;
};

// A token of the file as an error line quotes it: a NUL byte as \0 (printed as it is, it ended the
// line there: "unknown symmetry 'general" with the rest of the reason lost).
std::string shown(const std::string& token) {
  std::string out;
  for (const char c : token) out += c == '\0' ? std::string("\\0") : std::string(1, c);
  return out;
}

// The integers of a size line, rows and columns within kMaxMarketDimension, nothing else on the line.
std::vector<long long> size_line(const std::string& path, const std::string& line, int count,
                                 const std::string& field = "size line") {
  constexpr long long kHi = 1LL << 62;
  std::istringstream words(line);
  std::vector<long long> out(count);
  for (auto& v : out)
    if (!(words >> v) || v < 0 || v > kHi)
      throw InputError(path, field, fmt::format("expected {} integers in [0, {}]", count, kHi));
  std::string rest;
  if (words >> rest)
    throw InputError(path, field, fmt::format("unexpected '{}' after {} integers", shown(rest), count));
  if (out[0] > kMaxMarketDimension || out[1] > kMaxMarketDimension)
    throw InputError(
        path, field,
        fmt::format("{} by {} is beyond the limit of {} rows or columns", out[0], out[1], kMaxMarketDimension));
  return out;
}

// The column-major matrix of `entries` (rows × cols), duplicates summed in file order as
// setFromTriplets sums them, in O(nnz log nnz + cols). setFromTriplets also builds a row-major
// copy with an index per row: O(rows) for a tall matrix of few entries (a fuzzer's 49,672,948 × 2
// matrix with one entry took 12 s under the sanitizers).
Eigen::SparseMatrix<double> compressed_matrix(long long rows, long long cols,
                                              std::vector<Eigen::Triplet<double>>& entries) {
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    return a.col() != b.col() ? a.col() < b.col() : a.row() < b.row();
  });
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  Eigen::Index unique = 0;
  for (std::size_t k = 0; k < entries.size(); ++k)
    if (k == 0 || entries[k].col() != entries[k - 1].col() || entries[k].row() != entries[k - 1].row()) ++unique;
  A.resizeNonZeros(unique);
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* value = A.valuePtr();
  Eigen::Index at = -1;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const auto& e = entries[k];
    if (k > 0 && e.col() == entries[k - 1].col() && e.row() == entries[k - 1].row()) {
      value[at] += e.value();
      continue;
    }
    ++at;
    inner[at] = e.row();
    value[at] = e.value();
    ++outer[e.col() + 1];
  }
  for (long long c = 0; c < cols; ++c) outer[c + 1] += outer[c];
  return A;
}

}  // namespace

namespace {

// The banner of any real matrix file: its format, field and symmetry, lower case.
struct Banner {
  std::string format, field, symmetry;
};

Banner parse_banner(const std::string& path, const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) {
    std::transform(w.begin(), w.end(), w.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    words.push_back(w);
  }
  const std::string field = "line 1";
  const std::string expected =
      "expected '%%MatrixMarket matrix coordinate|array real|integer|pattern general|symmetric|skew-symmetric'";
  if (words.size() != 5 || words[0] != "%%matrixmarket" || words[1] != "matrix")
    throw InputError(path, field, expected);
  Banner b{words[2], words[3], words[4]};
  if (b.format != "coordinate" && b.format != "array")
    throw InputError(path, field, fmt::format("unknown format '{}' ({})", shown(b.format), expected));
  if (b.field == "complex") throw InputError(path, field, "complex matrices are not supported (real systems only)");
  if (b.field != "real" && b.field != "integer" && b.field != "pattern" && b.field != "double")
    throw InputError(path, field, fmt::format("unknown field '{}' ({})", shown(b.field), expected));
  if (b.field == "double") b.field = "real";  // an alias some writers use
  if (b.field == "pattern" && b.format == "array")
    throw InputError(path, field, "a pattern matrix needs the coordinate format");
  if (b.symmetry == "hermitian") throw InputError(path, field, "hermitian matrices are complex: not supported");
  if (b.symmetry != "general" && b.symmetry != "symmetric" && b.symmetry != "skew-symmetric")
    throw InputError(path, field, fmt::format("unknown symmetry '{}' ({})", shown(b.symmetry), expected));
  return b;
}

// A 1-based index in [1, hi] (a whole token), else nullopt.
std::optional<long long> parse_index(const std::string& token) {
  errno = 0;
  char* end = nullptr;
  const long long v = std::strtoll(token.c_str(), &end, 10);
  if (token.empty() || *end != '\0' || errno == ERANGE || token.find('\0') != std::string::npos) return std::nullopt;
  return v;
}

// One value of the file's field: a finite number (a whole token), integers for `integer`.
double parse_value(const std::string& path, const std::string& where, const std::string& token, const Banner& b) {
  char* end = nullptr;
  errno = 0;
  const double v =
      b.field == "integer" ? double(std::strtoll(token.c_str(), &end, 10)) : std::strtod(token.c_str(), &end);
  // (strtod also reads hexadecimal, '0x10' = 16; Matrix Market values are decimal; a NUL byte
  // ended the number there, "3\0junk" read as 3)
  if (token.empty() || *end != '\0' || token.find_first_of(std::string("xX\0", 3)) != std::string::npos) {
    throw InputError(
        path, where,
        fmt::format("'{}' is not {}", shown(token), b.field == "integer" ? "an integer" : "a decimal number"));
  }
  // a non-zero value below the smallest double (1e-400) read as an explicit 0, where 1e400 is refused
  if (b.field != "integer" && errno == ERANGE && v == 0)
    throw InputError(path, where,
                     fmt::format("the value '{}' is below the smallest double (it would be read as 0)", token));
  // strtoll clamps an integer beyond 64 bits to its limit and says so only in errno (strtod's
  // ERANGE on underflow is a finite value, and overflow is caught as not finite below)
  if (b.field == "integer" && errno == ERANGE)
    throw InputError(path, where, fmt::format("the integer '{}' is beyond the 64-bit range", token));
  if (!std::isfinite(v)) throw InputError(path, where, fmt::format("the value '{}' is not finite", token));
  return v;
}

std::vector<std::string> tokens_of(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// Adds (i, j, v) and, for a symmetric or skew-symmetric file, its mirror image.
void add_entry(std::vector<Eigen::Triplet<double>>& entries, long long i, long long j, double v, const Banner& b) {
  entries.emplace_back(Eigen::Index(i), Eigen::Index(j), v);
  if (i != j && b.symmetry != "general")
    entries.emplace_back(Eigen::Index(j), Eigen::Index(i), b.symmetry == "symmetric" ? v : -v);
}

// `size_field` names the size line (the field of a count that does not match the file).
void read_coordinate_entries(const std::string& path, const std::string& size_field, MarketLines& lines,
                             const Banner& b, long long rows, long long cols, long long nnz,
                             std::vector<Eigen::Triplet<double>>& entries) {
  const std::size_t width = b.field == "pattern" ? 2 : 3;
  const std::string form = b.field == "pattern" ? "'row column'" : "'row column value'";
  long long count = 0;
  std::string line;
  while (lines.next(line)) {
    const std::string where = fmt::format("line {}", lines.number());
    if (count == nnz) throw InputError(path, where, fmt::format("more entries than the {} of the size line", nnz));
    const std::vector<std::string> t = tokens_of(line);
    if (t.size() != width) throw InputError(path, where, "expected " + form);
    const std::optional<long long> i = parse_index(t[0]), j = parse_index(t[1]);
    if (!i || !j) throw InputError(path, where, "expected " + form + " with integer row and column");
    if (*i < 1 || *i > rows || *j < 1 || *j > cols)
      throw InputError(path, where, fmt::format("entry ({}, {}) outside the {} by {} matrix", *i, *j, rows, cols));
    if (b.symmetry == "symmetric" && *i < *j)
      throw InputError(
          path, where,
          fmt::format("entry ({}, {}) above the diagonal: a symmetric file stores the lower triangle", *i, *j));
    if (b.symmetry == "skew-symmetric" && *i <= *j)
      throw InputError(
          path, where,
          fmt::format("entry ({}, {}) not below the diagonal: a skew-symmetric file stores the strict lower triangle",
                      *i, *j));
    const double v = b.field == "pattern" ? 1.0 : parse_value(path, where, t[2], b);
    add_entry(entries, *i - 1, *j - 1, v, b);
    ++count;
  }
  if (count != nnz)
    throw InputError(path, size_field, fmt::format("promises {} entries, the file holds {}", nnz, count));
}

void read_array_entries(const std::string& path, const std::string& size_field, MarketLines& lines, const Banner& b,
                        long long rows, long long cols, std::vector<Eigen::Triplet<double>>& entries) {
  // the (i, j) of the k-th stored value: column by column, the lower (or strict lower) triangle
  // only for a symmetric (skew-symmetric) file
  const long long first_row_offset = b.symmetry == "general" ? -1 : (b.symmetry == "symmetric" ? 0 : 1);
  long long i = first_row_offset < 0 ? 0 : first_row_offset, j = 0;
  auto advance = [&] {
    if (++i == rows) {
      ++j;
      i = first_row_offset < 0 ? 0 : j + first_row_offset;
    }
  };
  auto done = [&] { return j >= cols || (first_row_offset >= 0 && i >= rows); };
  std::string line;
  while (lines.next(line)) {
    const std::string where = fmt::format("line {}", lines.number());
    for (const std::string& token : tokens_of(line)) {
      if (done()) throw InputError(path, where, "more values than the size line says");
      const double v = parse_value(path, where, token, b);
      if (v != 0 || std::signbit(v)) add_entry(entries, i, j, v, b);  // (a −0 is kept: B reads back bit for bit)
      advance();
    }
  }
  if (!done())
    throw InputError(path, size_field,
                     fmt::format("promises a {} by {} {} matrix, the file ends at entry ({}, {})", rows, cols,
                                 b.symmetry, i + 1, j + 1));
}

}  // namespace

double market_matrix_bytes(long long cols, long long stored) {
  const double entries = double(stored), pointers = double(cols) + 1;
  return 16 * entries + 2 * (12 * entries + 4 * pointers);
}

namespace {

// The reader of every kind; `check_banner` refuses a first line (read_market_text).
MarketMatrix read_market_file(const std::string& path, const BannerCheck& check_banner, const SizeCheck& check_sizes) {
  const std::string text = read_market_text(path, check_banner);
  MarketLines lines(text);
  const Banner b = parse_banner(path, lines.banner());
  std::string line;
  if (!lines.next(line)) throw InputError(path, "size line", "missing");
  const int size_line_number = lines.number();
  const std::string where = fmt::format("line {}", size_line_number);
  const bool coordinate = b.format == "coordinate";
  const std::vector<long long> size = size_line(path, line, coordinate ? 3 : 2, where);
  const long long rows = size[0], cols = size[1];
  if (rows < 1 || cols < 1) throw InputError(path, where, "rows and columns must be at least 1");
  if (b.symmetry != "general" && rows != cols)
    throw InputError(path, where, fmt::format("a {} matrix must be square, not {} by {}", b.symmetry, rows, cols));
  if (check_sizes) {
    const bool mirrored = b.symmetry != "general";
    const long long stored = coordinate ? (mirrored ? 2 : 1) * size[2] : rows * cols;
    check_sizes(rows, cols, stored, size_line_number);
  }
  std::vector<Eigen::Triplet<double>> entries;
  if (coordinate) {
    // An entry takes at least 4 bytes ("1 1\n"): a larger count cannot be in the file. (More
    // entries than cells can: duplicates are summed.)
    const long long nnz = size[2];
    if (nnz > static_cast<long long>(text.size() / 4))
      throw InputError(path, where, fmt::format("{} entries do not fit in a file of {} bytes", nnz, text.size()));
    entries.reserve(static_cast<std::size_t>(b.symmetry == "general" ? nnz : 2 * nnz));
    read_coordinate_entries(path, where, lines, b, rows, cols, nnz, entries);
  } else {
    // A value takes at least 2 bytes ("1\n"): a larger matrix cannot be in the file.
    if (rows * cols / (b.symmetry == "general" ? 1 : 2) > static_cast<long long>(text.size() / 2))
      throw InputError(path, where,
                       fmt::format("a {} by {} matrix does not fit in a file of {} bytes", rows, cols, text.size()));
    read_array_entries(path, where, lines, b, rows, cols, entries);
  }
  MarketMatrix out;
  out.matrix = compressed_matrix(rows, cols, entries);
  // Every value was finite; duplicates summed (1e308 twice) need not be.
  for (Eigen::Index c = 0; c < out.matrix.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(out.matrix, c); it; ++it)
      if (!std::isfinite(it.value()))
        throw InputError(path, fmt::format("entry ({}, {})", it.row() + 1, it.col() + 1),
                         fmt::format("the duplicate entries sum to {}, beyond the doubles", it.value()));
  out.format = b.format;
  out.field = b.field;
  out.symmetry = b.symmetry;
  out.size_line = size_line_number;
  // the values listed: the size line's count, or an array's cells (one triangle of a symmetric
  // array, the strict one of a skew-symmetric array)
  out.file_entries = coordinate                  ? size[2]
                     : b.symmetry == "general"   ? rows * cols
                     : b.symmetry == "symmetric" ? rows * (rows + 1) / 2
                                                 : rows * (rows - 1) / 2;
  return out;
}

// A banner check for one kind of file: `banner`'s words, in any spacing.
BannerCheck expect_banner(const std::string& path, const char* banner) {
  return [&path, banner](const std::string& line) {
    if (normalised_words(line) != banner) throw InputError(path, "header", fmt::format("expected '{}'", banner));
  };
}

}  // namespace

MarketMatrix read_market_matrix(const std::string& path, const SizeCheck& check_sizes) {
  return read_market_file(
      path, [&](const std::string& first) { parse_banner(path, first); }, check_sizes);
}

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  return read_market_file(path, expect_banner(path, "%%MatrixMarket matrix coordinate real general"), {}).matrix;
}

Eigen::MatrixXd read_dense_matrix_market(const std::string& path) {
  return Eigen::MatrixXd(
      read_market_file(path, expect_banner(path, "%%MatrixMarket matrix array real general"), {}).matrix);
}

}  // namespace coons
