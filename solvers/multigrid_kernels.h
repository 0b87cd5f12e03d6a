// The stencil kernels of one multigrid level (internal to the solvers layer): (A x)(i, j) at one
// point, specialised on the radius (1 … 5, or 0: the level's own) and on a constant stencil (the
// finest level), and on each row's stretch of free interior points that share the level's common
// stencil (every level), so that the interior loops run without bounds or mask checks over
// registers of weights.
// Every variant adds the products in the same order (stencil row by row), so results do not depend
// on which path a point takes.
#pragma once

#include <algorithm>
#include <type_traits>
#include <utility>

#include "multigrid_levels.h"

namespace coons::solvers::mg_detail {

// (A x)(i, j) with bounds checks; x is zero at fixed points and outside the grid.
inline double apply_at_edge(const Level& L, const double* x, int i, int j) {
  const int r = L.radius, w = L.width(), C = L.cols;
  const double* a = L.at(Eigen::Index(i) * C + j);
  double sum = 0;
  for (int di = -r; di <= r; ++di) {
    const int ii = i + di;
    if (ii < 0 || ii >= L.rows) continue;
    for (int dj = -r; dj <= r; ++dj) {
      const int jj = j + dj;
      if (jj < 0 || jj >= C) continue;
      sum += a[(di + r) * w + dj + r] * x[Eigen::Index(ii) * C + jj];
    }
  }
  return sum;
}

template <int kR>
inline int radius_of(const Level& L) {
  if constexpr (kR > 0) {
    return kR;
  } else {
    return L.radius;
  }
}

// (A x)(i, j) at an interior point (i ± r, j ± r inside the grid).
template <int kR, bool kConst>
inline double apply_at_interior(const Level& L, const double* x, int i, int j) {
  const int r = radius_of<kR>(L), w = 2 * r + 1, C = L.cols;
  const Eigen::Index p = Eigen::Index(i) * C + j;
  const double* a = kConst ? L.coef.data() : L.coef.data() + p * w * w;
  double sum = 0;
  for (int di = -r; di <= r; ++di) {
    const double* xr = x + p + Eigen::Index(di) * C;
    const double* ar = a + (di + r) * w + r;
    for (int dj = -r; dj <= r; ++dj) sum += ar[dj] * xr[dj];
  }
  return sum;
}

// out[j] = b[j] − (A x)(j) (kApply: (A x)(j)) for j = lo, lo + step, … < hi of one interior row,
// all of whose points are free and have the stencil a (kR > 0): the weights sit in registers and
// no point needs a bounds or mask check (the unit-step loop vectorises). b, x, out: the row's
// start; kPacked: out holds the values one after another, out[0] that of lo. The products are
// added in the order of apply_at_interior, so the values are the same.
template <int kR, bool kApply, bool kUnit, bool kPacked = false>
inline void eval_run(const double* a, const double* __restrict b, const double* __restrict x, double* __restrict out,
                     Eigen::Index C, int lo, int hi, int step) {
  constexpr int kW = 2 * kR + 1;
  double c[kW * kW];
  for (int k = 0; k < kW * kW; ++k) c[k] = a[k];
  const double* xr[kW];
  for (int di = -kR; di <= kR; ++di) xr[di + kR] = x + Eigen::Index(di) * C;
  auto point = [&](int j, double& o) {
    double sum = 0;
    for (int u = 0; u < kW; ++u)
      for (int v = 0; v < kW; ++v) sum += c[u * kW + v] * xr[u][j + v - kR];
    o = kApply ? sum : b[j] - sum;
  };
  if constexpr (kPacked) {
    for (int j = lo, t = 0; j < hi; j += step, ++t) point(j, out[t]);
  } else if constexpr (kUnit) {
    for (int j = lo; j < hi; ++j) point(j, out[j]);
  } else {
    for (int j = lo; j < hi; j += step) point(j, out[j]);
  }
}

// One row i: out[j] = b[p] − (A x)(p) (kApply: (A x)(p)) at the free points, 0 at fixed ones, for
// j = first, first + step, … < end (out indexed like the grid row; kPacked: out[(j − first)/step]).
// On an inner row the stretch of free points that share the level's common stencil takes
// eval_run; the rest point by point.
template <int kR, bool kConst, bool kApply, bool kPacked = false>
inline void eval_row(const Level& L, const double* b, const double* x, double* out, int i, int first, int end,
                     int step) {
  const int r = radius_of<kR>(L), C = L.cols;
  const Eigen::Index base = Eigen::Index(i) * C;
  const unsigned char* free = L.free.data() + base;
  const bool inner = i >= r && i + r < L.rows;
  auto finish = [&](int j, double s) {
    double& o = kPacked ? out[(j - first) / step] : out[j];
    if constexpr (kApply) {
      o = free[j] ? s : 0.0;
    } else {
      o = free[j] ? b[base + j] - s : 0.0;
    }
  };
  auto one = [&](int j) {
    finish(j, inner && j >= r && j + r < C ? apply_at_interior<kR, kConst>(L, x, i, j) : apply_at_edge(L, x, i, j));
  };
  int run_lo = 0, run_hi = 0;  // the stretch [run_lo, run_hi) of the common stencil on this row
  if constexpr (kR > 0) {
    if (inner && !L.common_lo.empty()) {
      run_lo = L.common_lo[std::size_t(i)];
      run_hi = L.common_hi[std::size_t(i)];
    }
  }
  // the first j of the sequence at or after run_lo, the end of the run, and the first j after it
  const int lo = run_lo <= first ? first : first + (run_lo - first + step - 1) / step * step;
  const int stop = std::min(end, run_hi);
  if (lo >= stop) {
    for (int j = first; j < end; j += step) one(j);
    return;
  }
  const int hi = lo + (stop - lo + step - 1) / step * step;
  for (int j = first; j < lo; j += step) one(j);
  if constexpr (kR > 0) {
    const double* a = L.common.data();
    const double* bb = kApply ? nullptr : b + base;
    if constexpr (kPacked)
      eval_run<kR, kApply, false, true>(a, bb, x + base, out + (lo - first) / step, C, lo, stop, step);
    else if (step == 1)
      eval_run<kR, kApply, true>(a, bb, x + base, out, C, lo, stop, 1);
    else
      eval_run<kR, kApply, false>(a, bb, x + base, out, C, lo, stop, step);
  }
  for (int j = hi; j < end; j += step) one(j);
}

// Calls f(std::integral_constant<int, R>, std::bool_constant<constant>) with R = the level's radius
// when it is 1 … 5 (the fine stencils have 1 or 2, bicubic Galerkin levels 4 and 5), else 0 (any).
template <bool kConst, class F>
inline void dispatch_radius(int radius, F&& f) {
  using Constant = std::bool_constant<kConst>;
  switch (radius) {
    case 1:
      return f(std::integral_constant<int, 1>{}, Constant{});
    case 2:
      return f(std::integral_constant<int, 2>{}, Constant{});
    case 3:
      return f(std::integral_constant<int, 3>{}, Constant{});
    case 4:
      return f(std::integral_constant<int, 4>{}, Constant{});
    case 5:
      return f(std::integral_constant<int, 5>{}, Constant{});
    default:
      return f(std::integral_constant<int, 0>{}, Constant{});
  }
}

template <class F>
inline void dispatch(const Level& L, F&& f) {
  if (L.constant) return dispatch_radius<true>(L.radius, std::forward<F>(f));
  return dispatch_radius<false>(L.radius, std::forward<F>(f));
}

}  // namespace coons::solvers::mg_detail
