#include "fast5_low_modes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace coons::solvers::fast5_detail {

LowModes low_modes(double a, double b, const Eigen::VectorXd& mu, const Eigen::VectorXd& nu, int modes, int threads) {
  LowModes lm;
  lm.rows = int(mu.size());
  lm.cols = int(nu.size());
  lm.modes = std::clamp(modes, 0, lm.cols);
  lm.sigma = std::sqrt(2.0) * first_sine_column(lm.rows);
  lm.inv_lambda.resize(lm.rows, lm.modes);
  lm.coupling.resize(lm.rows, lm.modes);
  [[maybe_unused]] const int nt = threads;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int q = 0; q < lm.modes; ++q) {           // the modes are independent; each writes its own column
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
                     const ChunkOutput& out, const Eigen::MatrixXd& sines, Eigen::MatrixXd& dot, int first, int last) {
  const int R = lm.rows, C = lm.cols;
  const int q0 = std::clamp(first, 0, lm.modes), q1 = last < 0 ? lm.modes : std::clamp(last, q0, lm.modes), Q = q1 - q0;
  const double scale_i = std::sqrt(2.0 / (R + 1));
  const Eigen::Index k = sines.cols();
  dot.setZero(R, 2 * k * count);
  Eigen::VectorXd column(R);
  Eigen::MatrixXd solved(R, Q);  // M_q⁻¹ of the input, column q − q0
  Eigen::MatrixXd input(R, Q);   // the input without the sources, gathered row by row
  std::vector<double> scratch(static_cast<std::size_t>(Q));
  for (int c = 0; c < count; ++c) {
    // the input's modes [0, Q), row by row (hats, edge rows or zero)
    const double* hat = in.hats[std::size_t(c)];
    const EdgeRows* edges = hat ? nullptr : in.edges[std::size_t(c)];
    if (hat || edges)
      for (int r = 0; r < R; ++r) {
        const double* row =
            hat ? hat + std::ptrdiff_t(r) * C + q0 : edge_row(*edges, r, in.s0, in.s1, q0, Q, scratch.data());
        for (int k = 0; k < Q; ++k) input(r, k) = row[k];
      }
    else
      input.setZero();
    for (int q = q0; q < q1; ++q) {
      const double t = q % 2 == 0 ? in.t_even[q] : in.t_odd[q];
      const Eigen::MatrixXd* z = in.z ? &(*in.z)[std::size_t(q % 2)] : nullptr;
      for (int r = 0; r < R; ++r) column[r] = input(r, q - q0) + (z ? in.sign * (*z)(r, c) * t : 0.0);
      along_i.apply(column.data(), column.data(), scale_i);
      // (√c σ Λ⁻¹)ᵀ v̂ on each parity block, each summed in the order of p (two scalar chains: an
      // array indexed by p % 2 made every addition wait for a store)
      const double* cp = lm.coupling.col(q).data();
      const double* il = lm.inv_lambda.col(q).data();
      double s_even = 0, s_odd = 0;
      int p = 0;
      for (; p + 1 < R; p += 2) {
        s_even += cp[p] * column[p];
        s_odd += cp[p + 1] * column[p + 1];
      }
      if (p < R) s_even += cp[p] * column[p];
      for (p = 0; p + 1 < R; p += 2) {
        column[p] = column[p] * il[p] - cp[p] * s_even;
        column[p + 1] = column[p + 1] * il[p + 1] - cp[p + 1] * s_odd;
      }
      if (p < R) column[p] = column[p] * il[p] - cp[p] * s_even;
      along_i.apply(column.data(), solved.col(q - q0).data(), scale_i);
    }
    // into the grid kTile rows at a time: the tile is read from solved a cache line per column
    // (row by row, each of the Q entries of a row was a line and a page of its own)
    double* grid = out.grid[std::size_t(c)];
    constexpr int kTile = 8;
    Eigen::Matrix<double, kTile, Eigen::Dynamic> tile(kTile, Q);
    for (int r0 = 0; r0 < R; r0 += kTile) {
      const int rows = std::min(kTile, R - r0);
      tile.topRows(rows) = solved.middleRows(r0, rows);
      for (int i = 0; i < rows; ++i) {
        const int r = r0 + i;
        double* x = tile.row(i).data();  // not contiguous: stride kTile
        double* g = grid ? grid + std::ptrdiff_t(r) * C + q0 : nullptr;
        for (int j = 0; j < Q; ++j) {
          double& v = x[std::ptrdiff_t(j) * kTile];
          if (g && out.add) v += g[j];
          if (g) g[j] = v;
        }
        for (Eigen::Index m = 0; m < k; ++m)
          for (int j = 0; j < Q; ++j)
            dot(r, 2 * (k * c + m) + (q0 + j) % 2) += x[std::ptrdiff_t(j) * kTile] * sines(q0 + j, m);
      }
    }
  }
}

}  // namespace coons::solvers::fast5_detail
