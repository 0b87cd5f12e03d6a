// What the hypre backends share (internal to solvers/, built with hypre only): the communicator
// and the all-gather of a solution split by blocks of rows.
#pragma once

#include <mpi.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "mpi_runtime.h"

namespace coons::solvers::hypre_detail {

//! Every rank of MPI_COMM_WORLD (started on first use: a singleton run is one rank).
inline MPI_Comm communicator() {
  ensure_mpi();
  return MPI_COMM_WORLD;
}

//! global = the concatenation of every rank's `local` block: block_of(rows, rank, size) rows of
//! row_length values each (matrix rows: 1; grid rows: the grid's columns).
inline void all_gather_blocks(const std::vector<double>& local, long long rows, long long row_length,
                              std::vector<double>& global) {
  const int size = mpi_size();
  std::vector<int> counts(std::size_t(size), 0), displacements(std::size_t(size), 0);
  for (int r = 0; r < size; ++r) {
    const auto [first, last] = block_of(rows, r, size);
    counts[std::size_t(r)] = int((last - first) * row_length);
    displacements[std::size_t(r)] = int(first * row_length);
  }
  global.assign(std::size_t(rows * row_length), 0.0);
  MPI_Allgatherv(local.data(), int(local.size()), MPI_DOUBLE, global.data(), counts.data(), displacements.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
}

}  // namespace coons::solvers::hypre_detail
