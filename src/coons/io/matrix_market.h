// Matrix Market output of an assembled mask system, for other solvers and tools.
// The matrix is written as `coordinate real general` (every stored entry, both triangles, as
// Eigen's saveMarket does, scientific with 17 decimals: it reads back bit-exactly); the right-hand sides
// as one dense `array real general` file of #rows by 3 (column-major, as the format prescribes).
// Every write is checked: a failed write is an InputError with the OS reason, and the file is
// published only when complete (write_files.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <ostream>
#include <string>

namespace coons {

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A);
void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& B);
//! The same into a stream (the caller checks it, e.g. OutputSet::write).
void write_matrix_market(std::ostream& out, const Eigen::SparseMatrix<double>& A);
void write_dense_matrix_market(std::ostream& out, const Eigen::MatrixXd& B);

//! Throws InputError when the file is missing or not a real general coordinate matrix.
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);
//! Throws InputError when the file is missing or not a real general array.
Eigen::MatrixXd read_dense_matrix_market(const std::string& path);

}  // namespace coons
