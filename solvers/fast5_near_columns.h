// fast5, the grid near its first and last columns, for the boundary check: A x − b vanishes off the
// columns 0 and cols−1 whatever the capacitance unknowns are, so fast5 checks the residual there
// (and on the columns 2 and cols−3, for the rounding of the rest). These functions keep what that
// check reads: X's columns 0–4 and cols−5 – cols−1, copied by the inverse row transform while each
// row is still in the cache, and B's columns from its row forms (fast5_rows.h) where it has them.
// (Read straight down a column of a row-major grid, every entry is in a page of its own: 0.3–0.5 ms
// at N = 1023, against about 0.05 ms for the arithmetic.)
// Sizes: rows × (10 + #columns checked) per right-hand side.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "fast5_rows.h"

namespace coons::solvers::fast5_detail {

struct NearColumns {
  int rows = 0, cols = 0;
  std::vector<int> x_cols;              //!< the columns of X kept, ascending
  std::array<Eigen::MatrixXd, 3> b, x;  //!< per right-hand side: rows × #checked, rows × #x_cols
  //! where X's column j is in x (it must be there)
  [[nodiscard]] int index(int j) const {
    return int(std::lower_bound(x_cols.begin(), x_cols.end(), j) - x_cols.begin());
  }
  //! Row r of X's column c (rows × cols row-major, `row` its first entry) into x.
  void keep(int c, int r, const double* row) {
    Eigen::MatrixXd& xc = x[std::size_t(c)];
    for (Eigen::Index k = 0; k < xc.cols(); ++k) xc(r, k) = row[x_cols[std::size_t(k)]];
  }
};

//! near for a rows × cols grid: x_cols, and x sized for `count` right-hand sides.
void prepare_near_columns(int rows, int cols, int count, NearColumns& near);

//! near.b: the columns `checked` of B (rows × cols row-major per column of B), from the row forms
//! edges[c] (a row that is not full is zero but on its four end values; nullptr: none) and from
//! B itself at the full rows.
void gather_b_columns(const Eigen::MatrixX3d& B, const std::array<EdgeRows, 3>* edges, int count,
                      const std::vector<int>& checked, NearColumns& near);

//! (b − A x) on column j = checked[k] of right-hand side c (#rows), A the 5×5 stencil (row-major,
//! di, dj = −2..2), from near: per weight one pass down the rows it reaches, the terms of each
//! entry in the order of the stencil (so the bits of a point-by-point sum).
Eigen::VectorXd column_residual(const NearColumns& near, const std::array<double, 25>& stencil, int j, int k, int c);

}  // namespace coons::solvers::fast5_detail
