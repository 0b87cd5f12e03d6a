#include "row_kernels.h"

#include "vector_clones.h"

namespace coons::solvers::detail {

// x = h − l∘p (p = nullptr: x = h).
COONS_VECTOR_CLONES void eliminate_dense(const double* __restrict h, const double* __restrict l,
                                         const double* __restrict p, double* __restrict x, int n) {
  if (!p) {
    for (int q = 0; q < n; ++q) x[q] = h[q];
    return;
  }
  for (int q = 0; q < n; ++q) x[q] = h[q] - l[q] * p[q];
}

// x = a·s + b·t − l∘p (p = nullptr: without the last term).
COONS_VECTOR_CLONES void eliminate_sparse(double a, double b, const double* __restrict s, const double* __restrict t,
                                          const double* __restrict l, const double* __restrict p, double* __restrict x,
                                          int n) {
  if (!p) {
    for (int q = 0; q < n; ++q) x[q] = a * s[q] + b * t[q];
    return;
  }
  for (int q = 0; q < n; ++q) x[q] = a * s[q] + b * t[q] - l[q] * p[q];
}

// x_c = a_c·s + b_c·t − l∘p_c for c = 0, 1, 2 (every pointer a parameter, so that restrict
// holds for the vectoriser).
namespace {
COONS_VECTOR_CLONES void sparse3_first(double a0, double a1, double a2, double b0, double b1, double b2,
                                       const double* __restrict s, const double* __restrict t, double* __restrict x0,
                                       double* __restrict x1, double* __restrict x2, int n) {
  for (int q = 0; q < n; ++q) {
    x0[q] = a0 * s[q] + b0 * t[q];
    x1[q] = a1 * s[q] + b1 * t[q];
    x2[q] = a2 * s[q] + b2 * t[q];
  }
}
COONS_VECTOR_CLONES void sparse3(double a0, double a1, double a2, double b0, double b1, double b2,
                                 const double* __restrict s, const double* __restrict t, const double* __restrict l,
                                 const double* __restrict p0, const double* __restrict p1, const double* __restrict p2,
                                 double* __restrict x0, double* __restrict x1, double* __restrict x2, int n) {
  for (int q = 0; q < n; ++q) {
    x0[q] = a0 * s[q] + b0 * t[q] - l[q] * p0[q];
    x1[q] = a1 * s[q] + b1 * t[q] - l[q] * p1[q];
    x2[q] = a2 * s[q] + b2 * t[q] - l[q] * p2[q];
  }
}
COONS_VECTOR_CLONES void back3(double* __restrict y0, double* __restrict y1, double* __restrict y2,
                               const double* __restrict o, const double* __restrict r, const double* __restrict n0,
                               const double* __restrict n1, const double* __restrict n2, int n) {
  for (int q = 0; q < n; ++q) {
    y0[q] = (y0[q] - o[q] * n0[q]) * r[q];
    y1[q] = (y1[q] - o[q] * n1[q]) * r[q];
    y2[q] = (y2[q] - o[q] * n2[q]) * r[q];
  }
}
}  // namespace

void eliminate_sparse3(const double* a, const double* b, const double* __restrict s, const double* __restrict t,
                       const double* __restrict l, const double* const* p, double* const* x, int n) {
  if (!p)
    sparse3_first(a[0], a[1], a[2], b[0], b[1], b[2], s, t, x[0], x[1], x[2], n);
  else
    sparse3(a[0], a[1], a[2], b[0], b[1], b[2], s, t, l, p[0], p[1], p[2], x[0], x[1], x[2], n);
}

// l = o∘r.
COONS_VECTOR_CLONES void multiply(const double* __restrict o, const double* __restrict r, double* __restrict l, int n) {
  for (int q = 0; q < n; ++q) l[q] = o[q] * r[q];
}

// y_c = (y_c − o∘next_c)∘r for c = 0, 1, 2.
void back_substitute_in_place3(double* const* y, const double* __restrict o, const double* __restrict r,
                               const double* const* next, int n) {
  back3(y[0], y[1], y[2], o, r, next[0], next[1], next[2], n);
}

// x = Σ_k a_k v_k (K ≥ 1 terms).
COONS_VECTOR_CLONES void rank_row(const double* a, const double* const* v, int K, double* __restrict x, int n) {
  int k = 0;
  if (K % 2) {
    const double a0 = a[0];
    const double* __restrict v0 = v[0];
    for (int j = 0; j < n; ++j) x[j] = a0 * v0[j];
    k = 1;
  } else {
    const double a0 = a[0], a1 = a[1];
    const double* __restrict v0 = v[0];
    const double* __restrict v1 = v[1];
    for (int j = 0; j < n; ++j) x[j] = a0 * v0[j] + a1 * v1[j];
    k = 2;
  }
  for (; k < K; k += 2) {
    const double a0 = a[k], a1 = a[k + 1];
    const double* __restrict v0 = v[k];
    const double* __restrict v1 = v[k + 1];
    for (int j = 0; j < n; ++j) x[j] += a0 * v0[j] + a1 * v1[j];
  }
}

// x = y − l·p (scalar l).
COONS_VECTOR_CLONES void axpy_rows(const double* __restrict y, double l, const double* __restrict p,
                                   double* __restrict x, int n) {
  for (int j = 0; j < n; ++j) x[j] = y[j] - l * p[j];
}

// x += a·v.
COONS_VECTOR_CLONES void add_scaled(double a, const double* __restrict v, double* __restrict x, int n) {
  for (int j = 0; j < n; ++j) x[j] += a * v[j];
}

double dot(const double* a, const double* b, int n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    s0 += a[j] * b[j];
    s1 += a[j + 1] * b[j + 1];
    s2 += a[j + 2] * b[j + 2];
    s3 += a[j + 3] * b[j + 3];
  }
  for (; j < n; ++j) s0 += a[j] * b[j];
  return (s0 + s1) + (s2 + s3);
}

}  // namespace coons::solvers::detail
