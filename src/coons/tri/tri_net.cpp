#include "coons/tri/tri_net.h"

#include <utility>
#include <vector>

namespace coons::tri {

namespace {

// One de Casteljau step with weights (w1, w2, w3): degree m → m − 1,
// b'_β = w1 b_{β+e1} + w2 b_{β+e2} + w3 b_{β+e3}.
TriNet casteljau_step(const TriNet& net, const Eigen::Vector3d& w) {
  const int m = net.n;
  TriNet out(m - 1);
  for (int k = 0; k <= m - 1; ++k)
    for (int j = 0; j <= m - 1 - k; ++j)
      out.points.row(net_index(m - 1, j, k)) = w(0) * net.points.row(net_index(m, j, k)) +
                                               w(1) * net.points.row(net_index(m, j + 1, k)) +
                                               w(2) * net.points.row(net_index(m, j, k + 1));
  return out;
}

}  // namespace

TriBoundary boundary_of(const TriNet& net, std::string name) {
  const int n = net.n;
  TriBoundary b;
  b.name = std::move(name);
  b.n = n;
  for (auto& side : b.sides) side.resize(n + 1, 3);
  for (int t = 0; t <= n; ++t) {
    b.sides[0].row(t) = net.at(n - t, t, 0);
    b.sides[1].row(t) = net.at(0, n - t, t);
    b.sides[2].row(t) = net.at(t, 0, n - t);
  }
  return b;
}

std::pair<Eigen::RowVector3d, Eigen::RowVector3d> boundary_box(const TriNet& net) {
  const TriBoundary b = boundary_of(net);
  Eigen::RowVector3d lo = b.sides[0].colwise().minCoeff(), hi = b.sides[0].colwise().maxCoeff();
  for (int s = 1; s < 3; ++s) {
    lo = lo.cwiseMin(b.sides[s].colwise().minCoeff());
    hi = hi.cwiseMax(b.sides[s].colwise().maxCoeff());
  }
  return {lo, hi};
}

Eigen::RowVector3d boundary_centre(const TriNet& net) {
  const auto [lo, hi] = boundary_box(net);
  return 0.5 * lo + 0.5 * hi;
}

TriNet frame_net(const TriBoundary& boundary) {
  const int n = boundary.n;
  TriNet net(n);
  for (int t = 0; t <= n; ++t) {
    net.at(n - t, t, 0) = boundary.sides[0].row(t);
    net.at(0, n - t, t) = boundary.sides[1].row(t);
    net.at(t, 0, n - t) = boundary.sides[2].row(t);
  }
  return net;
}

TriCornerGap largest_corner_gap(const TriBoundary& boundary) {
  const int n = boundary.n;
  const auto& s = boundary.sides;
  const std::pair<const char*, double> gaps[] = {
      {"b[n][0][0]", (s[2].row(n) - s[0].row(0)).norm()},
      {"b[0][n][0]", (s[0].row(n) - s[1].row(0)).norm()},
      {"b[0][0][n]", (s[1].row(n) - s[2].row(0)).norm()},
  };
  TriCornerGap worst{gaps[0].first, gaps[0].second};
  for (const auto& [corner, gap] : gaps)
    if (gap > worst.gap) worst = {corner, gap};
  return worst;
}

Eigen::RowVector3d evaluate(const TriNet& net, const Eigen::Vector3d& uvw) {
  TriNet level = net;
  while (level.n > 0) level = casteljau_step(level, uvw);
  return level.points.row(0);
}

TriNet derivative_net(const TriNet& net, const Eigen::Vector3d& d) {
  if (net.n == 0) return TriNet(0);
  TriNet out = casteljau_step(net, d);
  out.points *= net.n;
  return out;
}

Eigen::RowVector3d directional_derivative(const TriNet& net, const Eigen::Vector3d& uvw, const Eigen::Vector3d& d) {
  return evaluate(derivative_net(net, d), uvw);
}

Eigen::RowVector3d second_directional_derivative(const TriNet& net, const Eigen::Vector3d& uvw,
                                                 const Eigen::Vector3d& d1, const Eigen::Vector3d& d2) {
  return evaluate(derivative_net(derivative_net(net, d1), d2), uvw);
}

TriNet elevate_degree(const TriNet& net, int times) {
  TriNet cur = net;
  for (int t = 0; t < times; ++t) {
    const int n = cur.n;
    TriNet up(n + 1);
    for (int k = 0; k <= n + 1; ++k)
      for (int j = 0; j <= n + 1 - k; ++j) {
        const int i = n + 1 - k - j;
        Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
        if (i > 0) p += i * cur.at(i - 1, j, k);
        if (j > 0) p += j * cur.at(i, j - 1, k);
        if (k > 0) p += k * cur.at(i, j, k - 1);
        up.at(i, j, k) = p / double(n + 1);
      }
    cur = std::move(up);
  }
  return cur;
}

std::array<TriNet, 3> subdivide_at(const TriNet& net, const Eigen::Vector3d& uvw) {
  const int n = net.n;
  std::vector<TriNet> levels{net};  // levels[r]: degree n − r, blossom(P^r, ·)
  for (int r = 1; r <= n; ++r) levels.push_back(casteljau_step(levels.back(), uvw));
  std::array<TriNet, 3> parts{TriNet(n), TriNet(n), TriNet(n)};
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n - k; ++j) {
      const int i = n - k - j;
      parts[0].at(i, j, k) = levels[i].at(0, j, k);
      parts[1].at(i, j, k) = levels[j].at(i, 0, k);
      parts[2].at(i, j, k) = levels[k].at(i, j, 0);
    }
  return parts;
}

TriNet sub_net(const TriNet& net, int i0, int j0, int k0) {
  const int m = net.n - i0 - j0 - k0;
  TriNet out(m);
  for (int k = 0; k <= m; ++k)
    for (int j = 0; j <= m - k; ++j) out.at(m - k - j, j, k) = net.at(i0 + m - k - j, j0 + j, k0 + k);
  return out;
}

TriNet permuted(const TriNet& net, const std::array<int, 3>& perm) {
  const int n = net.n;
  TriNet out(n);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n - k; ++j) {
      const int old_index[3] = {n - k - j, j, k};
      int new_index[3] = {0, 0, 0};
      for (int m = 0; m < 3; ++m) new_index[perm[m]] = old_index[m];
      out.at(new_index[0], new_index[1], new_index[2]) = net.at(old_index[0], j, k);
    }
  return out;
}

}  // namespace coons::tri
