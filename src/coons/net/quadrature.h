// Gauss–Legendre quadrature on [0, 1]: exact for polynomials of degree ≤ 2k − 1 with k nodes.
// Based on: G. H. Golub, J. H. Welsch, Calculation of Gauss quadrature rules, Math. Comp. 23 (1969);
// nodes here by Newton's method on P_k (Numerical Recipes' gauleg).
#pragma once

#include <Eigen/Core>

namespace coons {

struct QuadratureRule {
  Eigen::VectorXd nodes;    //!< in (0, 1), increasing
  Eigen::VectorXd weights;  //!< sum to 1
};

QuadratureRule gauss_legendre(int k);

}  // namespace coons
