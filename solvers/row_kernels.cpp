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

// l = o∘r.
COONS_VECTOR_CLONES void multiply(const double* __restrict o, const double* __restrict r, double* __restrict l, int n) {
  for (int q = 0; q < n; ++q) l[q] = o[q] * r[q];
}

// xh = (y − o∘xh)∘r.
COONS_VECTOR_CLONES void back_substitute(const double* __restrict y, const double* __restrict o,
                                         const double* __restrict r, double* __restrict xh, int n) {
  for (int q = 0; q < n; ++q) xh[q] = (y[q] - o[q] * xh[q]) * r[q];
}

// y = (y − o∘next)∘r.
COONS_VECTOR_CLONES void back_substitute_in_place(double* __restrict y, const double* __restrict o,
                                                  const double* __restrict r, const double* __restrict next, int n) {
  for (int q = 0; q < n; ++q) y[q] = (y[q] - o[q] * next[q]) * r[q];
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
