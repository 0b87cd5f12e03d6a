#include "mask9.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace coons {

Mask9 alpha_mask(double alpha) { return {0.25 - alpha, 0.25 - alpha, alpha}; }

double mask9_eigenvalue_ratio(const Mask9& mask, int m, int n) {
  if (m < 2 || n < 2) return 1;
  std::vector<double> cq(std::size_t(n - 1));
  for (int q = 1; q < n; ++q) cq[std::size_t(q - 1)] = std::cos(M_PI * q / n);
  double smallest = HUGE_VAL, largest = 0;
  for (int p = 1; p < m; ++p) {
    const double cp = std::cos(M_PI * p / m);
    for (const double c : cq) {
      const double lambda = std::abs(mask9_eigenvalue(mask, cp, c));
      smallest = std::min(smallest, lambda);
      largest = std::max(largest, lambda);
    }
  }
  return largest > 0 ? smallest / largest : 0;
}

std::vector<double> alpha_family_singular_alphas(int m, int n, double lower, double upper) {
  // λ = 1 − 2(1/4 − α)s − 4α·cp·cq = 1 − s/2 + α(2s − 4cp·cq)
  std::vector<double> alphas;
  for (int p = 1; p < m; ++p) {
    const double cp = std::cos(M_PI * p / m);
    for (int q = 1; q < n; ++q) {
      const double cq = std::cos(M_PI * q / n), s = cp + cq, slope = 2 * s - 4 * cp * cq;
      if (std::abs(slope) <= 1e-13) continue;  // zero but for rounding (2 x 2: λ = 1 for every α)
      const double alpha = (s / 2 - 1) / slope, near = 1e-12 * std::max(std::abs(alpha), 1.0);
      // (a bound that is singular, computed an ulp inside it, is not inside)
      if (alpha > lower + near && alpha < upper - near) alphas.push_back(alpha);
    }
  }
  std::sort(alphas.begin(), alphas.end());
  // the modes (p, q) and (q, p) of a square net, or p and m − p against q and n − q, give one α
  // whose two roundings can differ in the last bits
  alphas.erase(std::unique(alphas.begin(), alphas.end(),
                           [](double a, double b) { return b - a <= 1e-12 * std::max(std::abs(a), 1.0); }),
               alphas.end());
  return alphas;
}

Mask9 anisotropic_mask(int m, int n, double mu) {
  const double mn = double(m) * n, rm = double(m) / n, rn = double(n) / m;
  const double D = 4 * mn + 2 * mu * (rm + rn);
  if (std::isfinite(D)) return {(2 * mn + mu * rm) / D, (2 * mn + mu * rn) / D, -mn / D};
  // μ near the largest double: D overflows, so numerators and D are divided by μ first
  const double d = 4 * (mn / mu) + 2 * (rm + rn);
  return {(2 * (mn / mu) + rm) / d, (2 * (mn / mu) + rn) / d, -(mn / mu) / d};
}

double alpha_from_mu(int n, double mu) {
  const double n2 = double(n) * n;
  return -n2 / (4 * (n2 + mu));
}

double mu_from_alpha(int n, double alpha) {
  const double n2 = double(n) * n;
  return -n2 * (1 + 4 * alpha) / (4 * alpha);
}

solvers::GridStencil mask_stencil(const Mask9& mask, int rows, int cols) {
  solvers::GridStencil s;
  s.rows = rows;
  s.cols = cols;
  s.center = 1;
  s.edge_i = -mask.edge_i;
  s.edge_j = -mask.edge_j;
  s.diag = -mask.diag;
  return s;
}

}  // namespace coons
