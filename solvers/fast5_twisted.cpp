#include "fast5_twisted.h"

#include <algorithm>
#include <cstddef>

namespace coons::solvers::fast5_detail {

TwistFactors twist_factors(const ModeFactors& f, int low) {
  TwistFactors tw;
  tw.rows = f.rows;
  tw.cols = f.cols;
  tw.low = std::clamp(low, 0, f.cols);
  tw.h = f.rows / 2;
  const int h = tw.h, m = f.rows - h - 2;
  tw.i11.setZero(f.cols);
  tw.i12.setZero(f.cols);
  tw.i22.setZero(f.cols);
  for (int q = tw.low; q < f.cols; ++q) {
    const std::array<double, 3> at_h = mode_factor(f, h, q), above_h = mode_factor(f, h - 1, q);
    const std::array<double, 3> at_m = mode_factor(f, m, q), above_m = mode_factor(f, m - 1, q);
    const double dh = 1 / at_h[0], dh1 = 1 / above_h[0], dm = 1 / at_m[0], dm1 = 1 / above_m[0];
    const double k11 = dh - above_m[2] * above_m[2] * dm1;
    const double k22 = dm - above_h[2] * above_h[2] * dh1;
    const double k12 = at_h[1] * dh - above_m[1] * above_m[2] * dm1;
    const double det = k11 * k22 - k12 * k12;
    tw.i11[q] = k22 / det;
    tw.i12[q] = -k12 / det;
    tw.i22[q] = k11 / det;
  }
  return tw;
}

void twisted_down(const ModeFactors& f, const TwistFactors& tw, int half, const SweepInput& in,
                  const std::array<double*, 3>& grid, TwistEnds& ends) {
  const int R = f.rows, C = f.cols;
  const int mid = half == 0 ? tw.h : R - tw.h - 2;   // the elimination steps 0 … mid, mid the middle row
  const std::ptrdiff_t stride = half == 0 ? C : -C;  // the row eliminated before is one grid row up (down)
  const auto grid_row = [&](int e) { return half == 0 ? e : R - 1 - e; };
  ends.assign(6 * std::size_t(C), 0.0);
  // row by row over all the banded modes at once (blocks of 128 or 512 modes were slower: the
  // rows above are read back from the L2 cache either way, and the per-row work grows with blocks)
  const int b0 = tw.low, n = C - b0;
  const std::vector<double> zeros(std::size_t(n), 0.0);
  std::vector<double> scratch(3 * std::size_t(n));
  for (int e = 0; e <= mid; ++e) {
    const std::ptrdiff_t at = std::ptrdiff_t(grid_row(e)) * C + b0;
    down_row(f, e, grid_row(e), b0, C, 3, in, {grid[0] + at, grid[1] + at, grid[2] + at}, stride, zeros.data(),
             scratch.data());
  }
  for (std::size_t c = 0; c < 3; ++c) {
    const double* y_mid = grid[c] + std::ptrdiff_t(grid_row(mid)) * C;
    const double* y_before = grid[c] + std::ptrdiff_t(grid_row(mid - 1)) * C;
    double* own = ends.data() + 2 * c * std::size_t(C);
    double* other = own + C;
    for (int q = b0; q < C; ++q) {
      own[q] = y_mid[q];
      other[q] = -(mode_factor(f, mid - 1, q)[2] * y_before[q]);
    }
  }
}

void twisted_up(const ModeFactors& f, const TwistFactors& tw, int half, const std::array<TwistEnds, 2>& ends,
                const std::array<double*, 3>& grid, detail::SineTransform& along_j, double scale_j, double* window,
                const std::function<void(int, int, const double*)>& done) {
  const int R = f.rows, C = f.cols, low = tw.low, h = tw.h;
  const auto win = [&](std::size_t c, int p) { return window + (std::ptrdiff_t(c) * kTwistWindow + p) * C; };
  // The window holds the rows finished last at p, p + 1, …: the row below a row (in the order of
  // this half's way up) is the next one in memory, so up_row_into reads it at stride cols.
  int p = kTwistWindow - 2;
  for (std::size_t c = 0; c < 3; ++c) {  // the middle: (x_h, x_{h+1}) = K⁻¹ (ρ_h, ρ_{h+1})
    const double* top_own = ends[0].data() + 2 * c * std::size_t(C);
    const double* top_other = top_own + C;
    const double* bottom_own = ends[1].data() + 2 * c * std::size_t(C);
    const double* bottom_other = bottom_own + C;
    double *own = win(c, p), *far = win(c, p + 1);
    for (int q = low; q < C; ++q) {
      const double rho_h = top_own[q] + bottom_other[q], rho_h1 = bottom_own[q] + top_other[q];
      const double xh = tw.i11[q] * rho_h + tw.i12[q] * rho_h1, xh1 = tw.i12[q] * rho_h + tw.i22[q] * rho_h1;
      own[q] = half == 0 ? xh : xh1;
      far[q] = half == 0 ? xh1 : xh;
    }
  }
  // a finished row: its lowest modes from the grid, then its transform into the grid
  const auto finish = [&](int r) {
    for (std::size_t c = 0; c < 3; ++c) {
      double* row = win(c, p);
      double* g = grid[c] + std::ptrdiff_t(r) * C;
      std::copy(g, g + low, row);
      along_j.apply(row, g, scale_j);
      done(int(c), r, g);
    }
  };
  finish(half == 0 ? h : h + 1);
  const int steps = half == 0 ? h : R - h - 2;
  for (int k = 0; k < steps; ++k) {
    const int r = half == 0 ? h - 1 - k : h + 2 + k, e = half == 0 ? r : R - 1 - r;
    if (p == 0) {  // the two rows read next to the window's end
      for (std::size_t c = 0; c < 3; ++c) {
        std::copy(win(c, 0), win(c, 0) + C, win(c, kTwistWindow - 2));
        std::copy(win(c, 1), win(c, 1) + C, win(c, kTwistWindow - 1));
      }
      p = kTwistWindow - 2;
    }
    --p;
    const std::ptrdiff_t at = std::ptrdiff_t(r) * C + low;
    up_row_into(f, e, low, C, {win(0, p) + low, win(1, p) + low, win(2, p) + low},
                {grid[0] + at, grid[1] + at, grid[2] + at}, C, 2);
    finish(r);
  }
}

}  // namespace coons::solvers::fast5_detail
