// The row form of a right-hand side (solvers/row_form.h): what a structured solver keeps of B
// when it reads it once.
#include "solvers/row_form.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace coons::solvers::detail;

namespace {

// The place of (i, j) in a row-major grid of `cols` columns.
std::size_t index(int i, int j, int cols) { return std::size_t(i) * std::size_t(cols) + std::size_t(j); }

// rows × cols, row-major, non-zero only next to the frame but for one full row (`dense`).
std::vector<double> ring_grid(int rows, int cols, int dense, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<double> b(std::size_t(rows) * std::size_t(cols), 0.0);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      if (i == 0 || j == 0 || i + 1 == rows || j + 1 == cols || i == dense) b[index(i, j, cols)] = u(rng);
  return b;
}

// The largest magnitude of b as a solver that splits its first `width` columns and keeps the
// others apart (fast's interface columns) finds it.
double largest_of_split(const std::vector<double>& b, int rows, int cols, int width) {
  std::vector<double> rest;
  for (int i = 0; i < rows; ++i)
    for (int j = width; j < cols; ++j) rest.push_back(b[index(i, j, cols)]);
  const double in_form = largest_magnitude(split_rows(b.data(), rows, width, cols));
  const double in_rest = largest_magnitude(rest.data(), rest.size());
  return larger_magnitude(in_form, in_rest);
}

}  // namespace

TEST_CASE("largest_magnitude: a split form holds the largest magnitude of the rows it was split from", "[solvers]") {
  const int rows = 9, cols = 13;
  std::uint32_t seed = 1;
  // The largest value at a sparse row's ends, inside the full row, in a column kept apart (12),
  // and in the last column of the split ones (width 10: column 9).
  const std::vector<std::pair<int, int>> places = {{0, 5}, {4, 0}, {4, 12}, {3, 6}, {7, 12}, {5, 9}, {8, 11}};
  for (const int width : {cols, 10})
    for (const auto& [i, j] : places)
      for (const double big : {7.5, -7.5, 0x1p-900, 0x1p900}) {
        std::vector<double> b = ring_grid(rows, cols, 3, seed++);
        if (std::abs(big) < 1)
          for (double& v : b) v *= 0x1p-1000;  // the largest is then big, however small
        b[index(i, j, cols)] = big;
        INFO("width " << width << ", (" << i << ", " << j << ") = " << big);
        double expected = 0;
        for (const double v : b) expected = std::max(expected, std::abs(v));
        CHECK(expected == std::abs(big));
        CHECK(largest_of_split(b, rows, cols, width) == expected);
      }
}

TEST_CASE("largest_magnitude: NaN when a value is a NaN or an infinity", "[solvers]") {
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()})
    for (const auto& [i, j] : std::vector<std::pair<int, int>>{{0, 0}, {3, 6}, {5, 12}, {6, 4}}) {
      std::vector<double> b = ring_grid(9, 13, 3, 7);
      b[index(i, j, 13)] = bad;
      INFO("(" << i << ", " << j << ") = " << bad);
      CHECK(std::isnan(largest_of_split(b, 9, 13, 10)));
    }
  const std::vector<double> zeros(5, 0.0);
  CHECK(largest_magnitude(zeros.data(), zeros.size()) == 0);
  CHECK(largest_magnitude(nullptr, 0) == 0);
}

TEST_CASE("join_rows: the forms of bands of rows, joined, are the form of the whole grid", "[solvers]") {
  const int rows = 11, cols = 9;
  for (const int dense : {0, 4, 5, 10})
    for (const std::vector<int>& cuts : {std::vector<int>{0, 11}, {0, 5, 11}, {0, 4, 5, 11}, {0, 3, 7, 9, 11}}) {
      std::vector<double> b = ring_grid(rows, cols, dense, std::uint32_t(dense + 20));
      b[index(7, 3, cols)] = 0.5;  // a second full row
      const RowForm whole = split_rows(b.data(), rows, 7, cols);
      std::vector<RowForm> pieces;
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
        pieces.push_back(split_rows(b.data() + index(cuts[k], 0, cols), cuts[k + 1] - cuts[k], 7, cols));
      const RowForm joined = join_rows(pieces);
      INFO("full row " << dense << ", " << cuts.size() - 1 << " bands");
      CHECK(joined.width == whole.width);
      CHECK(joined.first == whole.first);
      CHECK(joined.last == whole.last);
      CHECK(joined.dense_rows == whole.dense_rows);
      CHECK(joined.slot == whole.slot);
      CHECK(joined.values == whole.values);
    }
  CHECK(join_rows({}).slot.empty());
}
