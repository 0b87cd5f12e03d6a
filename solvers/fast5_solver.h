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
// form from the eigenvalues λ_pq = a μ_p² ν_q² + b (μ_p + ν_q)². Each block (about rows/2
// unknowns) is solved by the Woodbury inverse of its low-rank approximation and one correction
// by the exact residual (one pass over G, O(rows·cols/4) flops, no transforms), for all
// right-hand sides at once (fast5_capacitance.h).
//
//   analyze    sine-transform plans along i and j;
//   factorize  recognise a and b from the weights (else not_applicable); the per-mode banded
//              factors, the closed form of the lowest modes and the capacitance blocks
//              (O(rows·cols)). M_q is Toeplitz, so its LDLᵀ factors converge down the rows (to
//              1e-15 after about 40/√ν_q rows): only the rows above that are stored (4 % of
//              rows·cols at N = 1023), the rest read the limit;
//   solve      one scan of B (in rhs_scaling, which also takes its largest magnitudes and norms
//              from it) splits each column by rows (fast5_rows.h): a row that is zero off the
//              columns 0, 1, cols−2, cols−1 (all but four rows of a mask system) is kept as those
//              four values, and its sine transform is the combination of the four columns' sine
//              vectors, formed where a sweep reads it; the few other rows are transformed once.
//              (A B with more than rows/4 full rows in a column is transformed row by row into X
//              instead.) Then g, the capacitance right-hand side: in closed form from those row
//              forms when the full rows pair into at most four key rows (fast5_boundary_values.h,
//              two passes over the blocks' G), otherwise by a sweep of banded solves along i (down
//              and up the rows for a chunk of 128 modes at a time in a buffer that stays in the
//              cache, all right-hand sides together); the capacitance solve; then x̂ = A₁⁻¹(b̂ − U h)
//              and the inverse transform of X's rows: on B read from its row forms with at least
//              kMinTwistRows rows, by the twisted sweep (fast5_twisted.h: the banded solves from the
//              top and from the bottom to the middle rows and back, each row transformed as soon as
//              it is finished, while it is in the cache); otherwise a chunked sweep written into X
//              and the row transforms in place. X is the only grid-sized array, and on mask data
//              the first time it is written is by that sweep.
//              The modes q < cols/16 (rounded up to even) are solved in closed form in the
//              sweeps instead (fast5_low_modes.h; not factored): κ(M_q) ∝ (cols/(q+1))⁴ reaches 1e11 at
//              N = 1023, and the banded solves' forward error of κ·ε on those modes, on the
//              columns 0 and cols−1, was what left the first solve with a boundary residual of
//              2e-6 there.
// Threads (SolverOptions::threads, OpenMP): the chunks of modes (and the closed form of the lowest
// modes, as one more unit) are shared among the threads (fast5_modes.h), the four capacitance
// blocks run in parallel, the row transforms are shared (one SineTransform per thread); the
// twisted sweep runs its two halves' ways down and four parts of the lowest modes as six units,
// then the ways up, each half's rows finished by one thread and the row transforms shared by all;
// the result is the same bit for bit on any count.
// Files: fast5_modes.h (per-mode factors and sweeps), fast5_twisted.h (the sweep from both ends
// with the row transforms), fast5_low_modes.h (the lowest modes in closed form), fast5_rows.h (B row by row),
// fast5_boundary_values.h (g in closed form), fast5_capacitance.h (the blocks, their low-rank preconditioner and their
// solve), fast5_near_columns.h (what the boundary check reads, kept while the grid is in the cache). Accuracy. A x − b
// vanishes off the columns 0 and cols−1 for any capacitance unknowns h; on those two columns it is what the error of h
// leaves. With the lowest modes in closed form and the capacitance solve run to 1e-13 (1e-14 now), the first solve
// leaves 2.5–5.3·N·ε·‖b‖ there on mask data from N = 255 to 1023 (the level of the rest of the grid: relative
// residuals 1.3e-13 / 4.4e-13 at N = 255 and 1.0e-12 / 3.4e-12 at 1023, biharmonic / w = 0.5, against 7.5e-13 / 3.0e-12
// of the version before, which corrected it twice). Those columns are corrected from their exact residual, after the
// inverse transform, only while it is above 16·N·ε·‖b‖ (and 1e-13‖b‖) and above 4 times the residual the other columns
// are estimated to have (from the columns 2 and cols−3): a correction is a capacitance solve, a banded sweep and two
// more row transforms, whose rounding is as large as what it would remove at that level. On mask data up to N = 2047
// none is made; in the solver tests 14 of 250 solves (small grids, random data) make one.
// Cost at N = 1023 (docs/solvers.md has the history and the computed figures): about 16–17 ms on
// one thread and 9–10 ms on two (biharmonic, fresh solve, 3 right-hand sides of mask data, on
// this machine's varying host), of which the row transforms alone (BM_SineRows) take about 6.5
// and 4 ms.
// summary.iterations is the largest number of products with a capacitance block in any
// capacitance solve (the first to 1e-14, corrections to what they need, at least 1e-10): 1 on
// mask data from N = 31 to 2047 (the preconditioned solve and its one correction).
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
