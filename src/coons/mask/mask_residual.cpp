#include "mask_residual.h"

#include <algorithm>

namespace coons {

double mask_residual(const ControlNet& net, const Mask9& mask) {
  double worst = 0;
  for (int i = 1; i < net.m; ++i)
    for (int j = 1; j < net.n; ++j) {
      const Eigen::RowVector3d edge_i = net.at(i - 1, j) + net.at(i + 1, j);
      const Eigen::RowVector3d edge_j = net.at(i, j - 1) + net.at(i, j + 1);
      const Eigen::RowVector3d diag =
          net.at(i - 1, j - 1) + net.at(i + 1, j - 1) + net.at(i - 1, j + 1) + net.at(i + 1, j + 1);
      const Eigen::RowVector3d r = net.at(i, j) - mask.edge_i * edge_i - mask.edge_j * edge_j - mask.diag * diag;
      worst = std::max(worst, r.cwiseAbs().maxCoeff());
    }
  return worst;
}

}  // namespace coons
