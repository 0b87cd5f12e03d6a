#include "fast5_twisted.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <thread>
#include <utility>

#include "linear_solver.h"

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

TwistedUp::TwistedUp(const ModeFactors& f, const TwistFactors& tw, const std::array<TwistEnds, 2>& ends,
                     const std::array<double*, 3>& grid, const std::array<double*, 2>& scratch, double scale_j,
                     std::function<void(int, int, const double*)> done)
    : f_(f), tw_(tw), ends_(ends), grid_(grid), scale_j_(scale_j), done_(std::move(done)) {
  for (std::size_t k = 0; k < 2; ++k) {
    halves_[k].scratch = scratch[k];
    halves_[k].count = k == 0 ? tw.h + 1 : f.rows - tw.h - 1;  // the middle row and the half's rows
  }
}

int TwistedUp::grid_row(int half, int k) const { return half == 0 ? tw_.h - k : tw_.h + 1 + k; }

// The k-th row of the half, finished in the grid (whose columns < low hold the lowest modes
// already). From its third row on, the two rows before it are read from the grid, where nothing
// transforms them before (claimable); the first row after the middle reads the other middle row,
// which the other half owns, from the scratch rows: per right-hand side [that row, own middle, far middle].
void TwistedUp::step(int half) {
  Half& hf = halves_[std::size_t(half)];
  const int C = f_.cols, low = tw_.low;
  const int k = hf.next, r = grid_row(half, k);
  const auto scratch = [&](std::size_t c, int i) { return hf.scratch + (std::ptrdiff_t(c) * 3 + i) * C; };
  const auto grid_at = [&](std::size_t c, int row) { return grid_[c] + std::ptrdiff_t(row) * C + low; };
  if (k == 0) {  // the middle: (x_h, x_{h+1}) = K⁻¹ (ρ_h, ρ_{h+1})
    for (std::size_t c = 0; c < 3; ++c) {
      const double* top_own = ends_[0].data() + 2 * c * std::size_t(C);
      const double* top_other = top_own + C;
      const double* bottom_own = ends_[1].data() + 2 * c * std::size_t(C);
      const double* bottom_other = bottom_own + C;
      double *own = scratch(c, 1), *far = scratch(c, 2);
      for (int q = low; q < C; ++q) {
        const double rho_h = top_own[q] + bottom_other[q], rho_h1 = bottom_own[q] + top_other[q];
        const double xh = tw_.i11[q] * rho_h + tw_.i12[q] * rho_h1, xh1 = tw_.i12[q] * rho_h + tw_.i22[q] * rho_h1;
        own[q] = half == 0 ? xh : xh1;
        far[q] = half == 0 ? xh1 : xh;
      }
      std::copy(own + low, own + C, grid_at(c, r));
    }
  } else {
    const int e = half == 0 ? r : f_.rows - 1 - r;  // the factor row: mirrored from the bottom
    if (k == 1) {
      up_row_into(f_, e, low, C, {scratch(0, 0) + low, scratch(1, 0) + low, scratch(2, 0) + low},
                  {grid_at(0, r), grid_at(1, r), grid_at(2, r)}, C, 2);
      for (std::size_t c = 0; c < 3; ++c) std::copy(scratch(c, 0) + low, scratch(c, 0) + C, grid_at(c, r));
    } else {  // in place: the row before is the next grid row in this half's order
      up_row(f_, e, low, C, {grid_at(0, r), grid_at(1, r), grid_at(2, r)}, half == 0 ? C : -std::ptrdiff_t(C), 2);
    }
  }
  ++hf.next;
}

// Rows [k0, k1) of the half, finished (and no longer read by its owner), transformed in place.
void TwistedUp::transform(int half, int k0, int k1, detail::SineTransform& along_j) const {
  for (int k = k0; k < k1; ++k) {
    const int r = grid_row(half, k);
    for (std::size_t c = 0; c < 3; ++c) {
      double* g = grid_[c] + std::ptrdiff_t(r) * f_.cols;
      along_j.apply(g, g, scale_j_);
      done_(int(c), r, g);
    }
  }
}

void TwistedUp::work(int thread, int threads, detail::SineTransform& along_j) {
  constexpr int kSteps = 8;       // rows an owner finishes before it looks for rows to transform
  constexpr int kTransforms = 4;  // rows claimed at a time
  const auto owns = [&](int half) { return half % std::max(threads, 1) == thread; };
  // a claim of up to kTransforms finished rows of the half that no one has claimed yet
  const auto claim = [&](int half) {
    Half& hf = halves_[std::size_t(half)];
    int c = hf.claimed.load(std::memory_order_relaxed);
    for (;;) {
      const int p = hf.finished.load(std::memory_order_acquire);
      if (c >= p) return false;
      const int e = std::min(c + kTransforms, p);
      if (hf.claimed.compare_exchange_weak(c, e, std::memory_order_relaxed)) {
        transform(half, c, e, along_j);
        return true;
      }
    }
  };
  for (;;) {
    bool busy = false;
    for (int half = 0; half < 2; ++half) {
      Half& hf = halves_[std::size_t(half)];
      if (!owns(half) || hf.next == hf.count) continue;
      for (int k = 0; k < kSteps && hf.next < hf.count; ++k) step(half);
      // a row is read by the two rows after it in the half: claimable once they are finished
      hf.finished.store(hf.next == hf.count ? hf.count : std::max(hf.next - 2, 0), std::memory_order_release);
      busy = true;
    }
    // its own rows first (still in the cache), then the other half's
    for (int pass = 0; pass < 2; ++pass)
      for (int half = 0; half < 2; ++half)
        if (owns(half) == (pass == 0))
          while (claim(half)) busy = true;
    if (std::all_of(halves_.begin(), halves_.end(),
                    [](const Half& hf) { return hf.claimed.load(std::memory_order_acquire) == hf.count; }))
      return;
    if (!busy) std::this_thread::yield();  // the other half's owner has not finished a row since
  }
}

TwistedBuffers twisted_buffers(int rows, int cols, int threads, unsigned planning) {
  TwistedBuffers b;
  if (rows < kMinTwistRows) return b;
  for (int t = 1; t < threads; ++t) b.low_along_i.emplace_back(rows, planning);
  for (detail::AlignedBuffer& w : b.scratch) w = detail::AlignedBuffer(9 * std::size_t(cols));
  return b;
}

void twisted_solve(const ModeFactors& f, const TwistFactors& tw, const LowModes& low, const SweepInput& in,
                   const std::array<double*, 3>& grid, TwistedBuffers& buffers, detail::SineTransform& along_i,
                   std::vector<detail::SineTransform>& along_j, int threads,
                   const std::function<void(int, int, const double*)>& done) {
  ChunkOutput low_out;
  low_out.grid = grid;
  const int parts = 4;
  const Eigen::MatrixXd no_sines(f.cols, 0);  // no dots wanted
  std::vector<Eigen::MatrixXd> no_dots(static_cast<std::size_t>(parts));
  const double scale_j = std::sqrt(2.0 / (f.cols + 1));
  std::optional<TwistedUp> up;
  [[maybe_unused]] const int nt = threads;
#if defined(_OPENMP)
#pragma omp parallel num_threads(nt) if (nt > 1)
#endif
  {
#if defined(_OPENMP)
#pragma omp for schedule(dynamic)
#endif
    for (int u = 0; u < 2 + parts; ++u) {
      if (u < 2) {
        twisted_down(f, tw, u, in, grid, buffers.ends[std::size_t(u)]);
      } else {
        const int part = u - 2, t = thread_index();
        solve_low_modes(low, t == 0 ? along_i : buffers.low_along_i[std::size_t(t - 1)], 3, in, low_out, no_sines,
                        no_dots[std::size_t(part)], low.modes * part / parts, low.modes * (part + 1) / parts);
      }
    }
#if defined(_OPENMP)
#pragma omp single
#endif
    up.emplace(f, tw, buffers.ends, grid, std::array<double*, 2>{buffers.scratch[0].data(), buffers.scratch[1].data()},
               scale_j, done);
    // (the single's barrier: up is made, and both ways down are done)
    up->work(thread_index(), team_size(), along_j[std::size_t(thread_index())]);
  }
}

}  // namespace coons::solvers::fast5_detail
