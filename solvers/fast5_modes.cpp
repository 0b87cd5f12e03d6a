#include "fast5_modes.h"

#include <algorithm>
#include <cmath>

namespace coons::solvers::fast5_detail {

Eigen::VectorXd first_sine_column(int n) {
  Eigen::VectorXd s(n);
  for (int k = 0; k < n; ++k) s[k] = std::sqrt(2.0 / (n + 1)) * std::sin(M_PI * (k + 1) / (n + 1));
  return s;
}

Eigen::VectorXd second_difference_eigenvalues(int n) {
  Eigen::VectorXd e(n);
  for (int k = 0; k < n; ++k) e[k] = 4 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (n + 1))), 2);
  return e;
}

void FactorRow::seek(int r) {
  const int q = f_.active[std::size_t(r)];
  const std::size_t o = f_.offset[std::size_t(r)];
  std::copy_n(f_.inv_d.data() + o, q, inv_d.data());
  std::copy_n(f_.l1.data() + o, q, l1.data());
  std::copy_n(f_.l2.data() + o, q, l2.data());
  for (int k = q; k < active_; ++k) {  // converged since the last row
    inv_d[std::size_t(k)] = f_.lim_inv_d[std::size_t(k)];
    l1[std::size_t(k)] = f_.lim_l1[std::size_t(k)];
    l2[std::size_t(k)] = f_.lim_l2[std::size_t(k)];
  }
  active_ = q;
}

namespace {
constexpr double kConverged = 1e-15;
}  // namespace

ModeFactors factor_modes(double a, double b, const Eigen::VectorXd& nu, int rows) {
  ModeFactors f;
  const int cols = int(nu.size());
  f.rows = rows;
  f.cols = cols;
  f.lim_inv_d.resize(std::size_t(cols));
  f.lim_l1.resize(std::size_t(cols));
  f.lim_l2.resize(std::size_t(cols));
  std::vector<int> converged(std::size_t(cols), rows);
  const auto modes = std::size_t(cols);
  std::vector<std::vector<double>> d(modes), l1(modes), l2(modes);
  for (int q = 0; q < cols; ++q) {
    const double alpha = a * nu[q] * nu[q] + b, beta = 2 * b * nu[q], gamma = b * nu[q] * nu[q];
    const double a0 = 6 * alpha + 2 * beta + gamma, a1 = -4 * alpha - beta, a2 = alpha;  // definite
    auto& dq = d[std::size_t(q)];
    auto& l1q = l1[std::size_t(q)];
    auto& l2q = l2[std::size_t(q)];
    double dm1 = 0, dm2 = 0, l1m1 = 0, l2m1 = 0, l2m2 = 0;
    for (int r = 0; r < rows; ++r) {
      const double dr = a0 - l1m1 * l1m1 * dm1 - l2m2 * l2m2 * dm2;
      const double l1r = (a1 - l2m1 * dm1 * l1m1) / dr, l2r = a2 / dr;
      const double change =
          std::max({std::abs(dr - dm1) / dr, std::abs(l1r - l1m1) / std::abs(l1r), std::abs(l2r - l2m1) / l2r});
      if (r >= 3 && change <= kConverged) {
        converged[std::size_t(q)] = r;
        break;
      }
      dq.push_back(dr);
      l1q.push_back(l1r);
      l2q.push_back(l2r);
      dm2 = dm1;
      dm1 = dr;
      l1m1 = l1r;
      l2m2 = l2m1;
      l2m1 = l2r;
    }
    f.lim_inv_d[std::size_t(q)] = 1 / dq.back();
    f.lim_l1[std::size_t(q)] = l1q.back();
    f.lim_l2[std::size_t(q)] = l2q.back();
  }
  f.active.assign(std::size_t(rows), 0);
  f.offset.assign(std::size_t(rows) + 1, 0);
  int q_max = cols;
  for (int r = 0; r < rows; ++r) {
    while (q_max > 0 && converged[std::size_t(q_max) - 1] <= r) --q_max;
    f.active[std::size_t(r)] = q_max;
    f.offset[std::size_t(r) + 1] = f.offset[std::size_t(r)] + std::size_t(q_max);
  }
  const std::size_t total = f.offset.back();
  f.inv_d.resize(total);
  f.l1.resize(total);
  f.l2.resize(total);
  for (int r = 0; r < rows; ++r)
    for (int q = 0; q < f.active[std::size_t(r)]; ++q) {
      const std::size_t at = f.offset[std::size_t(r)] + std::size_t(q);
      const auto& dq = d[std::size_t(q)];
      const bool stored = std::size_t(r) < dq.size();
      f.inv_d[at] = stored ? 1 / dq[std::size_t(r)] : f.lim_inv_d[std::size_t(q)];
      f.l1[at] = stored ? l1[std::size_t(q)][std::size_t(r)] : f.lim_l1[std::size_t(q)];
      f.l2[at] = stored ? l2[std::size_t(q)][std::size_t(r)] : f.lim_l2[std::size_t(q)];
    }
  return f;
}

}  // namespace coons::solvers::fast5_detail
