// The loops of the fast solver's mode-parallel tridiagonal sweeps and rank-K products, each on
// distinct arrays of n doubles (restrict) so that it vectorises; the element-wise ones get an
// AVX2 clone (vector_clones.h).
#pragma once

namespace coons::solvers::detail {

//! x = h − l∘p (p = nullptr: x = h).
void eliminate_dense(const double* __restrict h, const double* __restrict l, const double* __restrict p,
                     double* __restrict x, int n);

//! x = a·s + b·t − l∘p (p = nullptr: without the last term).
void eliminate_sparse(double a, double b, const double* __restrict s, const double* __restrict t,
                      const double* __restrict l, const double* __restrict p, double* __restrict x, int n);

//! The same for three right-hand sides at once (x_c = a_c·s + b_c·t − l∘p_c, p = nullptr: without
//! the last term), reading s, t and l once.
void eliminate_sparse3(const double* a, const double* b, const double* __restrict s, const double* __restrict t,
                       const double* __restrict l, const double* const* p, double* const* x, int n);

//! l = o∘r.
void multiply(const double* __restrict o, const double* __restrict r, double* __restrict l, int n);

//! The back substitution of three right-hand sides in place of their eliminated rows:
//! y_c = (y_c − o∘next_c)∘r, c = 0, 1, 2.
void back_substitute_in_place3(double* const* y, const double* __restrict o, const double* __restrict r,
                               const double* const* next, int n);

//! x = Σ_k a_k v_k (K ≥ 1 terms).
void rank_row(const double* a, const double* const* v, int K, double* __restrict x, int n);

//! x = y − l·p (scalar l).
void axpy_rows(const double* __restrict y, double l, const double* __restrict p, double* __restrict x, int n);

//! x += a·v.
void add_scaled(double a, const double* __restrict v, double* __restrict x, int n);

//! Σ a_j b_j, in four partial sums.
double dot(const double* a, const double* b, int n);

}  // namespace coons::solvers::detail
