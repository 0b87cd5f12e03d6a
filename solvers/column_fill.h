// A compressed-column sparse matrix filled in one pass, without triplets: for assemblers that know
// the exact number of entries and can list each column's entries in increasing row order (grid
// stencils, free sets). n × n, nnz entries; the caller's count is checked in debug builds.
#pragma once

#include <Eigen/SparseCore>
#include <cassert>

namespace coons::solvers {

//! The n × n matrix whose column c holds what visit(c, emit) passes to emit(row, value), for
//! c = 0 … n−1 in order; rows must increase within a column, and the total must be nnz.
template <class VisitColumn>
Eigen::SparseMatrix<double> matrix_by_columns(Eigen::Index n, Eigen::Index nnz, VisitColumn&& visit) {
  using SpMat = Eigen::SparseMatrix<double>;
  using StorageIndex = SpMat::StorageIndex;
  SpMat A(n, n);
  A.resizeNonZeros(nnz);
  StorageIndex* outer = A.outerIndexPtr();
  StorageIndex* inner = A.innerIndexPtr();
  double* value = A.valuePtr();
  Eigen::Index pos = 0;
  outer[0] = 0;
  for (Eigen::Index c = 0; c < n; ++c) {
    visit(c, [&](Eigen::Index row, double w) {
      assert(pos < nnz);
      inner[pos] = StorageIndex(row);
      value[pos] = w;
      ++pos;
    });
    outer[c + 1] = StorageIndex(pos);
  }
  assert(pos == nnz);
  return A;
}

}  // namespace coons::solvers
