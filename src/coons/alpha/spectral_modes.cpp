#include "spectral_modes.h"

#include <algorithm>
#include <cstddef>

#include "coons/net/bernstein.h"
#include "solvers/vector_clones.h"

namespace coons::detail {

COONS_VECTOR_CLONES void mode_row(const double* __restrict u, const double* __restrict V, int cols,
                                  const double* __restrict symbol, double* __restrict quad, double* __restrict lin) {
  auto column = [&](int c) { return V + std::ptrdiff_t(c) * cols; };
  const double* __restrict l0 = column(FC::kBlend);
  const double* __restrict l1 = column(FC::kBlend + 1);
  const double u0 = u[FC::kBlend], u1 = u[FC::kBlend + 1];
  for (int q = 0; q < cols; ++q) {
    double rr = 0, cr = 0;
    for (int k = 0; k < 3; ++k) {
      const double r = u[FC::of(FC::kRSide, 0, k)] * l0[q] + u[FC::of(FC::kRSide, 1, k)] * l1[q] +
                       u0 * column(FC::of(FC::kRSide, 0, k))[q] + u1 * column(FC::of(FC::kRSide, 1, k))[q];
      const double c = u[FC::of(FC::kCSide, 0, k)] * l0[q] + u[FC::of(FC::kCSide, 1, k)] * l1[q] +
                       u0 * column(FC::of(FC::kCSide, 0, k))[q] + u1 * column(FC::of(FC::kCSide, 1, k))[q];
      rr += r * r;
      cr += c * r;
    }
    quad[q] = symbol[q] * rr;
    lin[q] = 2 * cr;
  }
}

COONS_VECTOR_CLONES ModeSums mode_sums(double alpha, const double* __restrict xi, int rows,
                                       const double* __restrict eta, int cols, const double* __restrict quad,
                                       const double* __restrict lin) {
  const double gamma = alpha + 0.25;
  ModeSums total;
  for (int p = 0; p < rows; ++p) {
    double f = 0, df = 0, d2f = 0, df_abs = 0, smallest = HUGE_VAL;
    const double xp = xi[p];
    const double* __restrict qr = quad + std::ptrdiff_t(p) * cols;
    const double* __restrict lr = lin + std::ptrdiff_t(p) * cols;
#pragma omp simd reduction(+ : f, df, d2f, df_abs) reduction(min : smallest)
    for (int q = 0; q < cols; ++q) {
      // λ = λ_C + γ·d with λ_C = ξη (the Coons eigenvalue) and d = 2(ξ + η − 2ξη), in ξ = 1 − x,
      // η = 1 − y: no cancellation for the low modes. δ̂ = u·R̂ with u = γ/λ, u' = λ_C/λ².
      const double lc = xp * eta[q], d = 2 * (xp + eta[q] - 2 * lc);
      const double lambda = lc + gamma * d, il = 1 / lambda;
      const double u = gamma * il, du = lc * il * il, d2u = -2 * du * d * il;
      const double w = 2 * qr[q] * u + lr[q];  // ∂f/∂u of the mode
      f += u * (qr[q] * u + lr[q]);
      df += w * du;
      df_abs += (std::abs(2 * qr[q] * u) + std::abs(lr[q])) * std::abs(du);
      d2f += 2 * qr[q] * du * du + w * d2u;
      smallest = std::min(smallest, std::abs(lambda));
    }
    total.f += f;
    total.df += df;
    total.d2f += d2f;
    total.df_abs += df_abs;
    total.smallest = std::min(total.smallest, smallest);
  }
  return total;
}

Eigen::MatrixXd basis_at_samples(int degree, int k) {
  Eigen::MatrixXd B(k, degree + 1);
  for (int s = 0; s < k; ++s) B.row(s) = bernstein_basis(degree, double(s) / (k - 1)).transpose();
  return B;
}

}  // namespace coons::detail
