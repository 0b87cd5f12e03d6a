// pcg-fast: conjugate gradients on the free points of a grid operator (any free set: holes,
// L-shapes, fixed interior curves), preconditioned by the exact structured solve of the full
// bounding rectangle: z = Rᵀ-restrict(A_box⁻¹ · extend-by-zero(r)), A_box the same stencil with
// every point of the rows × cols grid free. A_box⁻¹ is the 3×3 solver `fast` (sine transform
// along j, tridiagonal along i) for symmetric 9-point stencils, `fast5` for the 5×5 stencils
// a·C + b·T (c1-family, biharmonic) and the separable banded solver for other separable ones;
// every other stencil is not_applicable. The preconditioner (A_box⁻¹)_FF is the inverse of the
// Schur complement A_FF − A_FX A_XX⁻¹ A_XF, so the preconditioned operator is the identity plus
// a term of rank at most the number of fixed points next to free ones inside the rectangle:
// the iterations grow with the fixed set's perimeter (measured, BM_Stencil5: a centred square hole
// of side N/4 in an N×N c1-family w = 0.5 grid, mask right-hand sides, 3 columns to 1e-12: 11
// iterations at N = 15, 30 at 31, 89 at 127, 186 at 255 — about linear in N, so a fixed hole is
// cheap and a hole that grows with the grid is not). On a full rectangle it takes one iteration.
//
//   analyze    the grid operator (op.grid, else the 3×3 op.stencil) and the inner solver's analysis;
//   factorize  the inner solver's factorisation; for 3×3 stencils the exact eigenvalue range of the
//              box (a non-positive one is kNotPositiveDefinite: CG needs a definite system, and
//              every principal submatrix of a definite box operator is definite);
//   solve      PCG on the three right-hand sides at once (one preconditioner solve per iteration
//              for all three); the verdict of LinearSolver::finish_iteration.
// Based on: M. R. Hestenes & E. Stiefel, Methods of conjugate gradients for solving linear
// systems, J. Res. NBS 49 (1952); W. Proskurowski & O. Widlund, On the numerical solution of
// Helmholtz's equation by the capacitance matrix method, Math. Comp. 30 (1976) (fast solvers of a
// covering rectangle as preconditioners on irregular regions).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

//! The pcg-fast backend (registry name "pcg-fast").
std::unique_ptr<LinearSolver> make_pcg_fast_solver(const SolverOptions& options);

}  // namespace coons::solvers
