#include "fast5_rows.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "row_form.h"

namespace coons::solvers::fast5_detail {

EdgeRows split_edge_rows(const double* b, int rows, int cols, int threads, int max_full) {
  EdgeRows f;
  f.rows = rows;
  f.cols = cols;
  f.ends.assign(std::size_t(rows), {});
  f.slot.assign(std::size_t(rows), -1);
  // per row: full or not, its largest magnitude and its sum of squares (each row by one thread)
  std::vector<char> full(std::size_t(rows), 0);
  std::vector<double> largest(std::size_t(rows), 0.0), squares(std::size_t(rows), 0.0);
  detail::for_each_row_band(rows, std::max(1, std::min(threads, rows)), [&](int, int r0, int r1) {
    for (int r = r0; r < r1; ++r) {
      const double* row = b + std::ptrdiff_t(r) * cols;
      const auto at = std::size_t(r);
      if (detail::has_interior(row + 1, cols - 2)) {  // a value off the columns 0, 1, cols−2, cols−1
        full[at] = 1;
        largest[at] = detail::largest_magnitude(row, std::size_t(cols));
        double s = 0;
        for (int j = 0; j < cols; ++j) s += row[j] * row[j];
        squares[at] = s;
      } else {
        f.ends[at] = {row[0], row[1], row[cols - 2], row[cols - 1]};
        largest[at] = detail::largest_magnitude(f.ends[at].data(), 4);
        squares[at] = row[0] * row[0] + row[1] * row[1] + row[cols - 2] * row[cols - 2] + row[cols - 1] * row[cols - 1];
      }
    }
  });
  f.too_many = std::count(full.begin(), full.end(), char(1)) > max_full;
  double sum = 0;
  for (int r = 0; r < rows; ++r) {
    const auto at = std::size_t(r);
    f.largest = detail::larger_magnitude(f.largest, largest[at]);
    sum += squares[at];
    if (!full[at] || f.too_many) continue;
    f.slot[at] = f.full_rows();
    const double* row = b + std::ptrdiff_t(r) * cols;
    f.values.insert(f.values.end(), row, row + cols);
  }
  f.norm = std::sqrt(sum);
  return f;
}

void edge_row_transform(const std::array<double, 4>& e, const double* s0, const double* s1, int q0, int n,
                        double* out) {
  const double even0 = e[0] + e[3], even1 = e[1] + e[2], odd0 = e[0] - e[3], odd1 = e[1] - e[2];
  const auto at = [&](int q) { return q % 2 == 0 ? even0 * s0[q] + even1 * s1[q] : odd0 * s0[q] + odd1 * s1[q]; };
  int k = 0;
  if (q0 % 2 == 1 && n > 0) out[k++] = at(q0);
  for (; k + 1 < n; k += 2) {  // an even mode, then an odd one
    const int q = q0 + k;
    out[k] = even0 * s0[q] + even1 * s1[q];
    out[k + 1] = odd0 * s0[q + 1] + odd1 * s1[q + 1];
  }
  if (k < n) out[k] = at(q0 + k);
}

const double* edge_row(const EdgeRows& f, int r, const double* s0, const double* s1, int q0, int n, double* scratch) {
  const int slot = f.slot[std::size_t(r)];
  if (slot >= 0) return f.values.data() + std::ptrdiff_t(slot) * f.cols + q0;
  edge_row_transform(f.ends[std::size_t(r)], s0, s1, q0, n, scratch);
  return scratch;
}

}  // namespace coons::solvers::fast5_detail
