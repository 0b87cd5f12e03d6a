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
// iteration O(rows·cols/4) flops, no transforms), for all right-hand sides at once.
//
//   analyze    sine-transform plans along i and j;
//   factorize  recognise a and b from the weights (else not_applicable); the per-mode banded
//              factors and the capacitance blocks (O(rows·cols)). M_q is Toeplitz, so its LDLᵀ
//              factors converge down the rows (to 1e-15 after about 40/√ν_q rows): only the rows
//              above that are stored (4 % of rows·cols at N = 1023), the rest read the limit;
//   solve      a sine transform of each row (a row of B that is zero off the columns 0, 1,
//              cols−2, cols−1, as in most rows of a mask system, is the combination of those four
//              columns' sine vectors instead), written into X, sweeps of banded solves along i
//              (down and up the rows for a chunk of 128 modes at a time in a buffer that stays in
//              the cache, all right-hand sides together, the result back into X), the capacitance
//              solves, an inverse transform of X's rows in place. X is the only grid-sized array
//              (until 2026-12-02 the transformed rows and the sweeps' work had two more sets of
//              three: 48 MB at N = 1023).
// Threads (SolverOptions::threads, OpenMP): the chunks of modes are shared among the threads
// (fast5_modes.h), the four capacitance blocks run in parallel, the row transforms are shared
// (one SineTransform per thread); the result is the same bit for bit on any count.
// Files: fast5_modes.h (per-mode factors and sweeps), fast5_capacitance.h (the blocks and their CG).
// Accuracy. The rounding of the first solve sits almost entirely in the capacitance unknowns h
// (the sources on the columns 0 and cols−1): h comes from A₁⁻¹b, whose banded solves for the low
// modes (κ(M_q) ∝ N⁴) have forward errors of κ·ε, so the residual there is 5e-8 at N = 511 and
// 6e-6 at 1023 on mask data, while the other columns are at 5e-12. Since A x − b vanishes off
// those two columns, a correction needs no residual of the whole grid and no new transform:
// ρ = (b − A x) on the two columns (from x on the columns 0–2 and cols−3..cols−1, dot products of
// the transformed rows taken during the sweep up), δx = A⁻¹Uρ = A₁⁻¹U·Cap⁻¹H⁻¹ρ (Woodbury; the
// capacitance solve alone, then two banded sweeps with the rank-two right-hand side generated on
// the fly). At most kCorrections of them, until ‖ρ‖ ≤ 1e-13‖b‖: none to one up to N = 255, two
// at 1023. Relative residuals after them (mask data, 3 right-hand sides): 1e-13 (biharmonic) /
// 4e-13 (w = 0.5) at N = 255, 7e-13 / 3e-12 at 1023 (the columns other than 0 and cols−1).
// Cost at N = 1023 (CPU time of a fresh solve, 3 right-hand sides, 2 cores with load 12.7):
// biharmonic 90 ms and w = 0.5 105 ms, against 309 and 392 ms with two whole-grid refinement
// steps (residual, two row transforms and the whole solve again each), measured together; the
// memory pass took 1.8–4 ms at that load, so about 25–50× (biharmonic) and 30–60× (w = 0.5).
// The 10× target is not reached. Where a solve went on 2026-12-02 (biharmonic, N = 1023, mask data,
// one thread, phases timed inside the solver, medians of 8 solves; the benchmark's memory pass
// took 0.9 ms): factorisation 0.9 + capacitance blocks 3.0, forward transform 2.2, first sweep (g)
// 9.1, capacitance CG 4.7, second sweep (x̂ and the boundary values) 10.5, one correction (CG 4.7,
// sweep 11.9), inverse transform 6.0 ms. The inverse transform alone is 6–7 memory passes here.
// That day's changes (no grid-sized arrays but X, the capacitance product reading G once, eight-
// lane parity dots) took the benchmark from 62–67 to 48–54 ms on one thread and from 42–44 to
// 35–37 ms on two (alternating runs of both binaries). A capacitance formed without the forward
// error (so no correction) would need another exact representation of A₁⁻¹ on the boundary
// columns; not done.
// summary.iterations is the largest number of capacitance CG iterations of any capacitance solve
// (the first to 1e-7, corrections to what they need, at least 1e-10): 6 (biharmonic) and 7
// (w = 0.5) at N = 1023 on mask data; to 1e-14 it was 8 / 9 (about log N).
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
