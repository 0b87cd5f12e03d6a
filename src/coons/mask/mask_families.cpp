#include "mask_families.h"

#include <algorithm>
#include <cmath>

namespace coons {

MaskPoint alpha_family(double alpha) { return {alpha_mask(alpha), Mask9{-1, -1, 1}}; }

MaskPoint mu_family(int m, int n, double mu) {
  const double mn = double(m) * n, r = double(m) / n, s = double(n) / m;
  const double D = 4 * mn + 2 * mu * (r + s), dD = 2 * (r + s);
  MaskPoint p;
  p.mask = anisotropic_mask(m, n, mu);
  if (!std::isfinite(D)) {  // μ near the largest double: d/dμ ~ 1/μ² underflows to 0
    p.derivative = Mask9{0, 0, 0};
    return p;
  }
  p.derivative.diag = mn * dD / (D * D);
  p.derivative.edge_i = (r * D - (2 * mn + mu * r) * dD) / (D * D);
  p.derivative.edge_j = (s * D - (2 * mn + mu * s) * dD) / (D * D);
  return p;
}

double mu_of_compressed(int m, int n, double s) { return double(m) * n * s / (1 - s); }
double compressed_of_mu(int m, int n, double mu) { return mu / (mu + double(m) * n); }

double MuScale::mu(double s) const {
  if (s == s_lower()) return lower;
  if (s == s_upper()) return upper;
  return std::clamp(mu_of_compressed(m, n, s), lower, upper);
}

MaskPoint mu_family_compressed(int m, int n, double s) {
  MaskPoint p = mu_family(m, n, mu_of_compressed(m, n, s));
  const double dmu = double(m) * n / ((1 - s) * (1 - s));
  p.derivative.edge_i *= dmu;
  p.derivative.edge_j *= dmu;
  p.derivative.diag *= dmu;
  return p;
}

MaskPoint gamma_family(double alpha, double gamma) {
  return {Mask9{0.25 - alpha + gamma, 0.25 - alpha - gamma, alpha}, Mask9{1, -1, 0}};
}

Eigen::MatrixX3d mask_sensitivity_rhs(const ControlNet& net, const Mask9& d) {
  using Grid = Eigen::Map<const Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
  using Out = Eigen::Map<Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>;
  const Eigen::Index m = net.m, n = net.n, rows = std::max<Eigen::Index>(m - 1, 0),
                     cols = std::max<Eigen::Index>(n - 1, 0);
  Eigen::MatrixX3d R(rows * cols, 3);
  if (rows * cols == 0) return R;
  for (int c = 0; c < 3; ++c) {
    const Grid g(net.points.col(c).data(), m + 1, n + 1);
    Out r(R.col(c).data(), rows, cols);
    // neighbours of the interior block g(1..m−1, 1..n−1), vectorised row by row
    r = d.edge_i * (g.block(0, 1, rows, cols) + g.block(2, 1, rows, cols)) +
        d.edge_j * (g.block(1, 0, rows, cols) + g.block(1, 2, rows, cols)) +
        d.diag * (g.block(0, 0, rows, cols) + g.block(0, 2, rows, cols) + g.block(2, 0, rows, cols) +
                  g.block(2, 2, rows, cols));
  }
  return R;
}

}  // namespace coons
