#include "grid_fixtures.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <utility>

namespace coons::test {

using solvers::StencilOperator;

solvers::GridStencil alpha_grid_stencil(int rows, int cols, double alpha) {
  return {rows, cols, 1.0, -(0.25 - alpha), -(0.25 - alpha), -alpha};
}

std::vector<double> nine_point(double center, double edge, double diag) {
  return {diag, edge, diag, edge, center, edge, diag, edge, diag};
}

std::vector<double> c1_coons() {  // outer product of (1, −4, 6, −4, 1)
  const double a[5] = {1, -4, 6, -4, 1};
  std::vector<double> w(25);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) w[std::size_t(i) * 5 + std::size_t(j)] = a[i] * a[j];
  return w;
}

std::vector<double> biharmonic() {  // 13 points: centre 20, edges −8, diagonals 2, axial distance 2: 1
  std::vector<double> w(25, 0.0);
  auto set = [&](int di, int dj, double v) { w[std::size_t(di + 2) * 5 + std::size_t(dj + 2)] = v; };
  set(0, 0, 20);
  for (int s : {-1, 1}) {
    set(s, 0, -8), set(0, s, -8), set(2 * s, 0, 1), set(0, 2 * s, 1);
    for (int t : {-1, 1}) set(s, t, 2);
  }
  return w;
}

std::vector<NamedStencil> symmetric_stencils() {
  return {{"laplace", nine_point(1, -0.25, 0)},
          {"alpha -0.1", nine_point(1, -0.35, 0.1)},
          {"alpha -1/4", nine_point(1, -0.5, 0.25)},
          {"c1-coons", c1_coons()},
          {"biharmonic", biharmonic()}};
}

std::vector<unsigned char> shape_mask(Shape shape, int rows, int cols) {
  std::vector<unsigned char> free(std::size_t(rows) * cols, 1);
  if (shape == Shape::kFull) return {};
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      const bool out = shape == Shape::kLShape
                           ? (i >= rows / 2 && j >= cols / 2)
                           : (std::abs(i - rows / 2) <= rows / 6 && std::abs(j - cols / 3) <= cols / 5);
      if (out) free[std::size_t(i) * cols + j] = 0;
    }
  return free;
}

// Right-hand sides as in a boundary-value problem: a smooth function f on every fixed point (off the
// grid and in the mask), moved to the right-hand side: b = −Σ w(d) f(neighbour) over fixed neighbours.
Eigen::MatrixX3d boundary_rhs(const StencilOperator& op) {
  const std::vector<Eigen::Index> number = free_numbering(op);
  const std::function<double(double, double)> f[3] = {
      [](double u, double v) { return std::cos(1.3 * u + 0.4) * std::exp(0.7 * v) + u * u * v; },
      [](double u, double v) { return u - 2 * v + u * v; },
      [](double u, double v) { return std::sin(2 * u) * (1 + v * v); }};
  Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(op.size(), 3);
  const int r = op.radius;
  for (int i = 0; i < op.rows; ++i)
    for (int j = 0; j < op.cols; ++j) {
      const Eigen::Index k = number[std::size_t(i) * op.cols + j];
      if (k < 0) continue;
      for (int di = -r; di <= r; ++di)
        for (int dj = -r; dj <= r; ++dj) {
          const int ii = i + di, jj = j + dj;
          const bool inside = ii >= 0 && ii < op.rows && jj >= 0 && jj < op.cols;
          if (inside && op.is_free(ii, jj)) continue;
          const double u = double(ii + r) / (op.rows + 2 * r), v = double(jj + r) / (op.cols + 2 * r);
          for (int c = 0; c < 3; ++c) B(k, c) -= op.weight(di, dj) * f[c](u, v);
        }
    }
  return B;
}

double max_relative_error(const Eigen::MatrixXd& X, const Eigen::MatrixXd& reference) {
  return (X - reference).cwiseAbs().maxCoeff() / std::max(1.0, reference.cwiseAbs().maxCoeff());
}

std::string ReferenceProblem::label() const {
  return stencil->name + ", shape " + std::to_string(int(shape)) + ", " + std::to_string(op.rows) + "x" +
         std::to_string(op.cols);
}

void for_each_reference_problem(const std::function<void(const ReferenceProblem&)>& f) {
  const std::vector<NamedStencil> stencils = symmetric_stencils();
  for (const NamedStencil& stencil : stencils)
    for (Shape shape : {Shape::kFull, Shape::kLShape, Shape::kHole})
      for (auto [rows, cols] : {std::pair{23, 17}, {30, 41}}) {
        ReferenceProblem p;
        p.stencil = &stencil;
        p.shape = shape;
        p.op = solvers::make_stencil_operator(rows, cols, stencil.weights);
        p.op.free = shape_mask(shape, rows, cols);
        p.A = solvers::stencil_operator_matrix(p.op);
        p.B = boundary_rhs(p.op);
        p.reference = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>(p.A).solve(p.B);
        f(p);
      }
}

}  // namespace coons::test
