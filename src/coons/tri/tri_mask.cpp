#include "coons/tri/tri_mask.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace coons::tri {

std::optional<double> bubble_singular_c(int n) {
  if (n < 4) return std::nullopt;
  return -1.0 / 6.0 - 1.0 / (2.0 * (n - 3));
}

bool TriMask::is_valid(std::string* why) const {
  if (std::isfinite(c)) return true;
  if (why) *why = "c must be a finite number";
  return false;
}

const std::array<TriStencilEntry, 9>& tri_stencil() {
  static const std::array<TriStencilEntry, 9> entries = {{
      {{1, -1, 0}, true},
      {{-1, 1, 0}, true},
      {{1, 0, -1}, true},
      {{-1, 0, 1}, true},
      {{0, 1, -1}, true},
      {{0, -1, 1}, true},
      {{2, -1, -1}, false},
      {{-1, 2, -1}, false},
      {{-1, -1, 2}, false},
  }};
  return entries;
}

namespace {

// Mask applied to the whole net at interior point (i, j, k) with weights (wa, wc).
Eigen::RowVector3d apply_at(const TriNet& net, int i, int j, int k, double wa, double wc) {
  Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
  for (const auto& e : tri_stencil())
    sum += (e.neighbour ? wa : wc) * net.at(i + e.offset[0], j + e.offset[1], k + e.offset[2]);
  return sum;
}

template <class F>
void for_each_interior(int n, F&& f) {
  for (int k = 1; k <= n - 2; ++k)
    for (int j = 1; j <= n - 1 - k; ++j) f(n - k - j, j, k);
}

}  // namespace

TriMaskSystem assemble_tri_mask_system(const TriNet& net, const TriMask& mask) {
  const int n = net.n;
  const Eigen::Index size = interior_size(n);
  const double wa = mask.a(), wc = mask.c;
  TriMaskSystem sys;
  sys.A.resize(size, size);
  sys.B = Eigen::MatrixX3d::Zero(size, 3);
  sys.A.reserve(10 * size);
  std::vector<std::pair<Eigen::Index, double>> column;
  // Column of unknown β: the rows α = β − d whose stencil reaches β (and the diagonal).
  for_each_interior(n, [&](int i, int j, int k) {
    const Eigen::Index col = interior_index(n, j, k);
    column.clear();
    column.emplace_back(col, 1.0);
    for (const auto& e : tri_stencil()) {
      const int ri = i - e.offset[0], rj = j - e.offset[1], rk = k - e.offset[2];
      if (is_interior(n, ri, rj, rk)) column.emplace_back(interior_index(n, rj, rk), -(e.neighbour ? wa : wc));
    }
    std::sort(column.begin(), column.end());
    sys.A.startVec(col);
    for (const auto& [row, value] : column) sys.A.insertBack(row, col) = value;
  });
  sys.A.finalize();
  // Right-hand side: the stencil entries that fall on the boundary.
  for_each_interior(n, [&](int i, int j, int k) {
    const Eigen::Index row = interior_index(n, j, k);
    for (const auto& e : tri_stencil()) {
      const int ni = i + e.offset[0], nj = j + e.offset[1], nk = k + e.offset[2];
      if (!is_interior(n, ni, nj, nk)) sys.B.row(row) += (e.neighbour ? wa : wc) * net.at(ni, nj, nk);
    }
  });
  return sys;
}

Eigen::MatrixX3d tri_mask_sensitivity_rhs(const TriNet& solved) {
  const int n = solved.n;
  Eigen::MatrixX3d R = Eigen::MatrixX3d::Zero(interior_size(n), 3);
  for_each_interior(n, [&](int i, int j, int k) {
    R.row(interior_index(n, j, k)) = apply_at(solved, i, j, k, -0.5, 1.0);  // d a/dc = −1/2, d c/dc = 1
  });
  return R;
}

Eigen::MatrixX3d interior_of(const TriNet& net) {
  const int n = net.n;
  Eigen::MatrixX3d X(interior_size(n), 3);
  for_each_interior(n, [&](int i, int j, int k) { X.row(interior_index(n, j, k)) = net.at(i, j, k); });
  return X;
}

TriNet fill_interior(TriNet net, const Eigen::MatrixX3d& X) {
  const int n = net.n;
  for_each_interior(n, [&](int i, int j, int k) { net.at(i, j, k) = X.row(interior_index(n, j, k)); });
  return net;
}

double tri_mask_residual(const TriNet& net, const TriMask& mask) {
  double worst = 0;
  for_each_interior(net.n, [&](int i, int j, int k) {
    const Eigen::RowVector3d r = net.at(i, j, k) - apply_at(net, i, j, k, mask.a(), mask.c);
    worst = std::max(worst, r.cwiseAbs().maxCoeff());
  });
  return worst;
}

TriMaskFit fit_tri_mask(const TriNet& net) {
  double rs = 0, ss = 0, scale = 0;  // r(c) = r0 + c·s with r0 = b − ΣN/6 and s = ΣN/2 − ΣC
  for_each_interior(net.n, [&](int i, int j, int k) {
    const Eigen::RowVector3d r0 = net.at(i, j, k) - apply_at(net, i, j, k, 1.0 / 6, 0.0);
    const Eigen::RowVector3d half_neighbours = apply_at(net, i, j, k, 0.5, 0.0), far = apply_at(net, i, j, k, 0.0, 1.0);
    const Eigen::RowVector3d s = half_neighbours - far;
    rs += r0.dot(s);
    ss += s.squaredNorm();
    scale += half_neighbours.squaredNorm() + far.squaredNorm();
  });
  TriMaskFit fit;
  if (ss <= 1e-24 * scale) {  // s vanishes (to rounding) on affine nets
    fit.determined = false;
  } else {
    fit.c = -rs / ss;
  }
  fit.residual = tri_mask_residual(net, TriMask{fit.c});
  return fit;
}

}  // namespace coons::tri
