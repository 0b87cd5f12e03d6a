// The right-hand sides of the fast structured solver kept row by row: a column of x, y or z
// (rows × cols, row-major) whose row has a zero interior (columns 1..cols−2) is stored as its two
// end values, any other row in full. The right-hand side of a mask system has two full rows (next
// to the frame) and end values elsewhere, so only two rows need a sine transform.
// Sizes: 2·rows end values + cols per full row.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace coons::solvers::detail {

struct RowForm {
  int width = 0;                    // length of the stored rows: cols, or the transform length
  std::vector<double> first, last;  // end values of the sparse rows (zero at dense rows)
  std::vector<int> dense_rows;      // the rows stored in full, ascending
  std::vector<int> slot;            // per row: −1, or its index in dense_rows
  std::vector<double> values;       // the full rows, width each (physical or sine-transformed)
};

//! True when a value other than ±0 (NaN included) sits in row[1..C−2].
bool has_interior(const double* row, int C);

//! The row form of b (rows × cols, row-major; row i starts at b + i·stride, stride ≥ cols, so
//! that the first cols columns of a wider grid can be split).
RowForm split_rows(const double* b, int R, int C, int stride);
inline RowForm split_rows(const double* b, int R, int C) { return split_rows(b, R, C, C); }

//! The form of a grid cut by rows into pieces (the forms of consecutive row ranges, top first, of
//! one width) as one form: the form split_rows gives for the whole grid.
RowForm join_rows(const std::vector<RowForm>& pieces);

//! The larger of two magnitudes from largest_magnitude; NaN when either is NaN (std::max keeps
//! its first operand when the second is a NaN).
inline double larger_magnitude(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) ? a : b;
  return std::max(a, b);
}

//! max |v| over v[0..n); NaN when one of them is a NaN or an infinity.
double largest_magnitude(const double* v, std::size_t n);
//! The same over the values of a form that has not been transformed (its ends and full rows:
//! every value of the rows it was split from).
double largest_magnitude(const RowForm& f);

//! Σ_r w_r · forms[r] (same rows and width). A sparse row expands as first·e0 + last·e1, where
//! e0, e1 are the unit vectors (physical forms) or their sine transforms (transformed forms).
RowForm combine(const std::vector<const RowForm*>& forms, const std::vector<double>& w, int R,
                const std::vector<double>& e0, const std::vector<double>& e1);

//! f(p, r0, r1) for each band p = 0..bands−1 of the rows [r0, r1) that split `rows` evenly, one
//! band per thread (OpenMP) when bands > 1: the structured solvers' parallel reads of B (fast's
//! split_rows, dst's scaling and ring scan).
template <class F>
void for_each_row_band(int rows, int bands, F&& f) {
  auto run = [&](int p) { f(p, int(std::int64_t(rows) * p / bands), int(std::int64_t(rows) * (p + 1) / bands)); };
  if (bands == 1) {
    run(0);
    return;
  }
#if defined(_OPENMP)
#pragma omp parallel for num_threads(bands) schedule(static, 1)
#endif
  for (int p = 0; p < bands; ++p) run(p);
}

}  // namespace coons::solvers::detail
