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

namespace coons {

double mask_residual(const ControlNet& net, const FreeGrid& free, const Stencil& stencil) {
  const int r = stencil.radius;
  double worst = 0;
  for (int i = r; i <= net.m - r; ++i)
    for (int j = r; j <= net.n - r; ++j) {
      if (!free(i, j)) continue;
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (int a = -r; a <= r; ++a)
        for (int b = -r; b <= r; ++b)
          if (const double w = stencil.at(a, b); w != 0) sum += w * net.at(i + a, j + b);
      worst = std::max(worst, sum.cwiseAbs().maxCoeff());
    }
  return worst;
}

}  // namespace coons
