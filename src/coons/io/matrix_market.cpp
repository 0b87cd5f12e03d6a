#include "matrix_market.h"

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unsupported/Eigen/SparseExtra>

#include "coons/io/input_error.h"
#include "coons/io/write_files.h"

namespace coons {

void write_matrix_market(std::ostream& out, const Eigen::SparseMatrix<double>& A) {
  // As Eigen's saveMarket (column by column, 17 significant digits), but through a checked stream.
  fmt::print(out, "%%MatrixMarket matrix coordinate real general\n{} {} {}\n", A.rows(), A.cols(), A.nonZeros());
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      fmt::print(out, "{} {} {:.17g}\n", it.row() + 1, it.col() + 1, it.value());
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
// The banner's words, e.g. "%%MatrixMarket matrix coordinate real general" (any spacing).
std::string header_of(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::string line;
  std::getline(in, line);
  std::istringstream words(line);
  std::string word, normalised;
  while (words >> word) normalised += (normalised.empty() ? "" : " ") + word;
  return normalised;
}
}  // namespace

Eigen::SparseMatrix<double> read_matrix_market(const std::string& path) {
  const std::string header = header_of(path);
  if (header != "%%MatrixMarket matrix coordinate real general")
    throw InputError(path, "header", "expected '%%MatrixMarket matrix coordinate real general'");
  Eigen::SparseMatrix<double> A;
  if (!Eigen::loadMarket(A, path)) throw InputError(path, "", "cannot read the matrix");
  return A;
}

Eigen::MatrixXd read_dense_matrix_market(const std::string& path) {
  const std::string header = header_of(path);
  if (header != "%%MatrixMarket matrix array real general")
    throw InputError(path, "header", "expected '%%MatrixMarket matrix array real general'");
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line) && (line.empty() || line[0] == '%')) {
  }
  std::istringstream size_line(line);
  Eigen::Index rows = -1, cols = -1;
  if (!(size_line >> rows >> cols) || rows < 0 || cols < 0)
    throw InputError(path, "size line", "expected two non-negative integers");
  Eigen::MatrixXd B(rows, cols);
  for (Eigen::Index c = 0; c < cols; ++c)
    for (Eigen::Index r = 0; r < rows; ++r)
      if (!(in >> B(r, c)))
        throw InputError(path, fmt::format("entry ({}, {})", r + 1, c + 1), "missing or not a number");
  return B;
}

}  // namespace coons
