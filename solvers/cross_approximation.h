// Adaptive cross approximation with partial pivoting: A ≈ U Vᵀ from a few of A's rows and
// columns (each step takes the residual's row at the pivot row, its largest entry's column, and
// the next pivot row where that column's residual is largest), stopping when the new rank-one
// term falls below `tolerance` times the Frobenius norm of the approximation so far (estimated
// by the sum of the terms' norms squared). O((m + n)·k²)
// flops for rank k, and m + n entries of A per step: nothing of the size of A is formed. The
// stopping test is an estimate; users that need a guarantee check the result (fast5 uses it as a
// preconditioner, whose quality only changes the number of iterations).
// Based on: M. Bebendorf, Approximation of boundary element matrices, Numer. Math. 86 (2000)
// 565–589, and M. Bebendorf & S. Rjasanow, Adaptive low-rank approximation of collocation
// matrices, Computing 70 (2003) 1–24.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace coons::solvers {

struct CrossApproximation {
  Eigen::MatrixXd U;  //!< m × k
  Eigen::MatrixXd V;  //!< n × k: A ≈ U Vᵀ
};

//! Writes row i (#n) or column j (#m) of A into its second argument (sized by the caller).
using EntryLine = std::function<void(Eigen::Index, Eigen::VectorXd&)>;

//! The partially pivoted adaptive cross approximation of A (m × n, given by its rows and columns)
//! to relative `tolerance` (Frobenius, estimated), of rank at most `max_rank`, starting at row
//! `first_row`. Rank 0 for a zero matrix.
CrossApproximation cross_approximation(Eigen::Index m, Eigen::Index n, const EntryLine& row_of, const EntryLine& col_of,
                                       double tolerance, int max_rank, int first_row = 0);

//! The same of a stored A.
CrossApproximation cross_approximation(const Eigen::MatrixXd& A, double tolerance, int max_rank, int first_row = 0);

}  // namespace coons::solvers
