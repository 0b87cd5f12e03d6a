// The fast solver's narrowed grid: when cols+1 is a slow FFT length (a prime factor above 13, or
// odd on a wide grid: FFTW's real transform is then 2.5–10× slower than at a length 2^k), the
// transform covers only the first L columns (L + 1 a fast length, the nearest below cols + 1) and
// the k = cols − L columns on the right, the interface, are eliminated by their Schur complement
// (capacitance matrix method). The sine transform along i diagonalises every block: for the mode
// p along i the grid is one tridiagonal system along j, tridiag(c1_p, a_p, c1_p) with
// a_p = c + 2e_i·x_p, c1_p = e_j + 2d·x_p, x_p = cos(pπ/(rows+1)), and the interface unknowns of
// that mode solve the k × k system
//   S_p = tridiag(c1_p, a_p, c1_p) − c1_p² g_p e₁e₁ᵀ,   g_p = (T_p⁻¹)_{L−1,L−1} = 2/(L+1) Σ_q S(L−1,q)²/λ_pq,
// T_p the fast region's tridiagonal system and λ_pq = a_p + 2c1_p·cos(qπ/(L+1)) its eigenvalues.
// A solve is then: the fast region with the interface at zero (its column L−1 is V), the
// interface x_I from S_p x̃_I = b̃_I − c1_p Ṽ e₁ (all in the sine basis along i), and the fast
// region again with the interface moved to its right-hand side (column L−1 only).
// Narrowing is declined (factor() is false, and the fast solver takes its exact fallback) unless
// the fast region's operator is definite (every λ of one sign: then S_p is definite too) and its
// condition max|λ|/min|λ| is at most kMaxNarrowingLoss times the real grid's. Where the symbol
// changes sign, a mode of the smaller grid can fall next to its zero set while none of the real
// grid does (the widened grid this replaced lost up to 6 digits there, 29 × 16, α = −0.424).
// Sizes: k pivots per mode along i (k ≤ kMaxInterface); 2k + 1 transforms of length rows per column.
// Based on: B. L. Buzbee, F. W. Dorr, J. A. George & G. H. Golub, The direct solution of the
// discrete Poisson equation on irregular regions, SIAM J. Numer. Anal. 8 (1971).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "grid_stencil.h"
#include "sine_transform.h"

namespace coons::solvers::detail {

//! The largest error growth of the fast region over the real grid that factor() accepts.
constexpr double kMaxNarrowingLoss = 10;
//! The widest interface the fast solver makes (columns cut off the right of the grid).
constexpr int kMaxInterface = 32;
//! The smallest pivot of a Schur complement S_p, relative to |a_p| + 2|c1_p|, that factor() accepts.
constexpr double kInterfacePivot = 1e-8;

//! The largest prime factor of n ≥ 1 (1 for n = 1).
int largest_prime_factor(int n);

//! The number k of interface columns for a grid of `cols` columns: 0 when cols + 1 is a fast
//! transform length (or the grid is narrow), else the smallest k ≤ kMaxInterface for which
//! cols − k + 1 is one (0 if none is).
int interface_columns(int cols);

class Capacitance {
 public:
  //! Plans the transforms along i of `rows` rows with the FFTW planner flag `planning`
  //! (fft_planning()); called once per grid size, before factor().
  void prepare(int rows, unsigned planning);
  //! The blocks S_p (factored) of the grid s (s.cols columns), whose first L = y.size() columns are the
  //! fast region with modes y_q = cos(qπ/(L+1)); false when a block or an eigenvalue is
  //! singular, or when narrowing would lose accuracy (see above).
  bool factor(const GridStencil& s, const std::vector<double>& y);
  //! The interface values x_I (rows × k, row-major) from V (rows: column L−1 of the fast region's
  //! solution with a zero interface) and b_I (rows × k, row-major: the right-hand side there).
  void interface_values(const std::vector<double>& V, const std::vector<double>& b_interface,
                        std::vector<double>& x_interface);
  //! δ(i) = e_j·x_I(i, 0) + d·(x_I(i−1, 0) + x_I(i+1, 0)): what the interface contributes to the
  //! equation of the point (i, L−1); the fast region's right-hand side there is b − δ.
  void coupling(const std::vector<double>& x_interface, std::vector<double>& delta) const;
  [[nodiscard]] int columns() const { return k_; }

 private:
  int R_ = 0, L_ = 0, k_ = 0;
  double edge_j_ = 0, diag_ = 0;
  SineTransform sine_rows_;
  std::vector<double> c1_;      // c1_p per mode p
  std::vector<double> pivots_;  // the pivots of S_p's LDLᵀ, k per mode p
};

}  // namespace coons::solvers::detail
