#include "coons/tri/tri_energy.h"

#include <utility>
#include <vector>

#include "coons/metrics/scaled_energy.h"
#include "coons/net/quadrature.h"

namespace coons::tri {

namespace {

double binomial(int n, int r) {
  double b = 1;
  for (int t = 0; t < r; ++t) b = b * (n - t) / (t + 1);
  return b;
}

double multinomial(int n, int i, int j) { return binomial(n, i) * binomial(n - i, j); }

// The three mixed second-derivative nets of the twist: D_(e_a − e_m) D_(e_b − e_m).
std::array<TriNet, 3> mixed_nets(const TriNet& net) {
  const Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
  std::array<TriNet, 3> out;
  for (int m = 0; m < 3; ++m) {
    const int a = (m + 1) % 3, b = (m + 2) % 3;
    out[m] = derivative_net(derivative_net(net, e.col(a) - e.col(m)), e.col(b) - e.col(m));
  }
  return out;
}

double squared_norm(const TriNet& net) { return net.points.squaredNorm(); }

// tri_bernstein_gram(n), kept for the last few degrees asked for on this thread (the reference is
// valid until the next call): the metrics of one net take 12 inner products at three degrees, and
// building G entry by entry each time took 1.54 s of a 1.6 s degree-40 solve (now 0.40 of 0.46 s).
const Eigen::MatrixXd& cached_gram(int n) {
  constexpr std::size_t kKept = 4;
  thread_local std::vector<std::pair<int, Eigen::MatrixXd>> kept;
  for (const auto& [degree, gram] : kept)
    if (degree == n) return gram;
  if (kept.size() == kKept) kept.erase(kept.begin());
  kept.emplace_back(n, tri_bernstein_gram(n));
  return kept.back().second;
}

}  // namespace

Eigen::MatrixXd tri_bernstein_gram(int n) {
  const Eigen::Index size = net_size(n);
  Eigen::MatrixXd G(size, size);
  const double scale = 1.0 / ((2.0 * n + 1) * (2.0 * n + 2));
  for (int k1 = 0; k1 <= n; ++k1)
    for (int j1 = 0; j1 <= n - k1; ++j1) {
      const int i1 = n - k1 - j1;
      const double c1 = multinomial(n, i1, j1);
      for (int k2 = 0; k2 <= n; ++k2)
        for (int j2 = 0; j2 <= n - k2; ++j2) {
          const int i2 = n - k2 - j2;
          G(net_index(n, j1, k1), net_index(n, j2, k2)) =
              c1 * multinomial(n, i2, j2) / multinomial(2 * n, i1 + i2, j1 + j2) * scale;
        }
    }
  return G;
}

double tri_inner_product(const TriNet& X, const TriNet& Y) {
  return scaled_form(X, Y, [](const TriNet& x, const TriNet& y) {
    const Eigen::MatrixXd& G = cached_gram(x.n);
    return (x.points.transpose() * G * y.points).trace();
  });
}

double tri_dirichlet_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n == 0) return 0.0;
    const TriNet px = derivative_net(net, direction_x()), py = derivative_net(net, direction_y());
    return tri_inner_product(px, px) + tri_inner_product(py, py);
  });
}

double tri_thin_plate_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n < 2) return 0.0;
    const TriNet px = derivative_net(net, direction_x()), py = derivative_net(net, direction_y());
    const TriNet pxx = derivative_net(px, direction_x()), pxy = derivative_net(px, direction_y()),
                 pyy = derivative_net(py, direction_y());
    return tri_inner_product(pxx, pxx) + 2 * tri_inner_product(pxy, pxy) + tri_inner_product(pyy, pyy);
  });
}

double tri_twist_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n < 2) return 0.0;
    double sum = 0;
    for (const TriNet& q : mixed_nets(net)) sum += tri_inner_product(q, q);
    return sum / 3;
  });
}

double tri_e3_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n < 3) return 0.0;
    const TriNet px = derivative_net(net, direction_x()), py = derivative_net(net, direction_y());
    const TriNet pxx = derivative_net(px, direction_x()), pyy = derivative_net(py, direction_y());
    const TriNet pxxx = derivative_net(pxx, direction_x()), pxxy = derivative_net(pxx, direction_y()),
                 pxyy = derivative_net(pyy, direction_x()), pyyy = derivative_net(pyy, direction_y());
    return tri_inner_product(pxxx, pxxx) + 3 * tri_inner_product(pxxy, pxxy) + 3 * tri_inner_product(pxyy, pxyy) +
           tri_inner_product(pyyy, pyyy);
  });
}

double tri_discrete_dirichlet_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n == 0) return 0.0;
    const double s = 1.0 / (double(net.n) * net.n);
    return s * (squared_norm(derivative_net(net, direction_x())) + squared_norm(derivative_net(net, direction_y())));
  });
}

double tri_discrete_thin_plate_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n < 2) return 0.0;
    const double f = double(net.n) * (net.n - 1), s = 1.0 / (f * f);
    const TriNet px = derivative_net(net, direction_x()), py = derivative_net(net, direction_y());
    return s * (squared_norm(derivative_net(px, direction_x())) + 2 * squared_norm(derivative_net(px, direction_y())) +
                squared_norm(derivative_net(py, direction_y())));
  });
}

double tri_discrete_twist_energy(const TriNet& given) {
  return scaled_energy(given, [](const TriNet& net) -> double {
    if (net.n < 2) return 0.0;
    const double f = double(net.n) * (net.n - 1), s = 1.0 / (f * f);
    double sum = 0;
    for (const TriNet& q : mixed_nets(net)) sum += squared_norm(q);
    return s * sum / 3;
  });
}

TriQuadratureRule duffy_gauss_legendre(int k) {
  const QuadratureRule g = gauss_legendre(k);
  TriQuadratureRule rule;
  rule.xy.resize(Eigen::Index(k) * k, 2);
  rule.weights.resize(Eigen::Index(k) * k);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const Eigen::Index r = Eigen::Index(a) * k + b;
      const double s = g.nodes(a), t = g.nodes(b);
      rule.xy(r, 0) = s;
      rule.xy(r, 1) = (1 - s) * t;
      rule.weights(r) = g.weights(a) * g.weights(b) * (1 - s);
    }
  return rule;
}

TriNetMetrics tri_net_metrics(const TriNet& net, const TriMask& mask) {
  TriNetMetrics m;
  m.dirichlet_energy = tri_dirichlet_energy(net);
  m.thin_plate_energy = tri_thin_plate_energy(net);
  m.twist_energy = tri_twist_energy(net);
  m.e3_energy = tri_e3_energy(net);
  m.discrete_dirichlet_energy = tri_discrete_dirichlet_energy(net);
  m.discrete_thin_plate_energy = tri_discrete_thin_plate_energy(net);
  m.discrete_twist_energy = tri_discrete_twist_energy(net);
  m.mask_residual = tri_mask_residual(net, mask);
  return m;
}

}  // namespace coons::tri
