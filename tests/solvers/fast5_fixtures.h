// Fixtures of the fast5 internals' tests (fast5_sweeps_test.cpp, fast5_twisted_test.cpp): the
// matrix M_q of one mode, and a sweep's input and output on a grid, made in code.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "solvers/fast5_modes.h"

namespace coons::solvers::fast5_detail::testing {

// M_q = (a ν² + b)·P + 2bν·D + bν²·I of order n, P = toeplitz(6, −4, 1), D = tridiag(−1, 2, −1).
inline Eigen::MatrixXd mode_matrix(double a, double b, double nu, int n) {
  const double alpha = a * nu * nu + b, beta = 2 * b * nu, gamma = b * nu * nu;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    M(i, i) = 6 * alpha + 2 * beta + gamma;
    if (i + 1 < n) M(i, i + 1) = M(i + 1, i) = -4 * alpha - beta;
    if (i + 2 < n) M(i, i + 2) = M(i + 2, i) = alpha;
  }
  return M;
}

// A sweep's input and output on a rows × cols grid, three right-hand sides, with sources U z.
struct SweepFixture {
  int rows, cols;
  std::array<std::vector<double>, 3> hats, grid;
  std::array<Eigen::MatrixXd, 2> z;
  Eigen::VectorXd t_even, t_odd;
  Eigen::MatrixXd sines;

  SweepFixture(int r, int c, unsigned seed) : rows(r), cols(c) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (auto& h : hats) {
      h.resize(std::size_t(rows) * std::size_t(cols));
      for (double& v : h) v = u(gen);
    }
    for (auto& g : grid) {
      g.resize(std::size_t(rows) * std::size_t(cols));
      for (double& v : g) v = u(gen);
    }
    for (auto& m : z) m = Eigen::MatrixXd::NullaryExpr(rows, 3, [&] { return u(gen); });
    const Eigen::VectorXd t = std::sqrt(2.0) * first_sine_column(cols);
    t_even = t_odd = Eigen::VectorXd::Zero(cols);
    for (int q = 0; q < cols; ++q) (q % 2 == 0 ? t_even : t_odd)[q] = t[q];
    sines = Eigen::MatrixXd::NullaryExpr(cols, 2, [&] { return u(gen); });
  }

  [[nodiscard]] SweepInput input(double sign) const {
    SweepInput in;
    in.hats = {hats[0].data(), hats[1].data(), hats[2].data()};
    in.z = &z;
    in.sign = sign;
    in.t_even = t_even.data();
    in.t_odd = t_odd.data();
    return in;
  }
  // column q of the input of right-hand side c
  [[nodiscard]] Eigen::VectorXd input_column(int q, int c, double sign) const {
    Eigen::VectorXd v(rows);
    const double t = q % 2 == 0 ? t_even[q] : t_odd[q];
    for (int r = 0; r < rows; ++r)
      v[r] = hats[std::size_t(c)][std::size_t(r) * std::size_t(cols) + std::size_t(q)] +
             sign * z[std::size_t(q % 2)](r, c) * t;
    return v;
  }
};

}  // namespace coons::solvers::fast5_detail::testing
