#include "fast5_near_columns.h"

namespace coons::solvers::fast5_detail {

void prepare_near_columns(int rows, int cols, int count, NearColumns& near) {
  near.rows = rows;
  near.cols = cols;
  near.x_cols.clear();
  for (int j = 0; j < cols; ++j)
    if (j < 5 || j >= cols - 5) near.x_cols.push_back(j);
  for (int c = 0; c < count; ++c) near.x[std::size_t(c)].resize(rows, Eigen::Index(near.x_cols.size()));
}

void gather_b_columns(const Eigen::MatrixX3d& B, const std::array<EdgeRows, 3>* edges, int count,
                      const std::vector<int>& checked, NearColumns& near) {
  const int R = near.rows, C = near.cols;
  const auto nb = Eigen::Index(checked.size());
  for (int c = 0; c < count; ++c) {
    Eigen::MatrixXd& bg = near.b[std::size_t(c)];
    bg.resize(R, nb);
    const EdgeRows* f = edges ? &(*edges)[std::size_t(c)] : nullptr;
    for (int i = 0; i < R; ++i)
      for (Eigen::Index k = 0; k < nb; ++k) {
        const int j = checked[std::size_t(k)];
        if (!f || f->slot[std::size_t(i)] >= 0) {
          bg(i, k) = B(Eigen::Index(i) * C + j, c);
          continue;
        }
        const auto& e = f->ends[std::size_t(i)];
        bg(i, k) = j == 0 ? e[0] : j == 1 ? e[1] : j == C - 2 ? e[2] : j == C - 1 ? e[3] : 0.0;
      }
  }
}

Eigen::VectorXd column_residual(const NearColumns& near, const std::array<double, 25>& stencil, int j, int k, int c) {
  const int R = near.rows, C = near.cols;
  Eigen::VectorXd r = near.b[std::size_t(c)].col(k);
  const Eigen::MatrixXd& xg = near.x[std::size_t(c)];
  for (int di = -2; di <= 2; ++di)
    for (int dj = -2; dj <= 2; ++dj) {
      const int jj = j + dj;
      if (jj < 0 || jj >= C) continue;
      const double w = stencil[std::size_t(di + 2) * 5 + std::size_t(dj + 2)];
      const int i0 = std::max(0, -di), i1 = std::min(R, R - di);
      const double* xs = xg.col(near.index(jj)).data();  // row i + di of column jj
      for (int i = i0; i < i1; ++i) r[i] -= w * xs[i + di];
    }
  return r;
}

}  // namespace coons::solvers::fast5_detail
