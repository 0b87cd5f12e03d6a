// Grid-stencil problems for the solver tests: named 3×3 and 5×5 stencils (second- and fourth-order),
// free sets (full rectangle, L-shape, hole) and right-hand sides of a boundary-value problem.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <string>
#include <vector>

#include "solvers/stencil_operator.h"

namespace coons::test {

struct NamedStencil {
  std::string name;
  std::vector<double> weights;
};

//! The α family on a rows × cols grid: centre 1, edges −(1/4 − α), diagonals −α.
solvers::GridStencil alpha_grid_stencil(int rows, int cols, double alpha);

//! The 3×3 weights {d, e, d, e, c, e, d, e, d}.
std::vector<double> nine_point(double center, double edge, double diag);
//! The outer product of (1, −4, 6, −4, 1) (5×5).
std::vector<double> c1_coons();
//! 13 points: centre 20, edges −8, diagonals 2, axial distance 2: 1 (5×5).
std::vector<double> biharmonic();
//! laplace, alpha -0.1, alpha -1/4, c1-coons, biharmonic.
std::vector<NamedStencil> symmetric_stencils();

enum class Shape { kFull, kLShape, kHole };
//! The free mask of a shape (empty for kFull).
std::vector<unsigned char> shape_mask(Shape shape, int rows, int cols);

//! Right-hand sides as in a boundary-value problem: a smooth function f on every fixed point (off
//! the grid and in the mask), moved to the right-hand side: b = −Σ w(d) f(neighbour).
Eigen::MatrixX3d boundary_rhs(const solvers::StencilOperator& op);

//! max|X − reference| / max(1, max|reference|): the error of a solution against a reference.
double max_relative_error(const Eigen::MatrixXd& X, const Eigen::MatrixXd& reference);

//! One problem of the backends' sweep against a sparse direct reference.
struct ReferenceProblem {
  const NamedStencil* stencil = nullptr;
  Shape shape = Shape::kFull;
  solvers::StencilOperator op;  //!< the stencil on rows × cols with the shape's free mask
  Eigen::SparseMatrix<double> A;
  Eigen::MatrixX3d B;          //!< boundary_rhs(op)
  Eigen::MatrixX3d reference;  //!< A⁻¹B by a simplicial LDLᵀ
  //! "STENCIL, shape K, RxC" for a test's INFO.
  [[nodiscard]] std::string label() const;
};

//! f(problem) for every symmetric stencil on the full, L-shaped and holed free sets of 23×17 and
//! 30×41 grids (30 problems).
void for_each_reference_problem(const std::function<void(const ReferenceProblem&)>& f);

}  // namespace coons::test
