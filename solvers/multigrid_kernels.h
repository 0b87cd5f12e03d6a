// The stencil kernels of one multigrid level (internal to the solvers layer): (A x)(i, j) at one
// point, specialised on the radius (1 … 5, or 0: the level's own) and on a constant stencil (the
// finest level) so that the interior loops run without bounds checks over registers of weights.
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

// One row i: out[j] = b[p] − (A x)(p) (kApply: (A x)(p)) at the free points, 0 at fixed ones, for
// j = first, first + step, … < end (out indexed like the grid row).
template <int kR, bool kConst, bool kApply>
inline void eval_row(const Level& L, const double* b, const double* x, double* out, int i, int first, int end,
                     int step) {
  const int r = radius_of<kR>(L), C = L.cols;
  const Eigen::Index base = Eigen::Index(i) * C;
  const unsigned char* free = L.free.data() + base;
  const bool inner = i >= r && i + r < L.rows;
  auto finish = [&](int j, double s) {
    if constexpr (kApply) {
      out[j] = free[j] ? s : 0.0;
    } else {
      out[j] = free[j] ? b[base + j] - s : 0.0;
    }
  };
  if (step == 1 && inner) {
    const int lo = std::clamp(r, first, end), hi = std::clamp(C - r, lo, end);
    for (int j = first; j < lo; ++j) finish(j, apply_at_edge(L, x, i, j));
    for (int j = lo; j < hi; ++j) finish(j, apply_at_interior<kR, kConst>(L, x, i, j));
    for (int j = hi; j < end; ++j) finish(j, apply_at_edge(L, x, i, j));
    return;
  }
  for (int j = first; j < end; j += step)
    finish(j, inner && j >= r && j + r < C ? apply_at_interior<kR, kConst>(L, x, i, j) : apply_at_edge(L, x, i, j));
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
