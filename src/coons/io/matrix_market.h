// Matrix Market output of an assembled mask system, for other solvers and tools, and input of
// any real Matrix Market matrix (`coons bench-matrix`).
// The matrix is written as `coordinate real general` (every stored entry, both triangles, as
// Eigen's saveMarket does, scientific with 17 decimals: it reads back bit-exactly); the right-hand sides
// as one dense `array real general` file of #rows by 3 (column-major, as the format prescribes).
// Every write is checked: a failed write is an InputError with the OS reason, and the file is
// published only when complete (write_files.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <ostream>
#include <string>

namespace coons {

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A);
void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& B);
//! The same into a stream (the caller checks it, e.g. OutputSet::write).
void write_matrix_market(std::ostream& out, const Eigen::SparseMatrix<double>& A);
void write_dense_matrix_market(std::ostream& out, const Eigen::MatrixXd& B);

//! What write_matrix_market writes: read_market_matrix refusing any banner but `coordinate real
//! general` (InputError "FILE: header: expected ...", checked on the first line).
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);
//! What write_dense_matrix_market writes: read_market_matrix refusing any banner but `array real
//! general`.
Eigen::MatrixXd read_dense_matrix_market(const std::string& path);

//! A matrix as read by read_market_matrix(): the full matrix, whatever the file stored.
struct MarketMatrix {
  Eigen::SparseMatrix<double> matrix;  //!< symmetric and skew-symmetric files expanded to both triangles
  std::string format;                  //!< "coordinate" or "array"
  std::string field;                   //!< "real", "integer" or "pattern" (every stored entry 1)
  std::string symmetry;                //!< "general", "symmetric" or "skew-symmetric"
  int size_line = 0;                   //!< the number of the size line (for errors about the sizes)
  long long file_entries = 0;          //!< the values the file lists (a symmetric file: one triangle)
};

//! A check of the sizes a file declares (read_market_matrix).
using SizeCheck = std::function<void(long long rows, long long cols, long long stored, int size_line)>;

//! Any real Matrix Market matrix, as the NIST format and the SuiteSparse collection write them:
//! `coordinate` or `array`; `real`, `integer` or `pattern`; `general`, `symmetric` (the lower
//! triangle stored, mirrored here) or `skew-symmetric`. Duplicate coordinate entries are summed;
//! zeros of an array file are not stored (but a −0 is, so that a written B reads back bit for bit). Throws InputError
//! "FILE: line N: reason" for a wrong banner, size line, entry, index out of range, entry in the wrong triangle or
//! non-finite value. `check_sizes(rows, cols, stored, size_line)`, when given, is called once the size line is read and
//! before anything is allocated for it (stored: the entries the file promises, a symmetric file's mirrored ones
//! included; a file of 72 bytes can declare 2^26 columns, whose column pointers alone are 256 MB); it refuses them by
//! throwing.
MarketMatrix read_market_matrix(const std::string& path, const SizeCheck& check_sizes = {});

//! What read_market_matrix holds for a matrix of `cols` columns and `stored` entries, an upper-bound
//! sketch as in memory_estimate.h: the triplets, the compressed matrix and one copy of it.
double market_matrix_bytes(long long cols, long long stored);

}  // namespace coons
