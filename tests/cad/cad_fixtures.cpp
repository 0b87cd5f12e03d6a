#include "cad_fixtures.h"

namespace coons::test {

BSplineBoundary cad_sample_boundary() {
  Eigen::VectorXd U(10), V(7);
  U << 0, 0, 0, 0, 0.3, 0.45, 1, 1, 1, 1;
  V << 0, 0, 0, 0.6, 1, 1, 1;
  Eigen::MatrixX3d bottom(6, 3), top(6, 3), left(4, 3), right(4, 3);
  bottom << 0, 0, 0, 0.5, -0.2, 0.25, 1.25, 0.1, 0.5, 2, -0.1, 0.125, 2.5, 0.2, -0.25, 3, 0, 0;
  top << 0, 2, 0.5, 0.75, 2.25, 1, 1.5, 2.1, 0.75, 2, 1.9, 1.25, 2.5, 2.2, 0.5, 3, 2, 0.25;
  left << 0, 0, 0, -0.25, 0.75, 0.5, 0.2, 1.5, 0.75, 0, 2, 0.5;
  right << 3, 0, 0, 3.25, 0.5, -0.5, 2.9, 1.25, 0.75, 3, 2, 0.25;
  return {BSplineCurve(3, U, bottom), BSplineCurve(3, U, top), BSplineCurve(2, V, left), BSplineCurve(2, V, right)};
}

}  // namespace coons::test
