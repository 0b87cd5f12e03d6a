#include "sine_basis.h"

#include <fftw3.h>

#include <cmath>
#include <mutex>

#include "sine_transform.h"

namespace coons::solvers {

Eigen::MatrixXd sine_transform_2d(const Eigen::MatrixXd& X, int rows, int cols) {
  Eigen::MatrixXd Y(X.rows(), X.cols());
  if (X.rows() == 0) return Y;
  // FFTW's 2-D RODFT00 computes 4·ΣΣ x sin sin; the orthonormal scale is 1/(2·√((rows+1)(cols+1))).
  const double scale = 1.0 / (2.0 * std::sqrt(double(rows + 1) * double(cols + 1)));
  double* buffer = fftw_alloc_real(size_t(rows) * size_t(cols));
  fftw_plan plan = nullptr;
  {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    plan = fftw_plan_r2r_2d(rows, cols, buffer, buffer, FFTW_RODFT00, FFTW_RODFT00, FFTW_ESTIMATE);
  }
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    Eigen::Map<Eigen::VectorXd>(buffer, X.rows()) = X.col(c);
    fftw_execute(plan);
    Y.col(c) = scale * Eigen::Map<const Eigen::VectorXd>(buffer, X.rows());
  }
  {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(buffer);
  return Y;
}

Eigen::MatrixXd sine_transform_1d(const Eigen::MatrixXd& X) {
  Eigen::MatrixXd Y(X.rows(), X.cols());
  const int n = int(X.rows());
  if (n == 0 || X.cols() == 0) return Y;
  // FFTW's RODFT00 computes 2·Σ x sin; the orthonormal scale is 1/√(2(n+1)). One plan for all
  // columns (they are contiguous in Eigen's column-major storage).
  const double scale = 1.0 / std::sqrt(2.0 * (n + 1));
  double* buffer = fftw_alloc_real(size_t(n) * size_t(X.cols()));
  const fftw_r2r_kind kind = FFTW_RODFT00;
  fftw_plan plan = nullptr;
  {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    plan = fftw_plan_many_r2r(1, &n, int(X.cols()), buffer, nullptr, 1, n, buffer, nullptr, 1, n, &kind, FFTW_ESTIMATE);
  }
  Eigen::Map<Eigen::MatrixXd>(buffer, n, X.cols()) = X;
  fftw_execute(plan);
  Y = scale * Eigen::Map<const Eigen::MatrixXd>(buffer, n, X.cols());
  {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(buffer);
  return Y;
}

}  // namespace coons::solvers
