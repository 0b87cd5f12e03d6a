// Internal to the sine-basis objective (spectral_objective.h): the per-mode pieces, the loops
// that run once per mode (vectorised, with an AVX2 clone) and the layout of the factors they read.
// Sizes: rows × cols modes, FactorColumns::kCount columns per factor matrix.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) (the eigenvalues of the
// mask family).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace coons::detail {

// The sine-transformed factors of the Coons net along one direction (i: rows_, j: cols_ interior
// points) are the columns of one matrix, in three named blocks:
//   kRSide  (6)  the R side: −K_1 applied to the two sides along this direction, x y z of each;
//   kCSide  (6)  the c side: Σ w·K_order applied to the same two sides;
//   kBlend  (2)  the linear blends (1 − s, s) at the interior points.
// (The sides are bottom, top along i and left′, right′ along j; see the constructor.)
struct FactorColumns {
  static constexpr int kRSide = 0, kCSide = 6, kBlend = 12, kCount = 14;
  //! The column of coordinate k (0..2) of side `side` (0, 1) in the block starting at `block`.
  static constexpr int of(int block, int side, int k) { return block + 3 * side + k; }
};
using FC = FactorColumns;

//! One row p of modes: per coordinate R̂(p, q) = r_b(p)·L̂0(q) + r_t(p)·L̂1(q) + l̂0(p)·r_l(q) + l̂1(p)·r_r(q),
// ĉ likewise; quad = symbol·Σ R̂², lin = 2·Σ ĉ·R̂. `u` is row p of the i-direction factors, V the
// j-direction factors (#cols by FC::kCount, column-major).
void mode_row(const double* __restrict u, const double* __restrict V, int cols, const double* __restrict symbol,
              double* __restrict quad, double* __restrict lin);

//! Σ over the modes of f, f', f'' and min |λ| (see evaluate); one pass over two arrays.
struct ModeSums {
  double f = 0, df = 0, d2f = 0, df_abs = 0, smallest = HUGE_VAL;
};
ModeSums mode_sums(double alpha, const double* __restrict xi, int rows, const double* __restrict eta, int cols,
                   const double* __restrict quad, const double* __restrict lin);

//! The Bernstein basis of a degree at the k samples s/(k − 1) of sample_surface (#k by degree+1).
Eigen::MatrixXd basis_at_samples(int degree, int k);

}  // namespace coons::detail
