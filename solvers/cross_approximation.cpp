#include "cross_approximation.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace coons::solvers {

CrossApproximation cross_approximation(Eigen::Index m, Eigen::Index n, const EntryLine& row_of, const EntryLine& col_of,
                                       double tolerance, int max_rank, int first_row) {
  const Eigen::Index limit = std::min<Eigen::Index>({m, n, Eigen::Index(std::max(max_rank, 0))});
  Eigen::MatrixXd U(m, limit), V(n, limit);
  std::vector<bool> used(std::size_t(m), false);
  Eigen::Index k = 0, pivot_row = std::clamp<Eigen::Index>(first_row, 0, std::max<Eigen::Index>(m - 1, 0));
  double norm2 = 0;  // ‖U Vᵀ‖²_F of the terms so far
  Eigen::VectorXd row(n), col(m), line_n(n), line_m(m);
  while (k < limit && m > 0) {
    used[std::size_t(pivot_row)] = true;
    row_of(pivot_row, line_n);
    row = line_n - V.leftCols(k) * U.row(pivot_row).head(k).transpose();
    Eigen::Index pivot_col = 0;
    const double largest = row.cwiseAbs().maxCoeff(&pivot_col);
    if (largest > 0) {
      row /= row[pivot_col];
      col_of(pivot_col, line_m);
      col = line_m - U.leftCols(k) * V.row(pivot_col).head(k).transpose();
      U.col(k) = col;
      V.col(k) = row;
      // ‖U Vᵀ‖²_F estimated by Σ_j ‖u_j‖²‖v_j‖², without the cross terms 2Σ_j (u_jᵀu)(v_jᵀv)
      // (Bebendorf & Rjasanow keep them; they halve a step's cost and change the rank by one or
      // two on fast5's blocks)
      const double uu = col.squaredNorm(), vv = row.squaredNorm();
      norm2 += uu * vv;
      ++k;
      if (std::sqrt(uu * vv) <= tolerance * std::sqrt(std::max(norm2, 0.0))) break;
    }
    // the next pivot row: the largest entry of the new column among the rows not used yet (any
    // unused row after a zero residual row)
    Eigen::Index next = -1;
    double best = -1;
    for (Eigen::Index i = 0; i < m; ++i) {
      if (used[std::size_t(i)]) continue;
      const double v = largest > 0 ? std::abs(col[i]) : 0.0;
      if (v > best) {
        best = v;
        next = i;
      }
    }
    if (next < 0) break;
    pivot_row = next;
  }
  return {U.leftCols(k), V.leftCols(k)};
}

CrossApproximation cross_approximation(const Eigen::MatrixXd& A, double tolerance, int max_rank, int first_row) {
  return cross_approximation(
      A.rows(), A.cols(), [&](Eigen::Index i, Eigen::VectorXd& out) { out = A.row(i).transpose(); },
      [&](Eigen::Index j, Eigen::VectorXd& out) { out = A.col(j); }, tolerance, max_rank, first_row);
}

}  // namespace coons::solvers
