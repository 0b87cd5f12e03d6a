// The singular α of the non-uniform system of a B-spline boundary, for the tests of the
// near-singular refusal (bspline_search_test.cpp, bspline_net_test.cpp).
#pragma once

#include <Eigen/Eigenvalues>
#include <cmath>

#include "coons/mask/nonuniform_mask.h"
#include "coons/study/bspline_net.h"

namespace coons::test {

// The α in (0, 1/4] closest to 1/8 at which the system is singular (HUGE_VAL if none): A(α) =
// A(0) + α·∂A/∂α, so the singular α are the real eigenvalues of the pencil A(0) v = −α ∂A/∂α v.
inline double bspline_singular_alpha(const BSplineBoundary& compatible) {
  const NonUniformMaskSystem s =
      assemble_nonuniform_mask_system(bspline_frame(compatible), greville_grid(compatible), 0);
  const Eigen::MatrixXd a0 = Eigen::MatrixXd(s.A), a1 = Eigen::MatrixXd(s.dA);
  Eigen::GeneralizedEigenSolver<Eigen::MatrixXd> pencil(a0, -a1);
  double best = HUGE_VAL;
  for (Eigen::Index k = 0; k < a0.rows(); ++k) {
    if (!(std::abs(pencil.betas()(k)) > 1e-12) || std::abs(pencil.alphas()(k).imag()) > 1e-9) continue;
    const double alpha = pencil.alphas()(k).real() / pencil.betas()(k);
    if (alpha > 0 && alpha <= 0.25 && std::abs(alpha - 0.125) < std::abs(best - 0.125)) best = alpha;
  }
  return best;
}

}  // namespace coons::test
