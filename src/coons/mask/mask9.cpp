#include "mask9.h"

#include <cmath>

namespace coons {

Mask9 alpha_mask(double alpha) { return {0.25 - alpha, 0.25 - alpha, alpha}; }

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
