// The equations of a stencil at the free points of a problem as one sparse system with three
// right-hand sides (x, y, z): A X = B, #free by #free and #free by 3.
//
//   unknowns  the free points numbered row-major (k increases with i, then j);
//   A(q, p)   = W(q − p) for free p, q (symmetric when W is: W(a, b) = W(−a, −b));
//   B(p)      = −Σ_{data q} W(q − p) b_q  (the data moved to the right-hand side).
//
// A is filled directly in compressed column-major storage (two passes: count, then fill in
// index order; no triplets, no sort). Its pattern is the stencil's support, or with
// `box_pattern` the whole (2r+1)² box of every free point (zero weights stored), which does not
// depend on the values: a family of stencils of one radius (the C1 family over w, the α family)
// shares one pattern, one symbolic analysis, and refill_stencil_system() rewrites only the values
// and B. When the free set is a full rectangle and the stencil 3×3, the system is also described
// as a solvers::GridStencil (for the matrix-free and transform backends); when the free set is a
// full rectangle and the stencil separable (W = u vᵀ: c1-coons, the α = −1/4 mask), as a
// solvers::SeparableBandedOperator (A = P ⊗ Q, pentadiagonal Toeplitz P and Q). Always, the
// stencil on the free points' bounding rectangle is given as a solvers::StencilOperator.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <vector>

#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "solvers/grid_stencil.h"
#include "solvers/separable_banded_solver.h"
#include "solvers/stencil_operator.h"

namespace coons {

struct StencilAssemblyOptions {
  bool box_pattern = false;  //!< store the whole box (a pattern shared by every stencil of the radius)
  bool with_matrix = true;   //!< assemble A (structured backends need only B and the descriptions)
};

//! The free points of a problem and their numbering.
struct FreeNumbering {
  int m = 0, n = 0;
  std::vector<int> unknown;                //!< #(m+1)(n+1): the unknown of point (i, j), −1 for data
  std::vector<std::array<int, 2>> points;  //!< #free: (i, j) of each unknown, row-major order
  [[nodiscard]] int at(int i, int j) const { return unknown[std::size_t(i) * (n + 1) + j]; }
  [[nodiscard]] int size() const { return int(points.size()); }
};

FreeNumbering number_free_points(const FreeGrid& free);

//! The bounding rectangle [i0, i1] × [j0, j1] of the free points when they fill it completely.
struct FreeRectangle {
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;
  [[nodiscard]] int rows() const { return i1 - i0 + 1; }
  [[nodiscard]] int cols() const { return j1 - j0 + 1; }
};
std::optional<FreeRectangle> free_rectangle(const FreeNumbering& numbering);

struct StencilSystem {
  FreeNumbering numbering;
  int radius = 1;
  bool box_pattern = false;
  Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> pattern;  //!< the stored offsets, (2r+1)²
  Eigen::SparseMatrix<double> A;                               //!< #free by #free (empty when not requested)
  Eigen::MatrixX3d B;                                          //!< #free by 3
  std::optional<solvers::GridStencil> grid;                    //!< 3×3 stencil on a full rectangle
  std::optional<solvers::SeparableBandedOperator> separable;   //!< separable stencil on a full rectangle
  //! The stencil on the bounding rectangle of the free points, with their free mask (empty when the
  //! rectangle is full; rows = 0 when nothing is free): for the grid backends (fast5, pcg-fast, mg).
  solvers::StencilOperator grid_operator;
};

//! Precondition: check_stencil_problem(problem, stencil) has no structural issue (every free
//! point's stencil stays in the net).
StencilSystem assemble_stencil_system(const StencilProblem& problem, const Stencil& stencil,
                                      const StencilAssemblyOptions& options = {});

//! New values (A, B and the descriptions) for another stencil on the same problem, keeping the
//! pattern of A. Returns false (and changes nothing) when the stencil has another radius or a
//! non-zero weight outside the pattern (use box_pattern for families).
bool refill_stencil_system(const StencilProblem& problem, const Stencil& stencil, StencilSystem& system);

//! Only the right-hand side (#free by 3).
Eigen::MatrixX3d stencil_rhs(const ControlNet& net, const FreeNumbering& numbering, const Stencil& stencil);

//! Y = the stencil applied at every free point of the full net: the residual of the equations
//! (#free by 3; zero at a solution).
Eigen::MatrixX3d stencil_residual(const ControlNet& net, const FreeNumbering& numbering, const Stencil& stencil);

//! Sensitivity of a solution to a parameter p of the stencil family W(p) (e.g. w of the C1 family,
//! dweights = c1_family_stencil_derivative(w)): differentiating Σ W(p) N = 0 at the free points
//! gives A · dN/dp = −(dW/dp ⋆ N), the derivative weights applied to the solved full net N
//! (data included). Returns that right-hand side, #free by 3; dweights is (2r+1) square.
Eigen::MatrixX3d stencil_sensitivity_rhs(const ControlNet& solved, const FreeNumbering& numbering,
                                         const Eigen::MatrixXd& dweights);

//! `net` with its free points replaced by X (#free by 3); pass an rvalue to fill it in place.
ControlNet fill_free_points(ControlNet net, const FreeNumbering& numbering, const Eigen::MatrixX3d& X);

}  // namespace coons
