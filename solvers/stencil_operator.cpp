#include "stencil_operator.h"

#include <cmath>

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

void apply_stencil_operator(const StencilOperator& op, const Eigen::MatrixXd& X, Eigen::MatrixXd& Y) {
  const std::vector<Eigen::Index> number = free_numbering(op);
  Y.setZero(X.rows(), X.cols());
  for_each_coupling(op, number, [&](Eigen::Index row, Eigen::Index col, double w) {
    if (w != 0) Y.row(row) += w * X.row(col);
  });
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
