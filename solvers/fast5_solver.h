// fast5: an exact solver for the fourth-order 5×5 stencils a·C + b·T (a, b ≥ 0) on a full
// rows × cols rectangle (no free mask), C = δ⁴⊗δ⁴ (c1-coons), T = δ⁴⊗e + 2δ²⊗δ² + e⊗δ⁴
// (biharmonic), δ⁴ = (1, −4, 6, −4, 1): the c1-coons / c1-family / biharmonic masks (docs/math.md §3).
//
// With D = tridiag(−1, 2, −1) and P = toeplitz(6, −4, 1) = D² + E, E = e₁e₁ᵀ + e_ne_nᵀ, the operator is
//   A = a·P_i⊗P_j + b·(P_i⊗I + 2·D_i⊗D_j + I⊗P_j) = A₁ + (a·P_i + b·I)⊗E_j,
//   A₁ = a·P_i⊗D_j² + b·(P_i⊗I + 2·D_i⊗D_j + I⊗D_j²).
// The sine transform along j (DST-I, which diagonalises D_j) splits A₁ into one symmetric
// pentadiagonal Toeplitz matrix per mode q, M_q = (a ν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I, solved by
// banded LDLᵀ along i. The remaining correction lives on the first and last column; in the sine
// basis it decouples into odd and even modes (rank #rows each), and its capacitance matrix
// H⁻¹ + Σ_q t_q² M_q⁻¹ (H = a·P_i + b·I) is, in the sine basis along i too, block diagonal by the
// parity of p: per block a diagonal, a rank-one term and a low-rank term −G Gᵀ, all in closed
// form from the eigenvalues λ_pq = a μ_p² ν_q² + b (μ_p + ν_q)². It is solved by conjugate
// gradients with its diagonal as preconditioner (four blocks of about rows/2 unknowns, each
// iteration O(rows·cols/4) flops, no transforms), for all right-hand sides at once (one read of
// each block per iteration; the blocks are as large as the grid, so this is what a solve costs).
//
//   analyze    sine-transform plans along i and j;
//   factorize  recognise a and b from the weights (else not_applicable); the per-mode banded
//              factors (O(rows·cols)) and the capacitance blocks (O(rows·cols));
//   solve      per right-hand side: a sine transform of each row, two banded passes along i, the
//              capacitance solves, an inverse transform of each row.
// The capacitance operator is formed from differences of large terms (the sine-basis inverses of
// the low modes cancel), so a first solve loses digits as N grows (relative residual 5e-8 at
// N = 511, 1e-6 at 1023 on mask data); up to two steps of iterative refinement on the true
// residual (A applied in Kronecker form, O(rows·cols); the columns still above 1e-11 are refined
// together, the others are left alone), bring it to
// 5e-15–1.4e-13 up to N = 511 and 7e-12 (biharmonic) / 9e-14 (w = 0.5) at 1023.
// Cost at N = 1023 (BM_Stencil5, CPU time against the memory pass, a loaded 2-core machine):
// about 80× (biharmonic) and 105× (w = 0.5); without refinement 35× at residual 1e-6 / 6e-6, so
// two thirds of the time are the refinement's two extra solves (each two passes of row DSTs).
// Reaching 10× needs a capacitance formed without cancellation (no refinement) and fused passes.
// summary.iterations is the largest number of capacitance CG iterations (to 1e-14) of any solve.
// Measured (BM_Stencil5, N×N, mask right-hand sides), biharmonic / c1-family w = 0.5: 5 / 5 at
// N = 15, 6 / 6 at 31, 7 / 7 at 127, 7 / 8 at 255, 8 / 8 at 511, 8 / 9 at 1023: about log N.
// The Jacobi-scaled capacitance blocks have condition numbers of 1.1–1.3 (biharmonic) and
// 1.35–1.5 (w = 0.5) from N = 15 to 63, but 5, 10, 20 (∝ N) for the pure c1-coons stencil.
// b = 0 (pure c1-coons, κ ∝ N⁸) is separable and goes to the separable banded solver instead.
// Based on: P. E. Bjørstad, Fast numerical solution of the biharmonic Dirichlet problem on
// rectangles, SIAM J. Numer. Anal. 20 (1983) 59–71 (capacitance on the boundary columns);
// B. L. Buzbee, F. W. Dorr, J. A. George & G. H. Golub, The direct solution of the discrete
// Poisson equation on irregular regions, SIAM J. Numer. Anal. 8 (1971) (capacitance matrices).
#pragma once

#include <memory>
#include <optional>

#include "linear_solver.h"
#include "stencil_operator.h"

namespace coons::solvers {

//! The coefficients of a 5×5 stencil written as a·C + b·T.
struct C1FamilyWeights {
  double a = 0;  //!< weight of C = δ⁴⊗δ⁴
  double b = 0;  //!< weight of T = δ⁴⊗e + 2δ²⊗δ² + e⊗δ⁴
};

//! a, b when op's weights equal a·C + b·T (to 1e-12 relative) with a, b ≥ 0 and a + b > 0;
//! nullopt otherwise (also for radius 1).
std::optional<C1FamilyWeights> c1_family_weights(const StencilOperator& op);

//! The fast5 backend (registry name "fast5"); needs op.grid.
std::unique_ptr<LinearSolver> make_fast5_solver(const SolverOptions& options);

}  // namespace coons::solvers
