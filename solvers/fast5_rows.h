// fast5, the right-hand side row by row: a row of a column of B (rows × cols, row-major) that is
// zero off its columns 0, 1, cols−2 and cols−1 (every row of a mask system with two data rings
// but the four next to the frame) is kept as those four values, and its sine transform is the
// combination of the four columns' sine vectors, formed where a sweep reads it; any other row is
// kept in full and transformed once. So the sweeps read B's transform without a grid-sized copy
// of it, and the one scan that splits B also gives its largest magnitude and its norm.
// Sizes: 4·rows end values + cols per full row (four rows for mask data).
#pragma once

#include <array>
#include <vector>

namespace coons::solvers::fast5_detail {

struct EdgeRows {
  int rows = 0, cols = 0;
  std::vector<std::array<double, 4>> ends;  //!< per row: b[0], b[1], b[cols−2], b[cols−1]; zeros at full rows
  std::vector<int> slot;                    //!< per row: −1, or its index among the full rows
  std::vector<double> values;               //!< the full rows, cols each (transformed by the solver)
  double largest = 0;                       //!< max |b|; NaN when B holds a NaN or an infinity
  double norm = 0;                          //!< ‖b‖₂ (the squares summed row by row, in order)
  bool too_many = false;  //!< more full rows than the split was allowed to keep: none kept (no slots, no values)

  [[nodiscard]] int full_rows() const { return cols > 0 ? int(values.size() / std::size_t(cols)) : 0; }
};

//! The row form of b (rows × cols, row-major, cols ≥ 6), on up to `threads` threads (bands of rows;
//! the same bits on any count). With more than max_full full rows it keeps none of them
//! (too_many; largest and norm are still those of b), so that a B its user will not read in this
//! form is not copied.
EdgeRows split_edge_rows(const double* b, int rows, int cols, int threads, int max_full);

//! The sine transform of an edge row at the modes [q0, q0 + n): with s0, s1 the orthonormal sine
//! vectors of the columns 0 and 1 (those of cols−1 and cols−2 are the same times (−1)^q),
//! (e0 + e3)·s0 + (e1 + e2)·s1 at even q, (e0 − e3)·s0 + (e1 − e2)·s1 at odd q.
void edge_row_transform(const std::array<double, 4>& e, const double* s0, const double* s1, int q0, int n, double* out);

//! The input of row r at the modes [q0, q0 + n): the stored (transformed) full row, or the edge
//! row's transform written into scratch (n doubles).
const double* edge_row(const EdgeRows& f, int r, const double* s0, const double* s1, int q0, int n, double* scratch);

}  // namespace coons::solvers::fast5_detail
