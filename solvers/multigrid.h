// Geometric multigrid for a StencilOperator (3×3 or 5×5 constant stencil on a rows × cols grid with
// a free mask), matrix-free on the finest level; #free unknowns, vectors #free by 1.
//
// Coarsening: by 2 in each direction, coarse point (I, J) sits on fine point (2I+o_i, 2J+o_j),
// the offsets chosen so that coarse points start one point inside the bounding box of the free
// points (o = 1 when the first row or column is free: rows_c = rows/2), and it is free exactly when
// that fine point is free. Prolongation
// is interpolation restricted to free points (fixed points keep their zero correction);
// (bicubic for 5×5 stencils, see Interpolation); every coarse column has weight 1 on its own fine
// point, which no other column touches, so P has full rank and the Galerkin coarse operator
// A_c = Pᵀ A P is non-singular (and positive definite when A is). Coarse operators are stored as
// one (2r+1)² stencil per point: bilinear Galerkin keeps radius 1 at radius 1 and 2 at 2; bicubic
// grows radius 2 to 4 and then 5. The coarsest level (≤ coarsest_unknowns free points, or
// fewer than 3 rows or columns) is solved by a sparse LU.
//
// An integer separable stencil (c1-coons, the α = −1/4 mask: integer_separable_form) is kept as
// p ⊗ q with integer p and q, so that its weights sum to exactly 0 on every level, and the finest
// level applies it in factored form (along j, then along i). The stored weights are those products
// divided by 36 or 4 and rounded: their sum is 2⁻⁵⁴ for c1-coons, a shift 250,000 times the
// smallest eigenvalue at N = 1023, and the (2r+1)² sum of a smooth vector loses the product to
// cancellation (relative error ε Σ|w| / λ). `mg-cg` needed 112 iterations there with the rounded
// weights; 20 with the exact form (docs/solvers.md).
//
// Smoothing: alternating multicolour line Gauss–Seidel. A sweep solves the banded systems of the
// grid rows (all j at once, bandwidth r), colour by colour, then those of the grid columns; a
// line's colour is its index, counted from the first free line plus one, modulo r + 1, so lines
// of one colour do not couple and are solved together (zebra lines at r = 1, colour 0 through the
// coarse points): the result does not depend on the order within a colour or on the thread
// count, the column solves run across adjacent columns and the row solves interleave several
// rows. The stencils
// (−1/2, 1, −1/2)ᵀ(−1/2, 1, −1/2) (centre 1, edges −1/2, diagonals 1/4) and
// (1, −4, 6, −4, 1)ᵀ(1, −4, 6, −4, 1) are tensor products D⊗D of 1-D difference operators: a mode
// smooth along i but oscillating along j has a tiny eigenvalue and no point smoother reduces it,
// but the row-line solve does (its error propagator is a Jacobi/Gauss–Seidel step along j alone),
// and the column-line solve handles the transposed case. Post-smoothing runs the adjoint sweep
// (the colour steps in reverse order; each is an exact block solve), so a V-cycle with as many
// pre- as post-sweeps is a symmetric operator: a valid preconditioner for conjugate gradients
// (multigrid_cg).
//
// Measured (N×N grids, N = 31 … 511, relative residual 1e−10, data on the fixed points from a
// smooth function; tests/solvers/multigrid_test.cpp, the [slow] case, one sweep per side): V-cycles
// 8–9 (centre 1, edges −1/4), 7–8 (centre 1, edges −0.35, diagonals 0.1), 1 (the first tensor
// product above: zebra lines and bilinear Galerkin coarsening solve it exactly, up to rounding),
// 11–14 (the second), 10–25 (13-point biharmonic); CG with one V-cycle 6–7, 6–7, 1, 8–17, 7–13
// iterations.
//
// Based on: W. Hackbusch, Multi-Grid Methods and Applications, Springer (1985); U. Trottenberg,
// C. W. Oosterlee, A. Schüller, Multigrid, Academic Press (2001) (line smoothers, Galerkin
// coarse operators, the m_P + m_R > 2m rule for the interpolation order).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "iteration_summary.h"
#include "stencil_operator.h"

namespace coons::solvers {

enum class CycleType { kV, kF };
//! Prolongation: bilinear, bicubic (tensor (−1, 9, 16, 9, −1)/16 weights), or kAuto: bilinear for
//! radius-1 stencils, bicubic for radius-2 (fourth-order) ones, where bilinear interpolation is too
//! inaccurate for the coarse-grid correction (m_P + m_R must exceed the order of the operator).
enum class Interpolation { kAuto, kLinear, kCubic };

struct MultigridOptions {
  CycleType cycle = CycleType::kV;
  Interpolation interpolation = Interpolation::kAuto;
  int pre_smoothing = 1;                //!< alternating line sweeps (rows, then columns) before the coarse correction
  int post_smoothing = 1;               //!< adjoint sweeps after it
  Eigen::Index coarsest_unknowns = 64;  //!< solve directly at or below this many free points
  int max_levels = 20;
  //! threads of the smoother, residual, transfer and operator loops (1; 0: every core) on levels of
  //! at least 2048 points. They run over independent lines or points, so results are identical for
  //! every count. Called inside a parallel region (the backends solve the columns of B side by
  //! side), the loops run on the calling thread.
  int threads = 1;

  bool is_valid(std::string* why) const;
};

struct MultigridLevelInfo {
  int rows = 0, cols = 0, radius = 1;
  Eigen::Index unknowns = 0;
};

class Multigrid {
 public:
  Multigrid();
  ~Multigrid();
  Multigrid(Multigrid&&) noexcept;
  Multigrid& operator=(Multigrid&&) noexcept;

  //! Builds the hierarchy. kSuccess; kFailure for invalid input (why in *message);
  //! kNotApplicable when a line block has a zero pivot (the smoother's elimination without
  //! pivoting fails, which says nothing of A); kSingular when the coarsest system is singular.
  SolveStatus setup(const StencilOperator& op, const MultigridOptions& options = {}, std::string* message = nullptr);

  [[nodiscard]] bool ready() const;
  [[nodiscard]] Eigen::Index size() const;  //!< free unknowns of the finest level
  [[nodiscard]] std::vector<MultigridLevelInfo> levels() const;
  [[nodiscard]] const MultigridOptions& options() const { return options_; }

  //! y = A x on the free points.
  void apply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  //! z = B r: one cycle of the chosen type from a zero initial guess (the preconditioner).
  void precondition(const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
  //! The stationary iteration x ← x + B (b − A x), starting from x (set to 0 if its size is wrong).
  IterationSummary solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, const IterationOptions& options = {}) const;

  struct Level;

 private:
  friend IterationSummary multigrid_cg(const Multigrid&, const Eigen::VectorXd&, Eigen::VectorXd&,
                                       const IterationOptions&);
  MultigridOptions options_;
  std::vector<Level> levels_;
  std::vector<Eigen::Index> fine_number_;  // grid point → unknown (−1 at fixed points)
  // The levels hold A / scale: an integer separable stencil (integer_separable_form) is kept as its
  // integer factors p ⊗ q, scale the common factor of the weights (1 otherwise); b and r are
  // multiplied by 1 / scale on the way in.
  double scale_ = 1;
};

//! Conjugate gradients preconditioned by one cycle of mg (use a V-cycle with pre = post smoothing:
//! it is then symmetric positive definite for a positive definite A). Reports kNotPositiveDefinite
//! when a curvature pᵀAp or rᵀBr is not positive (kNotConverged when pᵀAp is below its own
//! rounding). Once the recursive residual falls below the tolerance, the true residual replaces it
//! and CG restarts; two restarts in a row that gain less than a factor 2 end it with kNotConverged
//! ("rounding floor", with the estimate ε(Σ|w| ‖x‖ + ‖b‖)/‖b‖) and the best iterate.
IterationSummary multigrid_cg(const Multigrid& mg, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                              const IterationOptions& options = {});

}  // namespace coons::solvers
