#include "fast5_modes.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "vector_clones.h"

namespace coons::solvers::fast5_detail {

Eigen::VectorXd first_sine_column(int n) {
  Eigen::VectorXd s(n);
  for (int k = 0; k < n; ++k) s[k] = std::sqrt(2.0 / (n + 1)) * std::sin(M_PI * (k + 1) / (n + 1));
  return s;
}

Eigen::VectorXd second_difference_eigenvalues(int n) {
  Eigen::VectorXd e(n);
  for (int k = 0; k < n; ++k) e[k] = 4 * std::pow(std::sin(M_PI * (k + 1) / (2.0 * (n + 1))), 2);
  return e;
}

namespace {

// The row r factors of the modes [qa, qb) all read from one place: the stored row (q < active[r])
// or the limits. base(r, q) returns pointers indexed by q.
struct FactorPointers {
  const double* inv_d;
  const double* l1;
  const double* l2;
};
FactorPointers factor_pointers(const ModeFactors& f, int r, int q) {
  if (q < f.active[std::size_t(r)]) {
    const std::size_t o = f.offset[std::size_t(r)];
    return {f.inv_d.data() + o, f.l1.data() + o, f.l2.data() + o};
  }
  return {f.lim_inv_d.data(), f.lim_l1.data(), f.lim_l2.data()};
}

// The kernels below work on the rows of all three right-hand sides at once, so that a factor is
// loaded once for the three; w0, w1, w2 are their rows (n modes from the segment's first), and
// the row above (below) a row is `stride` doubles before (after) it. rows ∈ {0, 1, 2}: how many
// rows above (below) there are to eliminate.

// Down: w_c = y_c + ze_c·te + zo_c·to − l1·(row above) − l2·(row two above).
COONS_VECTOR_CLONES void down_rows(double* __restrict w0, double* __restrict w1, double* __restrict w2,
                                   const double* __restrict y0, const double* __restrict y1,
                                   const double* __restrict y2, const double* __restrict te,
                                   const double* __restrict to, const std::array<double, 6>& z,
                                   const double* __restrict l1, const double* __restrict l2, std::ptrdiff_t stride,
                                   int rows, int n) {
  const double ze0 = z[0], zo0 = z[1], ze1 = z[2], zo1 = z[3], ze2 = z[4], zo2 = z[5];
  const std::ptrdiff_t s1 = stride, s2 = 2 * stride;
  if (rows == 2) {
    for (int q = 0; q < n; ++q) {
      const double a = l1[q], b = l2[q], e = te[q], o = to[q];
      w0[q] = y0[q] + ze0 * e + zo0 * o - a * w0[q - s1] - b * w0[q - s2];
      w1[q] = y1[q] + ze1 * e + zo1 * o - a * w1[q - s1] - b * w1[q - s2];
      w2[q] = y2[q] + ze2 * e + zo2 * o - a * w2[q - s1] - b * w2[q - s2];
    }
  } else if (rows == 1) {
    for (int q = 0; q < n; ++q) {
      const double a = l1[q], e = te[q], o = to[q];
      w0[q] = y0[q] + ze0 * e + zo0 * o - a * w0[q - s1];
      w1[q] = y1[q] + ze1 * e + zo1 * o - a * w1[q - s1];
      w2[q] = y2[q] + ze2 * e + zo2 * o - a * w2[q - s1];
    }
  } else {
    for (int q = 0; q < n; ++q) {
      const double e = te[q], o = to[q];
      w0[q] = y0[q] + ze0 * e + zo0 * o;
      w1[q] = y1[q] + ze1 * e + zo1 * o;
      w2[q] = y2[q] + ze2 * e + zo2 * o;
    }
  }
}

using detail::Lanes;  // vector_clones.h

// Down for three rows in their edge form (fast5_rows.h), the transform formed in the same pass:
// w_c = ((A_c·s0 + B_c·s1) + Z_c·t) − l1·(row above) − l2·(row two above), with A_c, B_c, Z_c the
// coefficients of the mode's parity, k[6c + 2j + parity] (j: A, B, Z); `parity` is that of the
// first mode. The same operations in the same order as edge_row_transform and then down_rows
// (whose z term of the other parity adds a zero), so the same values.
template <int Rows>
COONS_VECTOR_CLONES void down_edge_rows(double* __restrict w0, double* __restrict w1, double* __restrict w2,
                                        const double* __restrict s0, const double* __restrict s1,
                                        const double* __restrict t, const std::array<double, 18>& k,
                                        const double* __restrict l1, const double* __restrict l2, std::ptrdiff_t stride,
                                        int n, int parity) {
  struct Row {
    double* w;
    Lanes a, b, z;  // lane l: the coefficient of the parity of the mode (first + l)
  };
  std::array<Row, 3> rows{Row{w0, {}, {}, {}}, Row{w1, {}, {}, {}}, Row{w2, {}, {}, {}}};
  for (std::size_t c = 0; c < 3; ++c)
    for (int l = 0; l < 4; ++l) {
      const auto par = std::size_t((parity + l) % 2);
      rows[c].a[l] = k[6 * c + par];
      rows[c].b[l] = k[6 * c + 2 + par];
      rows[c].z[l] = k[6 * c + 4 + par];
    }
  const std::ptrdiff_t sa = stride, sb = 2 * stride;
  Lanes x0, x1, tt, a{}, b{}, up1{}, up2{};
  int q = 0;
  for (; q + 4 <= n; q += 4) {
    std::memcpy(&x0, s0 + q, sizeof x0);
    std::memcpy(&x1, s1 + q, sizeof x1);
    std::memcpy(&tt, t + q, sizeof tt);
    if constexpr (Rows >= 1) std::memcpy(&a, l1 + q, sizeof a);
    if constexpr (Rows >= 2) std::memcpy(&b, l2 + q, sizeof b);
    for (Row& row : rows) {
      double* wc = row.w + q;
      Lanes r = (row.a * x0 + row.b * x1) + row.z * tt;
      if constexpr (Rows >= 1) {
        std::memcpy(&up1, wc - sa, sizeof up1);
        r = r - a * up1;
      }
      if constexpr (Rows >= 2) {
        std::memcpy(&up2, wc - sb, sizeof up2);
        r = r - b * up2;
      }
      std::memcpy(wc, &r, sizeof r);
    }
  }
  for (; q < n; ++q) {
    const auto par = std::size_t((parity + q) % 2);
    for (std::size_t c = 0; c < 3; ++c) {
      double* wc = rows[c].w + q;
      double r = (k[6 * c + par] * s0[q] + k[6 * c + 2 + par] * s1[q]) + k[6 * c + 4 + par] * t[q];
      if constexpr (Rows >= 1) r = r - l1[q] * wc[-sa];
      if constexpr (Rows >= 2) r = r - l2[q] * wc[-sb];
      *wc = r;
    }
  }
}

// Up: w_c = w_c·inv_d − l1·(row below) − l2·(row two below).
COONS_VECTOR_CLONES void up_rows(double* __restrict w0, double* __restrict w1, double* __restrict w2,
                                 const double* __restrict inv_d, const double* __restrict l1,
                                 const double* __restrict l2, std::ptrdiff_t stride, int rows, int n) {
  const std::ptrdiff_t s1 = stride, s2 = 2 * stride;
  if (rows == 2) {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q], a = l1[q], b = l2[q];
      w0[q] = w0[q] * d - a * w0[q + s1] - b * w0[q + s2];
      w1[q] = w1[q] * d - a * w1[q + s1] - b * w1[q + s2];
      w2[q] = w2[q] * d - a * w2[q + s1] - b * w2[q + s2];
    }
  } else if (rows == 1) {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q], a = l1[q];
      w0[q] = w0[q] * d - a * w0[q + s1];
      w1[q] = w1[q] * d - a * w1[q + s1];
      w2[q] = w2[q] * d - a * w2[q + s1];
    }
  } else {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q];
      w0[q] *= d;
      w1[q] *= d;
      w2[q] *= d;
    }
  }
}

// Up into another array: o_c = y_c·inv_d − l1·(o row below) − l2·(o row two below), the rows of o
// `stride` doubles apart (the same arithmetic as up_rows, so the same bits). Not merged with
// up_rows: that one works in place, which the __restrict here (what lets these loops vectorise
// without run-time alias checks on six arrays) forbids.
COONS_VECTOR_CLONES void up_rows_into(double* __restrict o0, double* __restrict o1, double* __restrict o2,
                                      const double* __restrict y0, const double* __restrict y1,
                                      const double* __restrict y2, const double* __restrict inv_d,
                                      const double* __restrict l1, const double* __restrict l2, std::ptrdiff_t stride,
                                      int rows, int n) {
  const std::ptrdiff_t s1 = stride, s2 = 2 * stride;
  if (rows == 2) {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q], a = l1[q], b = l2[q];
      o0[q] = y0[q] * d - a * o0[q + s1] - b * o0[q + s2];
      o1[q] = y1[q] * d - a * o1[q + s1] - b * o1[q + s2];
      o2[q] = y2[q] * d - a * o2[q + s1] - b * o2[q + s2];
    }
  } else if (rows == 1) {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q], a = l1[q];
      o0[q] = y0[q] * d - a * o0[q + s1];
      o1[q] = y1[q] * d - a * o1[q + s1];
      o2[q] = y2[q] * d - a * o2[q + s1];
    }
  } else {
    for (int q = 0; q < n; ++q) {
      const double d = inv_d[q];
      o0[q] = y0[q] * d;
      o1[q] = y1[q] * d;
      o2[q] = y2[q] * d;
    }
  }
}

// Σ x[i]·v[i] over the even i < n and over the odd i < n, in eight interleaved partial sums (so
// that the AVX2 clone adds whole vectors; the bits are the same in either clone).
COONS_VECTOR_CLONES std::array<double, 2> parity_dot(const double* __restrict x, const double* __restrict v, int n) {
  std::array<double, 8> acc{};
  int i = 0;
  for (; i + 8 <= n; i += 8)
    for (std::size_t l = 0; l < 8; ++l) acc[l] += x[i + int(l)] * v[i + int(l)];
  std::array<double, 2> sums{(acc[0] + acc[2]) + (acc[4] + acc[6]), (acc[1] + acc[3]) + (acc[5] + acc[7])};
  for (; i < n; ++i) sums[std::size_t(i % 2)] += x[i] * v[i];
  return sums;
}

}  // namespace

std::array<double, 3> mode_factor(const ModeFactors& f, int r, int q) {
  const FactorPointers p = factor_pointers(f, r, q);
  return {p.inv_d[q], p.l1[q], p.l2[q]};
}

void down_row(const ModeFactors& f, int e, int r, int b0, int b1, int count, const SweepInput& in,
              const std::array<double*, 3>& w, std::ptrdiff_t stride, const double* zeros, double* scratch) {
  const int n = b1 - b0;
  const auto input_of = [&](int c) -> const double* {
    if (c >= count) return zeros;
    if (const double* h = in.hats[std::size_t(c)]) return h + std::ptrdiff_t(r) * f.cols + b0;
    if (const EdgeRows* edges = in.edges[std::size_t(c)])
      return edge_row(*edges, r, in.s0, in.s1, b0, n, scratch + std::ptrdiff_t(c) * n);
    return zeros;
  };
  std::array<double, 6> z{};
  for (int c = 0; c < count && in.z; ++c) {
    z[2 * std::size_t(c)] = in.sign * (*in.z)[0](r, c);
    z[2 * std::size_t(c) + 1] = in.sign * (*in.z)[1](r, c);
  }
  // all three rows in their edge form: formed inside the down pass (no scratch row)
  const bool fused = in.t && count == 3 &&
                     std::all_of(in.edges.begin(), in.edges.end(),
                                 [&](const EdgeRows* edges) { return edges && edges->slot[std::size_t(r)] < 0; }) &&
                     std::none_of(in.hats.begin(), in.hats.end(), [](const double* h) { return h != nullptr; });
  std::array<double, 18> coef{};
  if (fused)
    for (std::size_t c = 0; c < 3; ++c) {
      const std::array<double, 4>& ends = in.edges[c]->ends[std::size_t(r)];
      coef[6 * c] = ends[0] + ends[3];  // A (of s0), even and odd modes
      coef[6 * c + 1] = ends[0] - ends[3];
      coef[6 * c + 2] = ends[1] + ends[2];  // B (of s1)
      coef[6 * c + 3] = ends[1] - ends[2];
      coef[6 * c + 4] = z[2 * c];  // Z (of t)
      coef[6 * c + 5] = z[2 * c + 1];
    }
  std::array<const double*, 3> y{};
  if (!fused) y = {input_of(0), input_of(1), input_of(2)};
  const int rows = std::min(e, 2);
  // cut where the factor rows e − 1 and e − 2 change from stored to limit (active is non-increasing)
  const int a1 = e >= 1 ? std::clamp(f.active[std::size_t(e) - 1], b0, b1) : b1;
  const int a2 = e >= 2 ? std::clamp(f.active[std::size_t(e) - 2], a1, b1) : b1;
  const std::array<int, 4> cut{b0, a1, a2, b1};
  for (std::size_t s = 0; s + 1 < cut.size(); ++s) {
    if (cut[s] >= cut[s + 1]) continue;
    const int at = cut[s] - b0;
    const double* l1 = e >= 1 ? factor_pointers(f, e - 1, cut[s]).l1 + cut[s] : nullptr;
    const double* l2 = e >= 2 ? factor_pointers(f, e - 2, cut[s]).l2 + cut[s] : nullptr;
    if (fused) {
      const int m = cut[s + 1] - cut[s], parity = cut[s] % 2;
      double *w0 = w[0] + at, *w1 = w[1] + at, *w2 = w[2] + at;
      const double *s0 = in.s0 + cut[s], *s1 = in.s1 + cut[s], *t = in.t + cut[s];
      if (rows == 2)
        down_edge_rows<2>(w0, w1, w2, s0, s1, t, coef, l1, l2, stride, m, parity);
      else if (rows == 1)
        down_edge_rows<1>(w0, w1, w2, s0, s1, t, coef, l1, l2, stride, m, parity);
      else
        down_edge_rows<0>(w0, w1, w2, s0, s1, t, coef, l1, l2, stride, m, parity);
      continue;
    }
    down_rows(w[0] + at, w[1] + at, w[2] + at, y[0] + at, y[1] + at, y[2] + at, in.t_even + cut[s], in.t_odd + cut[s],
              z, l1, l2, stride, rows, cut[s + 1] - cut[s]);
  }
}

namespace {

// The row e factors at the modes [b0, b1) in their (at most two) segments, stored and limits:
// fn(offset from b0, the segment's factors indexed by mode, its first mode, its length).
template <class Fn>
void for_each_segment(const ModeFactors& f, int e, int b0, int b1, const Fn& fn) {
  const int a = std::clamp(f.active[std::size_t(e)], b0, b1);
  const std::array<int, 3> cut{b0, a, b1};
  for (std::size_t s = 0; s + 1 < cut.size(); ++s)
    if (cut[s] < cut[s + 1]) fn(cut[s] - b0, factor_pointers(f, e, cut[s]), cut[s], cut[s + 1] - cut[s]);
}

}  // namespace

void up_row_into(const ModeFactors& f, int e, int b0, int b1, const std::array<double*, 3>& o,
                 const std::array<const double*, 3>& y, std::ptrdiff_t stride, int rows) {
  for_each_segment(f, e, b0, b1, [&](int at, const FactorPointers& p, int q, int n) {
    up_rows_into(o[0] + at, o[1] + at, o[2] + at, y[0] + at, y[1] + at, y[2] + at, p.inv_d + q, p.l1 + q, p.l2 + q,
                 stride, rows, n);
  });
}

void up_row(const ModeFactors& f, int e, int b0, int b1, const std::array<double*, 3>& w, std::ptrdiff_t stride,
            int rows) {
  for_each_segment(f, e, b0, b1, [&](int at, const FactorPointers& p, int q, int n) {
    up_rows(w[0] + at, w[1] + at, w[2] + at, p.inv_d + q, p.l1 + q, p.l2 + q, stride, rows, n);
  });
}

void solve_chunk(const ModeFactors& f, int b0, int b1, int count, const SweepInput& in, const ChunkOutput& out,
                 double* buf, const Eigen::MatrixXd& sines, Eigen::MatrixXd& dot) {
  const int R = f.rows, C = f.cols, n = b1 - b0;
  const std::vector<double> zeros(std::size_t(n), 0.0);
  std::vector<double> scratch(3 * std::size_t(n));  // the edge rows' transforms, one row each
  // three right-hand sides are swept together; those from count on are zero and not written
  const auto row_of = [&](int c, int r) { return buf + (std::ptrdiff_t(c) * R + r) * n; };
  // down: buf = L⁻¹ (the input)
  for (int r = 0; r < R; ++r)
    down_row(f, r, r, b0, b1, count, in, {row_of(0, r), row_of(1, r), row_of(2, r)}, n, zeros.data(), scratch.data());
  // up: buf ← (LD)⁻ᵀ buf = M⁻¹ (the input), then into the output and the partial dots
  const Eigen::Index k = sines.cols();
  dot.resize(R, 2 * k * count);
  // With three right-hand sides written (not added) into grids, the way up writes the grid rows
  // directly (reading the two below from there), not the buffer and then a copy of it.
  const bool direct = count == 3 && !out.add && out.grid[0] && out.grid[1] && out.grid[2];
  const auto grid_row = [&](int c, int r) { return out.grid[std::size_t(c)] + std::ptrdiff_t(r) * C + b0; };
  for (int r = R - 1; r >= 0; --r) {
    const int rows = std::min(R - 1 - r, 2);
    if (direct)
      up_row_into(f, r, b0, b1, {grid_row(0, r), grid_row(1, r), grid_row(2, r)},
                  {row_of(0, r), row_of(1, r), row_of(2, r)}, C, rows);
    else
      up_row(f, r, b0, b1, {row_of(0, r), row_of(1, r), row_of(2, r)}, n, rows);
    for (int c = 0; c < count; ++c) {
      const double* w = row_of(c, r);
      double* g = out.grid[std::size_t(c)] ? grid_row(c, r) : nullptr;
      if (g && out.add)
        for (int q = 0; q < n; ++q) g[q] += w[q];
      else if (g && !direct)
        std::copy(w, w + n, g);
      const double* x = g ? g : w;
      for (Eigen::Index m = 0; m < k; ++m) {
        const std::array<double, 2> sums = parity_dot(x, sines.col(m).data() + b0, n);
        dot(r, 2 * (k * c + m)) = sums[0];
        dot(r, 2 * (k * c + m) + 1) = sums[1];
      }
    }
  }
}

namespace {
constexpr double kConverged = 1e-15;
}  // namespace

namespace {

// The banded LDLᵀ of one mode's M_q, row by row: step() gives the next row's pivot and
// multipliers, and tells whether they equal the previous row's to kConverged (from row 3 on).
struct ModeRecurrence {
  double a0, a1, a2;  // the bands of M_q: diagonal, first and second off-diagonal
  double dm1 = 0, dm2 = 0, l1m1 = 0, l2m1 = 0, l2m2 = 0;
  double d = 0, l1 = 0, l2 = 0;
  bool step(int r) {
    d = a0 - l1m1 * l1m1 * dm1 - l2m2 * l2m2 * dm2;
    l1 = (a1 - l2m1 * dm1 * l1m1) / d;
    l2 = a2 / d;
    const double change =
        std::max({std::abs(d - dm1) / d, std::abs(l1 - l1m1) / std::abs(l1), std::abs(l2 - l2m1) / l2});
    if (r >= 3 && change <= kConverged) return true;
    dm2 = dm1;
    dm1 = d;
    l1m1 = l1;
    l2m2 = l2m1;
    l2m1 = l2;
    return false;
  }
};

ModeRecurrence mode_recurrence(double a, double b, double nu) {
  const double alpha = a * nu * nu + b, beta = 2 * b * nu, gamma = b * nu * nu;
  return {6 * alpha + 2 * beta + gamma, -4 * alpha - beta, alpha};  // definite
}

}  // namespace

ModeFactors factor_modes(double a, double b, const Eigen::VectorXd& nu, int rows, int threads, int first) {
  ModeFactors f;
  const int cols = int(nu.size());
  f.rows = rows;
  f.cols = cols;
  f.lim_inv_d.assign(std::size_t(cols), 0.0);  // the modes q < first: limits zero, converged at row 0
  f.lim_l1.assign(std::size_t(cols), 0.0);
  f.lim_l2.assign(std::size_t(cols), 0.0);
  std::vector<int> converged(std::size_t(cols), 0);
  [[maybe_unused]] const int nt = threads;
  // Two passes over each mode's recurrence (it is cheap: about 40/√ν_q rows): the first finds the
  // row where it converges and its limits, the second writes the rows above into their places,
  // so that nothing is stored twice.
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int q = first; q < cols; ++q) {  // the modes are independent; each writes its own entries
    ModeRecurrence m = mode_recurrence(a, b, nu[q]);
    int r = 0;
    while (r < rows && !m.step(r)) ++r;
    // converged at r (its values are the last stored row's), or never: the last row is the limit
    converged[std::size_t(q)] = r;
    f.lim_inv_d[std::size_t(q)] = 1 / m.dm1;
    f.lim_l1[std::size_t(q)] = m.l1m1;
    f.lim_l2[std::size_t(q)] = m.l2m1;
  }
  f.active.assign(std::size_t(rows), 0);
  f.offset.assign(std::size_t(rows) + 1, 0);
  int q_max = cols;
  for (int r = 0; r < rows; ++r) {
    while (q_max > 0 && converged[std::size_t(q_max) - 1] <= r) --q_max;
    f.active[std::size_t(r)] = q_max;
    f.offset[std::size_t(r) + 1] = f.offset[std::size_t(r)] + std::size_t(q_max);
  }
  const std::size_t total = f.offset.back();
  f.inv_d.resize(total);
  f.l1.resize(total);
  f.l2.resize(total);
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int q = first; q < cols; ++q) {
    ModeRecurrence m = mode_recurrence(a, b, nu[q]);
    const int stored = converged[std::size_t(q)];
    for (int r = 0; r < rows && q < f.active[std::size_t(r)]; ++r) {
      const std::size_t at = f.offset[std::size_t(r)] + std::size_t(q);
      if (r < stored) {
        m.step(r);
        f.inv_d[at] = 1 / m.d;
        f.l1[at] = m.l1;
        f.l2[at] = m.l2;
      } else {
        f.inv_d[at] = f.lim_inv_d[std::size_t(q)];
        f.l1[at] = f.lim_l1[std::size_t(q)];
        f.l2[at] = f.lim_l2[std::size_t(q)];
      }
    }
  }
  // the modes below `first` are converged from row 0 on: no row keeps them unless a later mode
  // is still stored there (active counts modes from 0), and those read zero
  for (int r = 0; r < rows; ++r)
    for (int q = 0; q < std::min(first, f.active[std::size_t(r)]); ++q) {
      const std::size_t at = f.offset[std::size_t(r)] + std::size_t(q);
      f.inv_d[at] = f.l1[at] = f.l2[at] = 0;
    }
  return f;
}

}  // namespace coons::solvers::fast5_detail
