#include "separable_outer_products.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "row_form.h"

namespace coons::solvers {
namespace {

using detail::has_interior;
using detail::larger_magnitude;
using detail::largest_magnitude;

// The outer products are written in tiles of kOuterRows rows × kOuterCols columns, so that the
// K pieces of the v_k (K·kOuterCols doubles, 16 KB for K = 8) stay in L1 across the rows.
constexpr int kOuterRows = 64;
constexpr int kOuterCols = 256;

// x(i, j) = Σ_k a[i·K + k] v[k·C + j] for the rows i < nrows of x (row stride C) and the columns
// [j0, j1), summed over k in order (the fused path below rounds once per term instead of twice).
void outer_product_rows_plain(const double* __restrict a, const double* __restrict v, std::size_t C, int K, int nrows,
                              int j0, int j1, double* __restrict x) {
  const auto k_count = std::size_t(K);
  for (int i = 0; i < nrows; ++i) {
    const double* ai = a + std::size_t(i) * k_count;
    double* xi = x + std::size_t(i) * C;
    for (int j = j0; j < j1; ++j) {
      double sum = 0;
      for (std::size_t k = 0; k < k_count; ++k) sum += ai[k] * v[k * C + std::size_t(j)];
      xi[j] = sum;
    }
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define COONS_OUTER_PRODUCTS_FMA 1
// The same with AVX2 and fused multiply-adds (half the instructions of a multiply and an add, and
// what bounds this loop once the v_k are in L1): 32 points at a time, their sums in eight
// registers (eight independent chains of multiply-adds hide the latency of each), one store each.
__attribute__((target("avx2,fma"))) void outer_product_rows_fma(const double* __restrict a, const double* __restrict v,
                                                                std::size_t C, int K, int nrows, int j0, int j1,
                                                                double* __restrict x) {
  const auto k_count = std::size_t(K);
  for (int i = 0; i < nrows; ++i) {
    const double* ai = a + std::size_t(i) * k_count;
    double* xi = x + std::size_t(i) * C;
    int j = j0;
    for (; j + 32 <= j1; j += 32) {
      __m256d sum[8];
      for (__m256d& s : sum) s = _mm256_setzero_pd();
      for (std::size_t k = 0; k < k_count; ++k) {
        const __m256d w = _mm256_set1_pd(ai[k]);
        const double* vk = v + k * C + std::size_t(j);
        for (int q = 0; q < 8; ++q) sum[q] = _mm256_fmadd_pd(w, _mm256_loadu_pd(vk + 4 * q), sum[q]);
      }
      for (int q = 0; q < 8; ++q) _mm256_storeu_pd(xi + j + 4 * q, sum[q]);
    }
    for (; j + 4 <= j1; j += 4) {
      __m256d sum = _mm256_setzero_pd();
      for (std::size_t k = 0; k < k_count; ++k)
        sum = _mm256_fmadd_pd(_mm256_set1_pd(ai[k]), _mm256_loadu_pd(v + k * C + std::size_t(j)), sum);
      _mm256_storeu_pd(xi + j, sum);
    }
    for (; j < j1; ++j) {
      double sum = 0;
      for (std::size_t k = 0; k < k_count; ++k) sum = std::fma(ai[k], v[k * C + std::size_t(j)], sum);
      xi[j] = sum;
    }
  }
}
#endif

// The fused path where the processor has it (chosen once), else the plain one.
void outer_product_rows(const double* a, const double* v, std::size_t C, int K, int nrows, int j0, int j1, double* x) {
#if defined(COONS_OUTER_PRODUCTS_FMA)
  static const bool fused = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (fused) {
    outer_product_rows_fma(a, v, C, K, nrows, j0, j1, x);
    return;
  }
#endif
  outer_product_rows_plain(a, v, C, K, nrows, j0, j1, x);
}

// Y = F⁻¹ Y in place for Y of k rows × count columns (row-major): L, then D, then Lᵀ, each step
// across the count columns at once (independent recurrences: vectorised, no latency chain).
void solve_columns(const BandedLdlt& f, double* __restrict y, std::size_t count, int k) {
  const auto row = [&](int r) { return y + std::size_t(r) * count; };
  for (int r = 1; r < k; ++r) {
    double* __restrict yr = row(r);
    const double* __restrict y1 = row(r - 1);
    const double a = f.l1[r - 1];
    if (r >= 2) {
      const double* __restrict y2 = row(r - 2);
      const double c = f.l2[r - 2];
      for (std::size_t t = 0; t < count; ++t) yr[t] -= a * y1[t] + c * y2[t];
    } else {
      for (std::size_t t = 0; t < count; ++t) yr[t] -= a * y1[t];
    }
  }
  for (int r = k - 1; r >= 0; --r) {
    double* __restrict yr = row(r);
    const double d = f.d[r];
    if (r + 2 < k) {
      const double* __restrict y1 = row(r + 1);
      const double* __restrict y2 = row(r + 2);
      const double a = f.l1[r], c = f.l2[r];
      for (std::size_t t = 0; t < count; ++t) yr[t] = yr[t] / d - a * y1[t] - c * y2[t];
    } else if (r + 1 < k) {
      const double* __restrict y1 = row(r + 1);
      const double a = f.l1[r];
      for (std::size_t t = 0; t < count; ++t) yr[t] = yr[t] / d - a * y1[t];
    } else {
      for (std::size_t t = 0; t < count; ++t) yr[t] /= d;
    }
  }
}

}  // namespace

std::optional<detail::OuterForm> detail::outer_form(const double* b, int rows, int cols, int threads) {
  if (cols < 5) return std::nullopt;
  const auto R = std::size_t(rows), C = std::size_t(cols);
  std::vector<unsigned char> full(R, 0);
  // Rows with interior values; once more than kMaxFullRows are found the answer is the sweeps,
  // and the rest of B is not read (a general right-hand side stops within its first rows).
  std::atomic<int> found{0};
  [[maybe_unused]] const int nt = std::max(1, threads);
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int i = 0; i < rows; ++i) {
    if (found.load(std::memory_order_relaxed) > kMaxFullRows) continue;
    if (has_interior(b + std::size_t(i) * C + 1, cols - 2)) {
      full[std::size_t(i)] = 1;
      found.fetch_add(1, std::memory_order_relaxed);
    }
  }
  if (found.load() > kMaxFullRows) return std::nullopt;
  OuterForm form;
  for (int i = 0; i < rows; ++i) {
    const double* row = b + std::size_t(i) * C;
    // a full row in full; any other is zero but in its first and last two columns
    const bool whole = full[std::size_t(i)] != 0;
    if (whole) form.full_rows.push_back(i);
    form.largest = larger_magnitude(
        form.largest, whole ? largest_magnitude(row, C)
                            : larger_magnitude(largest_magnitude(row, 2), largest_magnitude(row + C - 2, 2)));
  }
  return form;
}

bool detail::solve_outer_products(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const double* b,
                                  double* x, int threads) {
  const std::optional<OuterForm> form = outer_form(b, rows, cols, threads);
  if (form) solve_outer_products(fi, fj, rows, cols, *form, b, x, threads);
  return form.has_value();
}

void detail::solve_outer_products(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const OuterForm& form,
                                  const double* b, double* x, int threads) {
  const auto R = std::size_t(rows), C = std::size_t(cols);
  const std::vector<int>& full_rows = form.full_rows;
  std::vector<unsigned char> full(R, 0);
  for (const int i : full_rows) full[std::size_t(i)] = 1;
  [[maybe_unused]] const int nt = std::max(1, threads);
  const int K = 4 + int(full_rows.size());
  const auto k_count = std::size_t(K);
  const std::array<int, 4> edges{0, 1, cols - 2, cols - 1};
  // a (rows × K): row i holds u_k[i] for the K terms, the right-hand sides of P⁻¹ side by side
  std::vector<double> a(R * k_count, 0.0);
  for (std::size_t i = 0; i < R; ++i)
    if (full[i] == 0)
      for (std::size_t e = 0; e < 4; ++e) a[i * k_count + e] = b[i * C + std::size_t(edges[e])];
  for (std::size_t f = 0; f < full_rows.size(); ++f) a[std::size_t(full_rows[f]) * k_count + 4 + f] = 1;
  solve_columns(fi, a.data(), k_count, rows);
  // w (cols × K) likewise for Q⁻¹, then v (K × cols): each v_k contiguous for the outer products
  std::vector<double> w(C * k_count, 0.0), v(k_count * C);
  for (std::size_t e = 0; e < 4; ++e) w[std::size_t(edges[e]) * k_count + e] = 1;
  for (std::size_t f = 0; f < full_rows.size(); ++f)
    for (std::size_t j = 0; j < C; ++j) w[j * k_count + 4 + f] = b[std::size_t(full_rows[f]) * C + j];
  solve_columns(fj, w.data(), k_count, cols);
  for (std::size_t j = 0; j < C; ++j)
    for (std::size_t k = 0; k < k_count; ++k) v[k * C + j] = w[j * k_count + k];
  const int blocks = (rows + kOuterRows - 1) / kOuterRows;
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nt) if (nt > 1) schedule(static)
#endif
  for (int block = 0; block < blocks; ++block) {
    const int i0 = block * kOuterRows, i1 = std::min(rows, i0 + kOuterRows);
    for (int j0 = 0; j0 < cols; j0 += kOuterCols)
      outer_product_rows(a.data() + std::size_t(i0) * std::size_t(K), v.data(), C, K, i1 - i0, j0,
                         std::min(cols, j0 + kOuterCols), x + std::size_t(i0) * C);
  }
}

}  // namespace coons::solvers
