#include "stencil_operator.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "vector_clones.h"

namespace coons::solvers {

bool StencilOperator::symmetric() const {
  for (int di = -radius; di <= radius; ++di)
    for (int dj = -radius; dj <= radius; ++dj)
      if (weight(di, dj) != weight(-di, -dj)) return false;
  return true;
}

Eigen::Index StencilOperator::size() const {
  if (free.empty()) return Eigen::Index(rows) * cols;
  Eigen::Index n = 0;
  for (unsigned char f : free) n += f != 0;
  return n;
}

bool StencilOperator::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (rows < 1 || cols < 1) return fail("the grid needs at least one row and one column");
  if (radius != 1 && radius != 2) return fail("the stencil radius must be 1 (3x3) or 2 (5x5)");
  if (weights.size() != std::size_t(width()) * std::size_t(width()))
    return fail("a radius-" + std::to_string(radius) + " stencil needs " + std::to_string(width() * width()) +
                " weights, got " + std::to_string(weights.size()));
  for (double w : weights)
    if (!std::isfinite(w)) return fail("the stencil weights must be finite");
  if (!free.empty() && free.size() != std::size_t(rows) * std::size_t(cols))
    return fail("the free mask needs rows*cols entries");
  return true;
}

StencilOperator make_stencil_operator(int rows, int cols, const std::vector<double>& weights) {
  StencilOperator op;
  op.rows = rows;
  op.cols = cols;
  op.radius = weights.size() == 25 ? 2 : 1;
  op.weights = weights;
  return op;
}

StencilOperator stencil_operator(const GridStencil& s) {
  return make_stencil_operator(s.rows, s.cols,
                               {s.diag, s.edge_i, s.diag, s.edge_j, s.center, s.edge_j, s.diag, s.edge_i, s.diag});
}

namespace {

// f divided by its smallest non-zero magnitude, when every entry is then within 1e−9 relative of
// an integer of magnitude ≤ 2²⁰ (those integers); empty otherwise.
std::vector<double> integer_factor(const std::vector<double>& f) {
  double unit = 0;
  for (double v : f)
    if (v != 0 && (unit == 0 || std::abs(v) < unit)) unit = std::abs(v);
  if (!(unit > 0)) return {};
  std::vector<double> out;
  for (double v : f) {
    const double ratio = v / unit, whole = std::round(ratio);
    if (std::abs(whole) > 1 << 20 || std::abs(ratio - whole) > 1e-9 * std::max(1.0, std::abs(whole))) return {};
    out.push_back(whole);
  }
  return out;
}

}  // namespace

std::optional<RankOneSplit> rank_one_split(const StencilOperator& op) {
  if (!op.is_valid(nullptr)) return std::nullopt;
  const int r = op.radius;
  RankOneSplit split;
  double largest = 0;
  for (int a = -r; a <= r; ++a)
    for (int b = -r; b <= r; ++b)
      if (std::abs(op.weight(a, b)) > largest) {
        largest = std::abs(op.weight(a, b));
        split.a0 = a;
        split.b0 = b;
      }
  if (!(largest > 0)) return std::nullopt;
  const double pivot = op.weight(split.a0, split.b0);
  for (int a = -r; a <= r; ++a)
    for (int b = -r; b <= r; ++b)
      if (!(std::abs(op.weight(a, b) - op.weight(a, split.b0) * op.weight(split.a0, b) / pivot) <= 1e-12 * largest))
        return std::nullopt;
  for (int k = -r; k <= r; ++k) {
    split.u.push_back(op.weight(k, split.b0));
    split.v.push_back(op.weight(split.a0, k) / pivot);
  }
  return split;
}

std::optional<IntegerSeparableForm> integer_separable_form(const StencilOperator& op) {
  const auto split = rank_one_split(op);
  if (!split) return std::nullopt;
  IntegerSeparableForm form;
  form.along_i = integer_factor(split->u);
  form.along_j = integer_factor(split->v);
  if (form.along_i.empty() || form.along_j.empty()) return std::nullopt;
  const int ia = split->a0 + op.radius, jb = split->b0 + op.radius;  // the pivot's entries in p and q
  form.scale = op.weight(split->a0, split->b0) / (form.along_i[std::size_t(ia)] * form.along_j[std::size_t(jb)]);
  return form;
}

std::vector<Eigen::Index> free_numbering(const StencilOperator& op) {
  std::vector<Eigen::Index> number(std::size_t(op.rows) * std::size_t(op.cols), -1);
  Eigen::Index next = 0;
  for (std::size_t p = 0; p < number.size(); ++p)
    if (op.free.empty() || op.free[p]) number[p] = next++;
  return number;
}

namespace {

// Calls f(row unknown, column unknown, weight) for every coupling between free points, rows in
// increasing order and, within a row, columns in increasing order.
template <class F>
void for_each_coupling(const StencilOperator& op, const std::vector<Eigen::Index>& number, F&& f) {
  const int r = op.radius;
  for (int i = 0; i < op.rows; ++i)
    for (int j = 0; j < op.cols; ++j) {
      const Eigen::Index row = number[std::size_t(i) * op.cols + j];
      if (row < 0) continue;
      for (int di = -r; di <= r; ++di) {
        const int ii = i + di;
        if (ii < 0 || ii >= op.rows) continue;
        for (int dj = -r; dj <= r; ++dj) {
          const int jj = j + dj;
          if (jj < 0 || jj >= op.cols) continue;
          const Eigen::Index col = number[std::size_t(ii) * op.cols + jj];
          if (col >= 0) f(row, col, op.weight(di, dj));
        }
      }
    }
}

}  // namespace

namespace {

// y[k] += w · x[k], k < n (no fused multiply-add: the products and sums of for_each_coupling's order).
COONS_VECTOR_CLONES void add_scaled_row(double w, const double* __restrict x, double* __restrict y, std::ptrdiff_t n) {
  for (std::ptrdiff_t k = 0; k < n; ++k) y[k] += w * x[k];
}

// y = A x on the whole grid (row-major, rows × cols, x = 0 at fixed points), row by row: for each
// offset (di, dj) in the order of for_each_coupling one pass along the row, so every point sums
// the same products in the same order as the coupling-by-coupling loop, bit for bit.
void apply_on_grid(const StencilOperator& op, const double* x, double* y) {
  const int r = op.radius;
  const std::ptrdiff_t cols = op.cols;
  std::fill(y, y + std::ptrdiff_t(op.rows) * cols, 0.0);
  for (int i = 0; i < op.rows; ++i)
    for (int di = -r; di <= r; ++di) {
      const int ii = i + di;
      if (ii < 0 || ii >= op.rows) continue;
      for (int dj = -r; dj <= r; ++dj) {
        const double w = op.weight(di, dj);
        if (w == 0) continue;
        const std::ptrdiff_t j0 = std::max(0, -dj), j1 = std::min<std::ptrdiff_t>(cols, cols - dj);
        if (j1 > j0) add_scaled_row(w, x + ii * cols + j0 + dj, y + i * cols + j0, j1 - j0);
      }
    }
}

}  // namespace

void apply_stencil_operator(const StencilOperator& op, const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) {
  Y.resize(X.rows(), X.cols());
  const std::size_t points = std::size_t(op.rows) * std::size_t(op.cols);
  if (Eigen::Index(points) == X.rows()) {  // every point free: X and Y are the grids themselves
    for (Eigen::Index c = 0; c < X.cols(); ++c) apply_on_grid(op, X.col(c).data(), Y.col(c).data());
    return;
  }
  // Fixed points: the free values scattered into a grid with zeros elsewhere (w·0 adds nothing,
  // as the coupling loop's skipped terms), the product gathered back.
  const std::vector<Eigen::Index> number = free_numbering(op);
  std::vector<double> x(points), y(points);
  for (Eigen::Index c = 0; c < X.cols(); ++c) {
    for (std::size_t p = 0; p < points; ++p) x[p] = number[p] >= 0 ? X(number[p], c) : 0.0;
    apply_on_grid(op, x.data(), y.data());
    for (std::size_t p = 0; p < points; ++p)
      if (number[p] >= 0) Y(number[p], c) = y[p];
  }
}

Eigen::SparseMatrix<double> stencil_operator_matrix(const StencilOperator& op) {
  const std::vector<Eigen::Index> number = free_numbering(op);
  std::vector<Eigen::Triplet<double>> entries;
  for_each_coupling(op, number,
                    [&](Eigen::Index row, Eigen::Index col, double w) { entries.emplace_back(int(row), int(col), w); });
  const Eigen::Index n = op.size();
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

std::string grid_operator_problem(const StencilOperator& op, const Eigen::SparseMatrix<double>* matrix) {
  std::string why;
  if (!op.is_valid(&why)) return "invalid grid operator: " + why;
  if (op.size() == 0) return "the grid operator has no free points";
  if (matrix && matrix->rows() != op.size())
    return "the matrix has " + std::to_string(matrix->rows()) + " rows but the grid operator " +
           std::to_string(op.size()) + " free points";
  return {};
}

}  // namespace coons::solvers
