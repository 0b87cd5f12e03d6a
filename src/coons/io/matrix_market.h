// Matrix Market output of an assembled mask system, for other solvers and tools.
// The matrix is written as `coordinate real general` (every stored entry, both triangles, by
// Eigen's saveMarket, 17 significant digits: it reads back bit-exactly); the right-hand sides as
// one dense `array real general` file of #rows by 3 (column-major, as the format prescribes).
#pragma once

#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace coons {

void write_matrix_market(const std::string& path, const Eigen::SparseMatrix<double>& A);
void write_dense_matrix_market(const std::string& path, const Eigen::MatrixXd& B);

//! Throws InputError when the file is missing or not a real general coordinate matrix.
Eigen::SparseMatrix<double> read_matrix_market(const std::string& path);
//! Throws InputError when the file is missing or not a real general array.
Eigen::MatrixXd read_dense_matrix_market(const std::string& path);

}  // namespace coons
