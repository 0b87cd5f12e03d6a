// The fast solver's widened grid: when cols+1 has a prime factor above 13 (FFTW is then several
// times slower), the grid gets a few extra columns so that the transform length L is fast, and
// the solution must vanish on them. Sources U on the extra columns enforce it (capacitance matrix
// method): G U = −V, V the response there to B, G = Eᵀ A'⁻¹ E. The sine transform along i
// block-diagonalises G: G_p(m, m') = 2/(L+1) Σ_q S(C+m, q) S(C+m', q) / λ'_pq.
// Widening is declined (factor() is false, and the fast solver takes its exact fallback) unless
// the widened operator is definite (every λ' of one sign: then G_p is definite too, and the sums
// do not cancel) and its condition max|λ'|/min|λ'| is at most kMaxWideningLoss times the real
// grid's. Where the symbol changes sign, a mode of the widened grid can fall next to its zero
// set while none of the real grid does, and the capacitance solve then loses digits that the
// transform of the real length does not (up to 6 at 29 × 16, α = −0.424).
// Sizes: rows blocks of #extra × #extra (at most 4 × 4).
// Based on: B. L. Buzbee, F. W. Dorr, J. A. George & G. H. Golub, The direct solution of the
// discrete Poisson equation on irregular regions, SIAM J. Numer. Anal. 8 (1971).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "grid_stencil.h"
#include "sine_transform.h"

namespace coons::solvers::detail {

//! The largest error growth of the widened grid over the real one that factor() accepts.
constexpr double kMaxWideningLoss = 10;

class Capacitance {
 public:
  //! Plans the transforms along i of `rows` rows with the FFTW planner flag `planning`
  //! (fft_planning()); called once per grid size, before factor().
  void prepare(int rows, unsigned planning);
  //! The blocks G_p⁻¹ for the modes y_q = y[q] (L = y.size()) and the extra columns' sine
  //! vectors sine_extra[m] = S·e_{C+m} (C = L − #extra, the real grid); false when a block or an
  //! eigenvalue is singular, or when widening would lose accuracy (see above).
  bool factor(const GridStencil& s, const std::vector<double>& y, const std::vector<std::vector<double>>& sine_extra);
  //! U = −(2/(R+1)) S_R [G_p⁻¹ (S_R V)_p], both rows × #extra, row-major.
  void sources(const std::vector<double>& V, std::vector<double>& U);

 private:
  int R_ = 0, L_ = 0, extra_ = 0;
  SineTransform sine_rows_;
  std::vector<Eigen::MatrixXd> inverse_;  // G_p⁻¹, extra × extra each
};

}  // namespace coons::solvers::detail
