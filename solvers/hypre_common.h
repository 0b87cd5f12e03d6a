// What the hypre backends share (internal to solvers/, built with hypre only): the communicator,
// the all-gather of a solution split by blocks of rows, and the solve of the three right-hand sides
// one at a time with its one verdict.
#pragma once

#include <HYPRE_utilities.h>
#include <mpi.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "iteration_summary.h"
#include "linear_solver.h"
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

//! A hypre backend: the iteration limit and the column-by-column solve both hypre interfaces use.
class HypreBackend : public LinearSolver {
 public:
  using LinearSolver::LinearSolver;

 protected:
  //! options.max_iterations, or 500 when it is 0.
  [[nodiscard]] int limit() const { return options_.max_iterations > 0 ? options_.max_iterations : 500; }

  //! One column's solve as hypre reports it.
  struct ColumnSolve {
    HYPRE_Int error = 0;  //!< the solve's error flag
    HYPRE_Int iterations = 0;
    double residual = 0;         //!< hypre's final relative residual norm
    const char* method = "PCG";  //!< hypre's Krylov method, for messages
  };

  //! X column by column: solve(c) → ColumnSolve for each non-zero column c of B (a zero column
  //! has x = 0 exactly), then, hypre's error flags cleared, read(c) writes X.col(c). One verdict
  //! (finish_iteration): the most iterations and the largest residual over the columns, converged
  //! by hypre's own test on each (any error flag is no convergence), diverged where X is not
  //! finite. A column that stopped on an error flag before the iteration limit (a breakdown: hypre's
  //! PCG flags a zero or negative pᵀAp or rᵀCr, or a subnormal step, with the flag of the limit,
  //! HYPRE_ERROR_CONV) makes the solve kFailure, its message naming the flag, the iterations and the
  //! residual of that column, not the limit; at a true residual within the tolerance it is
  //! kSuccess, at one of at most kStagnationFloor (iteration_summary.h) the iteration stagnating
  //! under a tolerance below rounding: kNotConverged, "stagnated".
  template <class Solve, class Read>
  SolveStatus solve_columns(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary, Solve&& solve,
                            Read&& read) {
    X.setZero(B.rows(), 3);
    IterationEnd end;
    end.limit = limit();
    end.krylov = true;  // hypre's PCG or GMRES, preconditioned by its multigrid
    end.converged = true;
    end.residual = 0;
    std::optional<std::pair<int, ColumnSolve>> broken;  // the first column that broke down
    std::optional<ColumnSolve> early;                   // a column that stopped short, unflagged
    for (int c = 0; c < 3; ++c) {
      if (B.col(c).isZero(0)) continue;  // x = 0 exactly
      const ColumnSolve column = solve(c);
      HYPRE_ClearAllErrors();
      read(c);
      end.iterations = std::max(end.iterations, int(column.iterations));
      end.residual = std::max(end.residual, std::isfinite(column.residual) ? column.residual : HUGE_VAL);
      const bool met = column.error == 0 && column.residual <= options_.tolerance && X.col(c).allFinite();
      end.converged = end.converged && met;
      if (!broken && broke_down(column, end.limit)) broken.emplace(c, column);
      if (!met && column.error == 0 && column.iterations < end.limit && !early) early = column;
    }
    // hypre stopped before the limit without a flag and above the tolerance (GMRES after 336 of
    // 500 iterations on an indefinite system): not "iteration limit 500 reached"
    if (early && !broken)
      end.stagnation = "hypre's " + std::string(early->method) + " stopped after " + std::to_string(early->iterations) +
                       " iterations, before the limit, with its own relative " + "residual " +
                       format_g(early->residual);
    if (!X.allFinite()) {
      end.diverged = true;
      end.residual = HUGE_VAL;
    }
    if (!broken || end.diverged) return finish_iteration(end, X, summary);
    // hypre's residual of a broken-down solve is not the iterate's (with logging off, PCG that
    // stops in its first iteration reports 0 for an X that is still 0): the true one is reported.
    Eigen::MatrixXd AX;
    if (apply_operator(factorized_operator(), X, AX)) {
      auto& [c, column] = *broken;
      column.residual = relative_norm(AX.col(c) - B.col(c), B.col(c));
      end.residual = max_relative_norm(AX - B, B);
      // hypre's PCG flags a step too small to change x: with the true residual within the
      // tolerance that is a success, near the rounding floor (a tolerance of 1e-300, say) the
      // iteration stagnating, and only above it a breakdown of the method.
      if (end.residual <= options_.tolerance) {
        end.converged = true;
        return finish_iteration(end, X, summary);
      }
      if (end.residual <= kStagnationFloor) {
        end.converged = false;
        end.stagnation = "hypre's " + std::string(column.method) + " stopped with error flag " +
                         std::to_string(column.error) + " at the rounding floor";
        return finish_iteration(end, X, summary);
      }
    }
    summary.iterations = end.iterations;
    summary.relative_residual = end.residual;
    summary.message = breakdown_message(broken->second, end.limit);
    return SolveStatus::kFailure;
  }

 private:
  //! True when hypre flagged an error other than running into the iteration limit.
  static bool broke_down(const ColumnSolve& column, int limit) {
    return column.error != 0 && !(column.error == HYPRE_ERROR_CONV && column.iterations >= limit);
  }

  //! "breakdown: residual R after N iterations (hypre's PCG stopped with error flag 256, did not
  //! converge, before the iteration limit L; tolerance T)".
  [[nodiscard]] std::string breakdown_message(const ColumnSolve& column, int limit) const {
    std::string flags;
    for (const auto& [bit, what] : {std::pair{HYPRE_ERROR_GENERIC, "generic error"},
                                    {HYPRE_ERROR_MEMORY, "out of memory"},
                                    {HYPRE_ERROR_ARG, "bad argument"},
                                    {HYPRE_ERROR_CONV, "did not converge"}})
      if (column.error & bit) flags += std::string(flags.empty() ? "" : " and ") + what;
    if (flags.empty()) flags = "unknown error";
    const int n = int(column.iterations);
    return "breakdown: residual " + format_g(column.residual) + " after " + std::to_string(n) + " iteration" +
           (n == 1 ? "" : "s") + " (hypre's " + column.method + " stopped with error flag " +
           std::to_string(column.error) + ", " + flags + ", before the iteration limit " + std::to_string(limit) +
           "; tolerance " + format_g(options_.tolerance) + ")";
  }
};

}  // namespace coons::solvers::hypre_detail
