#include "energies.h"

#include <cmath>
#include <map>

#include "coons/metrics/bernstein.h"

namespace coons {

namespace {

// Gram matrices are reused across the energies of one net.
class GramCache {
 public:
  const Eigen::MatrixXd& operator()(int k) {
    auto it = cache_.find(k);
    if (it == cache_.end()) it = cache_.emplace(k, bernstein_gram(k)).first;
    return it->second;
  }

 private:
  std::map<int, Eigen::MatrixXd> cache_;
};

double energy(const ControlNet& net, int a, int b, GramCache& gram) {
  if (a > net.m || b > net.n) return 0;
  const ControlNet d = derivative_net(net, a, b);
  const Eigen::MatrixXd& Gu = gram(d.m);
  const Eigen::MatrixXd& Gv = gram(d.n);
  double e = 0;
  for (int c = 0; c < 3; ++c) {
    const Eigen::MatrixXd C = coordinate_grid(d, c);
    e += ((Gu * C) * Gv).cwiseProduct(C).sum();
  }
  return e;
}

}  // namespace

double surface_energy(const ControlNet& net, int a, int b) {
  GramCache gram;
  return energy(net, a, b, gram);
}

double twist_energy(const ControlNet& net) { return surface_energy(net, 1, 1); }

double dirichlet_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 1, 0, g) + energy(net, 0, 1, g);
}

double thin_plate_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 2, 0, g) + 2 * energy(net, 1, 1, g) + energy(net, 0, 2, g);
}

double e3_energy(const ControlNet& net) {
  GramCache g;
  return energy(net, 3, 0, g) + 3 * energy(net, 2, 1, g) + 3 * energy(net, 1, 2, g) +
         energy(net, 0, 3, g);
}

double discrete_twist_energy(const ControlNet& net) {
  double e = 0;
  for (int i = 0; i < net.m; ++i)
    for (int j = 0; j < net.n; ++j)
      e += (net.at(i + 1, j + 1) - net.at(i + 1, j) - net.at(i, j + 1) + net.at(i, j)).squaredNorm();
  return e;
}

double discrete_dirichlet_energy(const ControlNet& net) {
  double e = 0;
  for (int i = 0; i <= net.m; ++i)
    for (int j = 0; j <= net.n; ++j) {
      if (i < net.m) e += (net.at(i + 1, j) - net.at(i, j)).squaredNorm();
      if (j < net.n) e += (net.at(i, j + 1) - net.at(i, j)).squaredNorm();
    }
  return e;
}

double mask_residual(const ControlNet& net, const Mask9& mask) {
  double worst = 0;
  for (int i = 1; i < net.m; ++i)
    for (int j = 1; j < net.n; ++j) {
      const Eigen::RowVector3d edge_i = net.at(i - 1, j) + net.at(i + 1, j);
      const Eigen::RowVector3d edge_j = net.at(i, j - 1) + net.at(i, j + 1);
      const Eigen::RowVector3d diag =
          net.at(i - 1, j - 1) + net.at(i + 1, j - 1) + net.at(i - 1, j + 1) + net.at(i + 1, j + 1);
      const Eigen::RowVector3d r =
          net.at(i, j) - mask.edge_i * edge_i - mask.edge_j * edge_j - mask.diag * diag;
      worst = std::max(worst, r.cwiseAbs().maxCoeff());
    }
  return worst;
}

NetMetrics net_metrics(const ControlNet& net, const Mask9& mask) {
  GramCache g;
  NetMetrics out;
  const double e11 = energy(net, 1, 1, g);
  out.twist_energy = e11;
  out.dirichlet_energy = energy(net, 1, 0, g) + energy(net, 0, 1, g);
  out.thin_plate_energy = energy(net, 2, 0, g) + 2 * e11 + energy(net, 0, 2, g);
  out.e3_energy = energy(net, 3, 0, g) + 3 * energy(net, 2, 1, g) + 3 * energy(net, 1, 2, g) +
                  energy(net, 0, 3, g);
  out.discrete_twist_energy = discrete_twist_energy(net);
  out.discrete_dirichlet_energy = discrete_dirichlet_energy(net);
  out.mask_residual = mask_residual(net, mask);
  return out;
}

}  // namespace coons
