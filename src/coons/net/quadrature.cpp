#include "quadrature.h"

#include <cmath>

namespace coons {

QuadratureRule gauss_legendre(int k) {
  QuadratureRule rule{Eigen::VectorXd(k), Eigen::VectorXd(k)};
  for (int r = 0; r < (k + 1) / 2; ++r) {
    double x = std::cos(M_PI * (r + 0.75) / (k + 0.5));  // initial guess for the r-th root
    double dp = 1;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = 0;
      for (int d = 1; d <= k; ++d) {  // P_d by the three-term recurrence
        const double p2 = p1;
        p1 = p0;
        p0 = ((2 * d - 1) * x * p1 - (d - 1) * p2) / d;
      }
      dp = k * (x * p0 - p1) / (x * x - 1);
      const double dx = p0 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2 / ((1 - x * x) * dp * dp);
    // map [−1, 1] → [0, 1]; roots come in ± pairs
    rule.nodes(r) = (1 - x) / 2;
    rule.nodes(k - 1 - r) = (1 + x) / 2;
    rule.weights(r) = rule.weights(k - 1 - r) = w / 2;
  }
  return rule;
}

}  // namespace coons
