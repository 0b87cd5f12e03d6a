#include "assemble_mask_system.h"

namespace coons {

Eigen::MatrixX3d mask_rhs(const ControlNet& net, const Mask9& mask) {
  const int m = net.m, n = net.n, cols = n - 1;
  const Eigen::Index N = Eigen::Index(std::max(m - 1, 0)) * std::max(n - 1, 0);
  Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(N, 3);
  if (N == 0) return B;
  auto on_frame = [&](int i, int j) { return i == 0 || i == m || j == 0 || j == n; };
  auto add_known = [&](int i, int j) {
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        if (di == 0 && dj == 0) continue;
        if (!on_frame(i + di, j + dj)) continue;
        const double w = di == 0 ? mask.edge_j : (dj == 0 ? mask.edge_i : mask.diag);
        sum += w * net.at(i + di, j + dj);
      }
    B.row(Eigen::Index(i - 1) * cols + (j - 1)) = sum;
  };
  // Only the ring of interior points next to the frame has known neighbours.
  for (int j = 1; j < n; ++j) {
    add_known(1, j);
    if (m - 1 > 1) add_known(m - 1, j);
  }
  for (int i = 2; i < m - 1; ++i) {
    add_known(i, 1);
    if (n - 1 > 1) add_known(i, n - 1);
  }
  return B;
}

MaskSystem assemble_mask_system(const ControlNet& net, const Mask9& mask, bool with_matrix) {
  MaskSystem system;
  system.stencil = mask_stencil(mask, std::max(net.m - 1, 0), std::max(net.n - 1, 0));
  if (with_matrix) system.A = solvers::stencil_matrix(system.stencil);
  system.B = mask_rhs(net, mask);
  return system;
}

ControlNet fill_interior(ControlNet net, const Eigen::MatrixX3d& X) {
  const int cols = net.n - 1;
  for (int i = 1; i < net.m; ++i)
    net.points.middleRows(net.index(i, 1), cols) = X.middleRows(Eigen::Index(i - 1) * cols, cols);
  return net;
}

Eigen::MatrixX3d interior_of(const ControlNet& net) {
  const int cols = net.n - 1;
  Eigen::MatrixX3d X(Eigen::Index(std::max(net.m - 1, 0)) * std::max(cols, 0), 3);
  for (int i = 1; i < net.m; ++i)
    X.middleRows(Eigen::Index(i - 1) * cols, cols) = net.points.middleRows(net.index(i, 1), cols);
  return X;
}

}  // namespace coons
