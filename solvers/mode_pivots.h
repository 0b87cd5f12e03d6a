// The tridiagonal systems of every sine mode of the fast solver, factored as one batch: for the
// mode q along j (y_q = cos(qπ/(L+1))) the stencil acts along i as T_q = tridiag(o_q, D_q),
// o_q = e_i + 2d·y_q, D_q = c + 2e_j·y_q, and elimination without pivoting has the pivots
// m_0 = D_q, m_i = D_q − o_q²/m_{i−1}, computed row by row and vectorised across q.
// The recursion of a mode reaches its fixed point in floating point after a few rows for most
// modes (bit for bit: once m_i = m_{i−1}, every later pivot is the same number), so only 3–6 %
// of the table is computed and kept (at 1023², α ∈ [−0.2, 1/4]): row i stores the modes
// [0, lo_i) ∪ [hi_i, L), where [lo_i, hi_i) is the run of converged modes around the one that
// converges first, and the others take their limit. Nothing of the size of the grid is made.
// Sizes: L per row of the compressed table (a few % of rows × L in all), three rows of L.
// Based on: L. H. Thomas (1949), the tridiagonal algorithm; R. W. Hockney, J. ACM 12 (1965).
#pragma once

#include <cstddef>
#include <vector>

#include "grid_stencil.h"
#include "sine_transform.h"

namespace coons::solvers::detail {

class ModePivots {
 public:
  //! Factors T_q for the modes with y_q = y[q] (L = y.size()) on s.rows rows; false when a pivot
  //! is (near) zero, or changes sign and is small enough for elimination to be unsafe.
  bool factor(const GridStencil& s, const std::vector<double>& y);
  //! Makes pivots() the row r_to of inverse pivots and multipliers() = o∘r_to, updating only
  //! the modes stored in row `from` or `to` (from = −1: the whole row).
  void load(int from, int to);
  //! The same restricted to the modes [q0, q1): threads that own disjoint mode ranges can share
  //! pivots() and multipliers().
  void load(int from, int to, int q0, int q1);
  //! o_q, the off-diagonal of every mode (L values).
  [[nodiscard]] const double* off() const { return off_.data(); }
  [[nodiscard]] const double* pivots() const { return pivots_.data(); }
  [[nodiscard]] const double* multipliers() const { return multipliers_.data(); }

 private:
  int R_ = 0, L_ = 0;
  AlignedBuffer off_, multipliers_, pivots_;
  std::vector<int> pivot_lo_, pivot_hi_;
  std::vector<std::size_t> pivot_offset_;
  std::vector<double> pivot_values_, pivot_limit_;
};

}  // namespace coons::solvers::detail
