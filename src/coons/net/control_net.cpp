#include "control_net.h"

#include <cmath>

namespace coons {

Eigen::RowVector3d unit_scaled(const Eigen::RowVector3d& v) {
  const double top = v.cwiseAbs().maxCoeff();
  if (!(top > 0) || !std::isfinite(top)) return v;
  const int e = std::ilogb(top);
  return v.unaryExpr([e](double x) { return std::ldexp(x, -e); });
}

double scaled_norm(const Eigen::RowVector3d& v) {
  const double top = v.cwiseAbs().maxCoeff();
  if (!(top > 0) || !std::isfinite(top)) return v.norm();
  return std::ldexp(unit_scaled(v).norm(), std::ilogb(top));
}

Boundary boundary_of(const ControlNet& net, std::string name) {
  Boundary b;
  b.name = std::move(name);
  b.m = net.m;
  b.n = net.n;
  b.bottom.resize(net.m + 1, 3);
  b.top.resize(net.m + 1, 3);
  b.left.resize(net.n + 1, 3);
  b.right.resize(net.n + 1, 3);
  for (int i = 0; i <= net.m; ++i) {
    b.bottom.row(i) = net.at(i, 0);
    b.top.row(i) = net.at(i, net.n);
  }
  for (int j = 0; j <= net.n; ++j) {
    b.left.row(j) = net.at(0, j);
    b.right.row(j) = net.at(net.m, j);
  }
  return b;
}

ControlNet frame_net(const Boundary& b) {
  ControlNet net(b.m, b.n);
  for (int j = 0; j <= b.n; ++j) {
    net.at(0, j) = b.left.row(j);
    net.at(b.m, j) = b.right.row(j);
  }
  for (int i = 0; i <= b.m; ++i) {
    net.at(i, 0) = b.bottom.row(i);
    net.at(i, b.n) = b.top.row(i);
  }
  return net;
}

CornerGap largest_corner_gap(const Boundary& b) {
  const CornerGap gaps[] = {
      {"bottom-left", scaled_norm(b.bottom.row(0) - b.left.row(0))},
      {"bottom-right", scaled_norm(b.bottom.row(b.m) - b.right.row(0))},
      {"top-left", scaled_norm(b.top.row(0) - b.left.row(b.n))},
      {"top-right", scaled_norm(b.top.row(b.m) - b.right.row(b.n))},
  };
  CornerGap worst = gaps[0];
  for (const auto& g : gaps)
    if (g.gap > worst.gap) worst = g;
  return worst;
}

Eigen::RowVector3d bounding_box_centre(const Eigen::MatrixX3d& points) {
  if (points.rows() == 0 || !points.allFinite()) return Eigen::RowVector3d::Zero();
  const Eigen::RowVector3d lo = points.colwise().minCoeff(), hi = points.colwise().maxCoeff();
  return lo + 0.5 * (hi - lo);
}

Eigen::RowVector3d bounding_box_centre(const Boundary& b) {
  Eigen::MatrixX3d all(b.bottom.rows() + b.top.rows() + b.left.rows() + b.right.rows(), 3);
  all << b.bottom, b.top, b.left, b.right;
  return bounding_box_centre(all);
}

double bounding_box_diagonal(const Boundary& b) {
  Eigen::RowVector3d lo = b.bottom.colwise().minCoeff(), hi = b.bottom.colwise().maxCoeff();
  for (const Eigen::MatrixX3d* side : {&b.top, &b.left, &b.right}) {
    lo = lo.cwiseMin(side->colwise().minCoeff());
    hi = hi.cwiseMax(side->colwise().maxCoeff());
  }
  return scaled_norm(hi - lo);
}

}  // namespace coons
