#include "mask_families.h"

namespace coons {

MaskPoint alpha_family(double alpha) { return {alpha_mask(alpha), Mask9{-1, -1, 1}}; }

MaskPoint mu_family(int m, int n, double mu) {
  const double mn = double(m) * n, r = double(m) / n, s = double(n) / m;
  const double D = 4 * mn + 2 * mu * (r + s), dD = 2 * (r + s);
  MaskPoint p;
  p.mask = anisotropic_mask(m, n, mu);
  p.derivative.diag = mn * dD / (D * D);
  p.derivative.edge_i = (r * D - (2 * mn + mu * r) * dD) / (D * D);
  p.derivative.edge_j = (s * D - (2 * mn + mu * s) * dD) / (D * D);
  return p;
}

double mu_of_compressed(int m, int n, double s) { return double(m) * n * s / (1 - s); }
double compressed_of_mu(int m, int n, double mu) { return mu / (mu + double(m) * n); }

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
  const int m = net.m, n = net.n, cols = n - 1;
  Eigen::MatrixX3d R(Eigen::Index(std::max(m - 1, 0)) * std::max(cols, 0), 3);
  for (int i = 1; i < m; ++i)
    for (int j = 1; j < n; ++j) {
      const Eigen::RowVector3d ei = net.at(i - 1, j) + net.at(i + 1, j);
      const Eigen::RowVector3d ej = net.at(i, j - 1) + net.at(i, j + 1);
      const Eigen::RowVector3d k = net.at(i - 1, j - 1) + net.at(i + 1, j - 1) + net.at(i - 1, j + 1) + net.at(i + 1, j + 1);
      R.row(Eigen::Index(i - 1) * cols + (j - 1)) = d.edge_i * ei + d.edge_j * ej + d.diag * k;
    }
  return R;
}

}  // namespace coons
