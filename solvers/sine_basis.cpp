#include "sine_basis.h"

#include <cmath>

#include <fftw3.h>

namespace coons::solvers {

Eigen::MatrixXd sine_transform_2d(const Eigen::MatrixXd& X, int rows, int cols) {
  Eigen::MatrixXd Y(X.rows(), X.cols());
  if (X.rows() == 0) return Y;
  // FFTW's 2-D RODFT00 computes 4·ΣΣ x sin sin; the orthonormal scale is 1/(2·√((rows+1)(cols+1))).
  const double scale = 1.0 / (2.0 * std::sqrt(double(rows + 1) * double(cols + 1)));
  double* buffer = fftw_alloc_real(size_t(rows) * size_t(cols));
  fftw_plan plan = fftw_plan_r2r_2d(rows, cols, buffer, buffer, FFTW_RODFT00, FFTW_RODFT00, FFTW_ESTIMATE);
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    Eigen::Map<Eigen::VectorXd>(buffer, X.rows()) = X.col(c);
    fftw_execute(plan);
    Y.col(c) = scale * Eigen::Map<const Eigen::VectorXd>(buffer, X.rows());
  }
  fftw_destroy_plan(plan);
  fftw_free(buffer);
  return Y;
}

}  // namespace coons::solvers
