#include "multigrid_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "multigrid_kernels.h"

// The outer loop over rows on loop_threads(L) threads (a local `nt`); every iteration writes its own
// points, so the result does not depend on the count.
#if defined(_OPENMP)
#define COONS_PARALLEL_ROWS _Pragma("omp parallel for num_threads(nt) if (nt > 1) schedule(static)")
#else
#define COONS_PARALLEL_ROWS
#endif

namespace coons::solvers::mg_detail {

// r = b − A x (kApply: r = A x) on the free points, row by row.
template <bool kApply>
static void eval_grid(const Level& L, const Vector& b, const Vector& x, Vector& r) {
  r.resize(L.points());
  [[maybe_unused]] const int nt = loop_threads(L);
  dispatch(L, [&](auto radius, auto constant) {
    constexpr int kR = decltype(radius)::value;
    constexpr bool kConst = decltype(constant)::value;
    COONS_PARALLEL_ROWS
    for (int i = 0; i < L.rows; ++i)
      eval_row<kR, kConst, kApply>(L, kApply ? nullptr : b.data(), x.data(), r.data() + Eigen::Index(i) * L.cols, i, 0,
                                   L.cols, 1);
  });
}

// The same on a level with factors: t = (I ⊗ q) x on a block of rows and the 2r rows around it,
// then (A x)(i, j) = Σ_a p(a) t(i + a, j); x is zero at fixed points and outside the grid, as the
// (2r+1)² sum assumes. Each block of rows writes its own points: the result does not depend on the
// thread count. kR: the radius (1 or 2), so that the interior taps unroll.
template <int kR, bool kApply>
static void eval_factored(const Level& L, const Vector& b, const Vector& x, Vector& r) {
  constexpr int kBlock = 32;
  r.resize(L.points());
  const int R = L.rows, C = L.cols, blocks = (R + kBlock - 1) / kBlock;
  const double* p = L.factor_i.data() + kR;
  const double* q = L.factor_j.data() + kR;
  [[maybe_unused]] const int nt = loop_threads(L);
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int block = 0; block < blocks; ++block) {
    const int i0 = block * kBlock, i1 = std::min(R, i0 + kBlock);
    const int t0 = std::max(0, i0 - kR), t1 = std::min(R, i1 + kR);
    std::vector<double> t(std::size_t(t1 - t0) * std::size_t(C));
    for (int i = t0; i < t1; ++i) {
      const double* xi = x.data() + Eigen::Index(i) * C;
      double* ti = t.data() + std::size_t(i - t0) * std::size_t(C);
      auto edge = [&](int j) {
        double s = 0;
        for (int k = std::max(-kR, -j); k <= std::min(kR, C - 1 - j); ++k) s += q[k] * xi[j + k];
        ti[j] = s;
      };
      for (int j = 0; j < std::min(kR, C); ++j) edge(j);
      for (int j = kR; j < C - kR; ++j) {
        double s = 0;
        for (int k = -kR; k <= kR; ++k) s += q[k] * xi[j + k];
        ti[j] = s;
      }
      for (int j = std::max(kR, C - kR); j < C; ++j) edge(j);
    }
    for (int i = i0; i < i1; ++i) {
      double* out = r.data() + Eigen::Index(i) * C;
      const unsigned char* free = L.free.data() + Eigen::Index(i) * C;
      const int lo = std::max(-kR, -i), hi = std::min(kR, R - 1 - i);
      for (int j = 0; j < C; ++j) out[j] = 0;
      for (int a = lo; a <= hi; ++a) {
        const double* ta = t.data() + std::size_t(i + a - t0) * std::size_t(C);
        for (int j = 0; j < C; ++j) out[j] += p[a] * ta[j];
      }
      for (int j = 0; j < C; ++j) {
        if constexpr (kApply) {
          out[j] = free[j] ? out[j] : 0.0;
        } else {
          out[j] = free[j] ? b[Eigen::Index(i) * C + j] - out[j] : 0.0;
        }
      }
    }
  }
}

template <bool kApply>
static void eval_factored(const Level& L, const Vector& b, const Vector& x, Vector& r) {
  if (L.radius == 1)
    eval_factored<1, kApply>(L, b, x, r);
  else
    eval_factored<2, kApply>(L, b, x, r);
}

void residual(const Level& L, const Vector& b, const Vector& x, Vector& r) {
  if (L.factor_i.empty())
    eval_grid<false>(L, b, x, r);
  else
    eval_factored<false>(L, b, x, r);
}

void apply_level(const Level& L, const Vector& x, Vector& y) {
  if (L.factor_i.empty())
    eval_grid<true>(L, x, x, y);
  else
    eval_factored<true>(L, x, x, y);
}

// Interpolation weight of a fine point at offset a from a coarse point's own fine point, along one
// axis: linear (1/2, 1, 1/2) or cubic (−1/16, 0, 9/16, 1, 9/16, 0, −1/16). Values beyond the grid
// and at fixed points are zero (they carry a zero correction).
static double interp_weight(int reach, int a) {
  if (a < 0) a = -a;
  if (reach == 1) return a == 0 ? 1.0 : a == 1 ? 0.5 : 0.0;
  return a == 0 ? 1.0 : a == 1 ? 9.0 / 16 : a == 3 ? -1.0 / 16 : 0.0;
}

// The coarse points whose interpolation reaches fine index f along one axis, with their weights.
static int coarse_parents(int f, int coarse_len, int offset, int reach, int* parent, double* weight) {
  int n = 0;
  for (int K = (f - offset - reach) / 2 - 1; K <= (f - offset + reach) / 2 + 1; ++K) {
    if (K < 0 || K >= coarse_len) continue;
    const int a = f - (2 * K + offset);
    if (a < -reach || a > reach) continue;
    const double w = interp_weight(reach, a);
    if (w == 0) continue;
    parent[n] = K;
    weight[n++] = w;
  }
  return n;
}

// The coarse parents of every fine index along one axis.
struct Parents {
  int count = 0, index[4] = {0, 0, 0, 0};
  double weight[4] = {0, 0, 0, 0};
};

static std::vector<Parents> parents_along(int len, int coarse_len, int offset, int reach) {
  std::vector<Parents> out(static_cast<std::size_t>(len));
  for (int f = 0; f < len; ++f)
    out[std::size_t(f)].count =
        coarse_parents(f, coarse_len, offset, reach, out[std::size_t(f)].index, out[std::size_t(f)].weight);
  return out;
}

// r_c = Pᵀ r (P: interpolation restricted to free points). At coarse points whose fine
// neighbourhood lies inside the grid the weights come from a table of the same products, added
// in the same order (the values do not change), without bounds checks.
void restrict_to(const Level& F, const Level& Cl, const Vector& r, Vector& rc) {
  const int h = Cl.reach, w = 2 * h + 1;
  rc.setZero(Cl.points());
  std::vector<double> weight(std::size_t(w) * w);
  for (int a = -h; a <= h; ++a)
    for (int c = -h; c <= h; ++c)
      weight[std::size_t(a + h) * std::size_t(w) + std::size_t(c + h)] = interp_weight(h, a) * interp_weight(h, c);
  // coarse I with every 2I + offset_i + a inside the fine rows (likewise J)
  auto inside = [h](int offset, int fine_len, int coarse_len, int& lo, int& hi) {
    const int last = fine_len - 1 - h - offset;  // 2I may reach this
    lo = std::max(0, (h - offset + 1) / 2);
    hi = last < 0 ? 0 : std::min(coarse_len, last / 2 + 1);
  };
  int I_lo = 0, I_hi = 0, J_lo = 0, J_hi = 0;
  inside(Cl.offset_i, F.rows, Cl.rows, I_lo, I_hi);
  inside(Cl.offset_j, F.cols, Cl.cols, J_lo, J_hi);
  [[maybe_unused]] const int nt = loop_threads(F);
  COONS_PARALLEL_ROWS
  for (int I = 0; I < Cl.rows; ++I)
    for (int J = 0; J < Cl.cols; ++J) {
      const Eigen::Index q = Eigen::Index(I) * Cl.cols + J;
      if (!Cl.free[q]) continue;
      double sum = 0;
      if (I >= I_lo && I < I_hi && J >= J_lo && J < J_hi) {
        const double* centre = r.data() + Eigen::Index(2 * I + Cl.offset_i) * F.cols + 2 * J + Cl.offset_j;
        for (int a = -h; a <= h; ++a) {
          const double* wa = &weight[std::size_t(a + h) * std::size_t(w) + std::size_t(h)];
          if (interp_weight(h, a) == 0) continue;
          const double* row = centre + Eigen::Index(a) * F.cols;
          for (int c = -h; c <= h; ++c) sum += wa[c] * row[c];
        }
        rc[q] = sum;
        continue;
      }
      for (int a = -h; a <= h; ++a) {
        const int i = 2 * I + Cl.offset_i + a;
        const double wa = interp_weight(h, a);
        if (i < 0 || i >= F.rows || wa == 0) continue;
        for (int c = -h; c <= h; ++c) {
          const int j = 2 * J + Cl.offset_j + c;
          if (j < 0 || j >= F.cols) continue;
          sum += wa * interp_weight(h, c) * r[Eigen::Index(i) * F.cols + j];  // r = 0 at fixed
        }
      }
      rc[q] = sum;
    }
}

// x += P x_c, fine row by fine row (each writes its own points): the sum over the coarse parents.
void prolong_add(const Level& F, const Level& Cl, const Vector& xc, Vector& x) {
  const std::vector<Parents> parents_i = parents_along(F.rows, Cl.rows, Cl.offset_i, Cl.reach);
  const std::vector<Parents> parents_j = parents_along(F.cols, Cl.cols, Cl.offset_j, Cl.reach);
  [[maybe_unused]] const int nt = loop_threads(F);
  COONS_PARALLEL_ROWS
  for (int i = 0; i < F.rows; ++i) {
    const Parents& pi = parents_i[std::size_t(i)];
    for (int j = 0; j < F.cols; ++j) {
      const Eigen::Index p = Eigen::Index(i) * F.cols + j;
      if (!F.free[p]) continue;
      const Parents& pj = parents_j[std::size_t(j)];
      double sum = 0;
      for (int a = 0; a < pi.count; ++a) {
        const double* row = xc.data() + Eigen::Index(pi.index[a]) * Cl.cols;
        double along = 0;
        for (int c = 0; c < pj.count; ++c) along += pj.weight[c] * row[pj.index[c]];  // xc = 0 at fixed points
        sum += pi.weight[a] * along;
      }
      x[p] += sum;
    }
  }
}

// The Galerkin operator Pᵀ A P of the fine level, as one stencil per coarse point.
Level galerkin_coarse(const Level& F, int reach) {
  Level Cl;
  // Coarse points start one point inside the free region (its bounding box), as in the standard
  // vertex-centred coarsening, whatever fixed margin the grid carries.
  int first_i = F.rows, first_j = F.cols;
  for (int i = 0; i < F.rows; ++i)
    for (int j = 0; j < F.cols; ++j)
      if (F.free[std::size_t(i) * F.cols + j]) {
        first_i = std::min(first_i, i);
        first_j = std::min(first_j, j);
      }
  Cl.offset_i = (first_i + 1) % 2;
  Cl.offset_j = (first_j + 1) % 2;
  Cl.rows = (F.rows + 1 - Cl.offset_i) / 2;
  Cl.cols = (F.cols + 1 - Cl.offset_j) / 2;
  Cl.reach = reach;
  Cl.radius = (F.radius + 2 * reach) / 2;
  const int rc = Cl.radius, wc = Cl.width(), rf = F.radius, wf = F.width();
  Cl.free.assign(std::size_t(Cl.points()), 0);
  for (int I = 0; I < Cl.rows; ++I)
    for (int J = 0; J < Cl.cols; ++J)
      Cl.free[std::size_t(I) * Cl.cols + J] = F.free[std::size_t(2 * I + Cl.offset_i) * F.cols + 2 * J + Cl.offset_j];
  Cl.unknowns = std::count(Cl.free.begin(), Cl.free.end(), 1);
  Cl.coef.assign(std::size_t(Cl.points()) * wc * wc, 0.0);
  // Two passes, row by row: B = A P for the fine rows a coarse row needs (kept in a ring of
  // 2·reach + 1 rows), then A_c = Pᵀ B. B(p, ·) lives in a bw × bw window of coarse points.
  const std::vector<Parents> parents_i = parents_along(F.rows, Cl.rows, Cl.offset_i, reach);
  const std::vector<Parents> parents_j = parents_along(F.cols, Cl.cols, Cl.offset_j, reach);
  const int bw = rf + reach + 1;
  auto window_start = [&](int f, int offset) {  // ceil((f − rf − reach − offset) / 2)
    const int t = f - rf - reach - offset;
    return t >= 0 ? (t + 1) / 2 : -((-t) / 2);
  };
  // B(p, ·) of the free fine point p = (i, j) into b (bw × bw, zero on entry).
  auto compute_point = [&](int i, int j, double* b) {
    const int lo_i = window_start(i, Cl.offset_i), lo_j = window_start(j, Cl.offset_j);
    const double* A = F.at(Eigen::Index(i) * F.cols + j);
    for (int di = -rf; di <= rf; ++di) {
      const int k = i + di;
      if (k < 0 || k >= F.rows) continue;
      const Parents& pk = parents_i[std::size_t(k)];
      for (int dj = -rf; dj <= rf; ++dj) {
        const int l = j + dj;
        if (l < 0 || l >= F.cols) continue;
        const double aw = A[(di + rf) * wf + dj + rf];
        if (aw == 0 || !F.free[Eigen::Index(k) * F.cols + l]) continue;
        const Parents& pl = parents_j[std::size_t(l)];
        for (int s = 0; s < pk.count; ++s)
          for (int t = 0; t < pl.count; ++t)
            b[(pk.index[s] - lo_i) * bw + pl.index[t] - lo_j] += aw * pk.weight[s] * pl.weight[t];
      }
    }
  };
  // A_c(I, J) into out (wc × wc, zero on entry) from B_at(i, j), the B of the fine point (i, j).
  auto accumulate = [&](int I, int J, double* out, auto&& B_at) {
    for (int a = -reach; a <= reach; ++a) {
      const int i = 2 * I + Cl.offset_i + a;
      const double wa = interp_weight(reach, a);
      if (i < 0 || i >= F.rows || wa == 0) continue;
      const int lo_i = window_start(i, Cl.offset_i);
      for (int c = -reach; c <= reach; ++c) {
        const int j = 2 * J + Cl.offset_j + c;
        const double pw = wa * interp_weight(reach, c);
        if (j < 0 || j >= F.cols || pw == 0 || !F.free[Eigen::Index(i) * F.cols + j]) continue;
        const double* b = B_at(i, j);
        const int lo_j = window_start(j, Cl.offset_j);
        for (int u = 0; u < bw; ++u)
          for (int v = 0; v < bw; ++v) {
            const double value = b[u * bw + v];
            if (value == 0) continue;
            const int K1 = lo_i + u, K2 = lo_j + v;  // within the coarse radius of (I, J)
            if (!Cl.free[std::size_t(K1) * Cl.cols + K2]) continue;
            out[(K1 - I + rc) * wc + K2 - J + rc] += pw * value;
          }
      }
    }
  };
  // The deep interior. A_c(I, J) depends only on the fine stencils and free flags within
  // deep_radius = 2·reach + rf of its fine point (2I + offset_i, 2J + offset_j), and on nothing else
  // (the parents of a point away from the grid's edges are its neighbours' shifted by 2): where
  // that window lies in the grid and every point of it is free with the level's common stencil,
  // A_c is the same stencil, computed once (by the same sums, so equal bit for bit to what the
  // point-by-point pass gives) and copied. Only the fine points a coarse point outside the deep
  // interior needs get their B. On a rectangle this leaves O(rows + cols) points to the sums.
  const int deep_radius = 2 * reach + rf;
  std::vector<std::int64_t> good_sum;  // summed-area table of the good fine points, (rows+1) × (cols+1)
  if (!F.common.empty()) {
    const std::size_t ww = std::size_t(wf) * wf, C1 = std::size_t(F.cols) + 1;
    good_sum.assign((std::size_t(F.rows) + 1) * C1, 0);
    for (int i = 0; i < F.rows; ++i) {
      std::int64_t row = 0;  // good points of row i up to j
      for (int j = 0; j < F.cols; ++j) {
        const Eigen::Index p = Eigen::Index(i) * F.cols + j;
        row += F.free[std::size_t(p)] && (F.constant || std::equal(F.at(p), F.at(p) + ww, F.common.begin()));
        good_sum[(std::size_t(i) + 1) * C1 + std::size_t(j) + 1] =
            good_sum[std::size_t(i) * C1 + std::size_t(j) + 1] + row;
      }
    }
  }
  // Every fine point within `radius` of (i, j) lies in the grid and is good.
  auto all_good = [&](int i, int j, int radius) {
    if (good_sum.empty() || i - radius < 0 || j - radius < 0 || i + radius >= F.rows || j + radius >= F.cols)
      return false;
    const std::size_t C1 = std::size_t(F.cols) + 1, i0 = std::size_t(i - radius), i1 = std::size_t(i + radius) + 1,
                      j0 = std::size_t(j - radius), j1 = std::size_t(j + radius) + 1;
    const std::int64_t side = 2 * radius + 1;
    return good_sum[i1 * C1 + j1] - good_sum[i0 * C1 + j1] - good_sum[i1 * C1 + j0] + good_sum[i0 * C1 + j0] ==
           side * side;
  };
  auto deep = [&](int I, int J) { return all_good(2 * I + Cl.offset_i, 2 * J + Cl.offset_j, deep_radius); };
  std::vector<double> deep_stencil;  // A_c of the deep interior, once one deep point is found
  for (int I = 0; I < Cl.rows && deep_stencil.empty() && !good_sum.empty(); ++I)
    for (int J = 0; J < Cl.cols; ++J) {
      if (!deep(I, J)) continue;
      // its fine neighbourhood's B, in a (2·reach + 1)² block of windows
      const int side = 2 * reach + 1, fi = 2 * I + Cl.offset_i, fj = 2 * J + Cl.offset_j;
      std::vector<double> local(std::size_t(side) * side * std::size_t(bw) * bw, 0.0);
      auto local_at = [&](int i, int j) {
        return &local[(std::size_t(i - fi + reach) * side + std::size_t(j - fj + reach)) * std::size_t(bw) * bw];
      };
      for (int a = -reach; a <= reach; ++a)
        for (int c = -reach; c <= reach; ++c) compute_point(fi + a, fj + c, local_at(fi + a, fj + c));
      deep_stencil.assign(std::size_t(wc) * wc, 0.0);
      accumulate(I, J, deep_stencil.data(), [&](int i, int j) -> const double* { return local_at(i, j); });
      break;
    }
  const int ring = 2 * reach + 1;
  std::vector<std::vector<double>> B(std::size_t(ring), std::vector<double>(std::size_t(F.cols) * bw * bw, 0.0));
  auto compute_row = [&](int i) {
    std::vector<double>& row = B[std::size_t(i % ring)];
    std::fill(row.begin(), row.end(), 0.0);
    for (int j = 0; j < F.cols; ++j) {
      const Eigen::Index p = Eigen::Index(i) * F.cols + j;
      // (a point whose coarse neighbours within reach are all deep is needed by none)
      if (!F.free[p] || (!deep_stencil.empty() && all_good(i, j, reach + deep_radius))) continue;
      compute_point(i, j, &row[std::size_t(j) * bw * bw]);
    }
  };
  int next_row = 0;
  for (int I = 0; I < Cl.rows; ++I) {
    const int last = std::min(F.rows - 1, 2 * I + Cl.offset_i + reach);
    for (; next_row <= last; ++next_row) compute_row(next_row);
    for (int J = 0; J < Cl.cols; ++J) {
      const Eigen::Index q = Eigen::Index(I) * Cl.cols + J;
      if (!Cl.free[q]) continue;
      double* out = &Cl.coef[std::size_t(q) * wc * wc];
      if (!deep_stencil.empty() && deep(I, J)) {
        std::copy(deep_stencil.begin(), deep_stencil.end(), out);
        continue;
      }
      accumulate(I, J, out,
                 [&](int i, int j) -> const double* { return &B[std::size_t(i % ring)][std::size_t(j) * bw * bw]; });
    }
  }
  return Cl;
}

void find_common_stencil(Level& L) {
  const int r = L.radius, ww = L.width() * L.width(), R = L.rows, C = L.cols;
  L.common_lo.assign(std::size_t(R), 0);
  L.common_hi.assign(std::size_t(R), 0);
  L.common.clear();
  if (R < 2 * r + 1 || C < 2 * r + 1) return;
  // The fine level's one stencil, or on a Galerkin level the one of the longest run of free
  // interior points with equal stencils along a row: on a rectangle (or away from holes) the
  // Galerkin sums are the same at every interior point away from the boundary.
  const std::size_t bytes = sizeof(double) * std::size_t(ww);
  const double* best = L.at(Eigen::Index(R / 2) * C + C / 2);
  if (!L.constant) {
    int longest = 0;
    for (int i = r; i + r < R; ++i)
      for (int j = r, run = 0; j + r < C; ++j) {
        const Eigen::Index p = Eigen::Index(i) * C + j;
        run = !L.free[std::size_t(p)] ? 0 : run > 0 && std::memcmp(L.at(p), L.at(p - 1), bytes) == 0 ? run + 1 : 1;
        if (run > longest) {
          longest = run;
          best = L.at(p);
        }
      }
  }
  L.common.assign(best, best + ww);
  for (int i = r; i + r < R; ++i) {
    auto fits = [&](int j) {
      const Eigen::Index p = Eigen::Index(i) * C + j;
      return L.free[std::size_t(p)] && (L.constant || std::memcmp(L.at(p), L.common.data(), bytes) == 0);
    };
    int best_lo = 0, best_hi = 0;
    for (int j = r; j + r < C;) {
      if (!fits(j)) {
        ++j;
        continue;
      }
      const int lo = j;
      while (j + r < C && fits(j)) ++j;
      if (j - lo > best_hi - best_lo) {
        best_lo = lo;
        best_hi = j;
      }
    }
    L.common_lo[std::size_t(i)] = best_lo;
    L.common_hi[std::size_t(i)] = best_hi;
  }
}

bool setup_direct(Level& L) {
  L.number.assign(std::size_t(L.points()), -1);
  Eigen::Index n = 0;
  for (Eigen::Index p = 0; p < L.points(); ++p)
    if (L.free[p]) L.number[p] = n++;
  std::vector<Eigen::Triplet<double>> entries;
  const int r = L.radius, w = L.width();
  for (int i = 0; i < L.rows; ++i)
    for (int j = 0; j < L.cols; ++j) {
      const Eigen::Index p = Eigen::Index(i) * L.cols + j;
      if (!L.free[p]) continue;
      const double* a = L.at(p);
      for (int di = -r; di <= r; ++di)
        for (int dj = -r; dj <= r; ++dj) {
          const int ii = i + di, jj = j + dj;
          if (ii < 0 || ii >= L.rows || jj < 0 || jj >= L.cols) continue;
          const Eigen::Index col = L.number[Eigen::Index(ii) * L.cols + jj];
          if (col >= 0 && a[(di + r) * w + dj + r] != 0)
            entries.emplace_back(int(L.number[p]), int(col), a[(di + r) * w + dj + r]);
        }
    }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  L.direct = std::make_unique<Eigen::SparseLU<Eigen::SparseMatrix<double>>>();
  L.direct->compute(A);
  return L.direct->info() == Eigen::Success;
}

void solve_direct(const Level& L, const Vector& b, Vector& x) {
  Vector bf(L.unknowns);
  for (Eigen::Index p = 0; p < L.points(); ++p)
    if (L.number[p] >= 0) bf[L.number[p]] = b[p];
  const Vector xf = L.direct->solve(bf);
  x.setZero(L.points());
  for (Eigen::Index p = 0; p < L.points(); ++p)
    if (L.number[p] >= 0) x[p] = xf[L.number[p]];
}

}  // namespace coons::solvers::mg_detail
