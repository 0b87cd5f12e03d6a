#include "grid_stencil.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "column_fill.h"

namespace coons::solvers {

double stencil_eigenvalue(const GridStencil& s, int p, int q) {
  const double x = std::cos(M_PI * p / (s.rows + 1));
  const double y = std::cos(M_PI * q / (s.cols + 1));
  return s.center + 2 * s.edge_i * x + 2 * s.edge_j * y + 4 * s.diag * x * y;
}

std::pair<double, double> stencil_eigenvalue_range(const GridStencil& s) {
  // λ is bilinear in (x, y) = (cos pπ/(rows+1), cos qπ/(cols+1)), so its extremes over the grid of
  // modes sit at the four extreme modes p ∈ {1, rows}, q ∈ {1, cols}.
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int p : {1, s.rows})
    for (int q : {1, s.cols}) {
      const double l = stencil_eigenvalue(s, p, q);
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
  return {lo, hi};
}

void apply_stencil(const GridStencil& s, const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) {
  const int R = s.rows, C = s.cols;
  Y.resize(X.rows(), X.cols());
  for (Eigen::Index k = 0; k < X.cols(); ++k) {
    const double* x = X.col(k).data();
    double* y = Y.col(k).data();
    for (int i = 0; i < R; ++i) {
      const double* up = i > 0 ? x + Eigen::Index(i - 1) * C : nullptr;
      const double* mid = x + Eigen::Index(i) * C;
      const double* down = i + 1 < R ? x + Eigen::Index(i + 1) * C : nullptr;
      double* out = y + Eigen::Index(i) * C;
      for (int j = 0; j < C; ++j) {
        double ej = 0, ei = 0, dg = 0;
        if (j > 0) ej += mid[j - 1];
        if (j + 1 < C) ej += mid[j + 1];
        if (up) {
          ei += up[j];
          if (j > 0) dg += up[j - 1];
          if (j + 1 < C) dg += up[j + 1];
        }
        if (down) {
          ei += down[j];
          if (j > 0) dg += down[j - 1];
          if (j + 1 < C) dg += down[j + 1];
        }
        out[j] = s.center * mid[j] + s.edge_i * ei + s.edge_j * ej + s.diag * dg;
      }
    }
  }
}

namespace {

// Visits the stored entries of column k = (i, j) in increasing row order, calling f(row, weight).
// By symmetry column k holds the same entries as row k.
template <class F>
void for_each_in_column(const GridStencil& s, int i, int j, F&& f) {
  const int C = s.cols;
  for (int di = -1; di <= 1; ++di) {
    const int ii = i + di;
    if (ii < 0 || ii >= s.rows) continue;
    for (int dj = -1; dj <= 1; ++dj) {
      const int jj = j + dj;
      if (jj < 0 || jj >= C) continue;
      const double w = di == 0 ? (dj == 0 ? s.center : s.edge_j) : (dj == 0 ? s.edge_i : s.diag);
      f(Eigen::Index(ii) * C + jj, w);
    }
  }
}

}  // namespace

Eigen::SparseMatrix<double> stencil_matrix(const GridStencil& s) {
  // Count the entries of each column (3×3 minus what falls off the grid).
  auto span = [](int k, int len) { return 1 + (k > 0) + (k + 1 < len); };
  Eigen::Index nnz = 0;
  for (int i = 0; i < s.rows; ++i)
    for (int j = 0; j < s.cols; ++j) nnz += span(i, s.rows) * span(j, s.cols);
  return matrix_by_columns(s.size(), nnz, [&](Eigen::Index k, const auto& emit) {
    for_each_in_column(s, int(k / s.cols), int(k % s.cols), emit);
  });
}

void refill_stencil_matrix(const GridStencil& s, Eigen::SparseMatrix<double>& A) {
  assert(A.rows() == s.size() && A.isCompressed());
  double* value = A.valuePtr();
  Eigen::Index pos = 0;
  for (int i = 0; i < s.rows; ++i)
    for (int j = 0; j < s.cols; ++j) for_each_in_column(s, i, j, [&](Eigen::Index, double w) { value[pos++] = w; });
}

}  // namespace coons::solvers
