#include "fast5_low_modes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace coons::solvers::fast5_detail {

LowModes low_modes(double a, double b, const Eigen::VectorXd& mu, const Eigen::VectorXd& nu, int modes) {
  LowModes lm;
  lm.rows = int(mu.size());
  lm.cols = int(nu.size());
  lm.modes = std::clamp(modes, 0, lm.cols);
  lm.sigma = std::sqrt(2.0) * first_sine_column(lm.rows);
  lm.inv_lambda.resize(lm.rows, lm.modes);
  lm.coupling.resize(lm.rows, lm.modes);
  for (int q = 0; q < lm.modes; ++q) {
    const double alpha = a * nu[q] * nu[q] + b;  // the weight of E_i in M_q
    std::array<double, 2> gamma{};               // σᵀΛ⁻¹σ on each parity block of p
    for (int p = 0; p < lm.rows; ++p) {
      const double s = mu[p] + nu[q];
      lm.inv_lambda(p, q) = 1 / (a * mu[p] * mu[p] * nu[q] * nu[q] + b * s * s);
      gamma[std::size_t(p % 2)] += lm.sigma[p] * lm.sigma[p] * lm.inv_lambda(p, q);
    }
    for (int p = 0; p < lm.rows; ++p) {
      const double c = alpha / (1 + alpha * gamma[std::size_t(p % 2)]);
      lm.coupling(p, q) = std::sqrt(c) * lm.sigma[p] * lm.inv_lambda(p, q);
    }
  }
  return lm;
}

void solve_low_modes(const LowModes& lm, detail::SineTransform& along_i, int count, const SweepInput& in,
                     const ChunkOutput& out, const Eigen::MatrixXd& sines, Eigen::MatrixXd& dot) {
  const int R = lm.rows, C = lm.cols, Q = lm.modes;
  const double scale_i = std::sqrt(2.0 / (R + 1));
  const Eigen::Index k = sines.cols();
  dot.setZero(R, 2 * k * count);
  Eigen::VectorXd column(R);
  Eigen::MatrixXd solved(R, Q);  // M_q⁻¹ of the input, column q
  Eigen::MatrixXd input(R, Q);   // the input without the sources, gathered row by row
  std::vector<double> scratch(static_cast<std::size_t>(Q));
  for (int c = 0; c < count; ++c) {
    // the input's modes [0, Q), row by row (hats, edge rows or zero)
    const double* hat = in.hats[std::size_t(c)];
    const EdgeRows* edges = hat ? nullptr : in.edges[std::size_t(c)];
    if (hat || edges)
      for (int r = 0; r < R; ++r) {
        const double* row = hat ? hat + std::ptrdiff_t(r) * C : edge_row(*edges, r, in.s0, in.s1, 0, Q, scratch.data());
        for (int q = 0; q < Q; ++q) input(r, q) = row[q];
      }
    else
      input.setZero();
    for (int q = 0; q < Q; ++q) {
      const double t = q % 2 == 0 ? in.t_even[q] : in.t_odd[q];
      const Eigen::MatrixXd* z = in.z ? &(*in.z)[std::size_t(q % 2)] : nullptr;
      for (int r = 0; r < R; ++r) column[r] = input(r, q) + (z ? in.sign * (*z)(r, c) * t : 0.0);
      along_i.apply(column.data(), column.data(), scale_i);
      std::array<double, 2> s{};  // (√c σ Λ⁻¹)ᵀ v̂ on each parity block
      for (int p = 0; p < R; ++p) s[std::size_t(p % 2)] += lm.coupling(p, q) * column[p];
      for (int p = 0; p < R; ++p)
        column[p] = column[p] * lm.inv_lambda(p, q) - lm.coupling(p, q) * s[std::size_t(p % 2)];
      along_i.apply(column.data(), solved.col(q).data(), scale_i);
    }
    double* grid = out.grid[std::size_t(c)];
    std::vector<double> x(static_cast<std::size_t>(Q));
    for (int r = 0; r < R; ++r) {
      double* g = grid ? grid + std::ptrdiff_t(r) * C : nullptr;
      for (int q = 0; q < Q; ++q) {
        x[std::size_t(q)] = g && out.add ? g[q] + solved(r, q) : solved(r, q);
        if (g) g[q] = x[std::size_t(q)];
      }
      for (Eigen::Index m = 0; m < k; ++m)
        for (int q = 0; q < Q; ++q) dot(r, 2 * (k * c + m) + q % 2) += x[std::size_t(q)] * sines(q, m);
    }
  }
}

}  // namespace coons::solvers::fast5_detail
