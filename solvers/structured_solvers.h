// Structured (matrix-free, exact) solvers for a constant GridStencil on a rectangular grid: they
// never look at the assembled matrix, only at op.stencil (kNotApplicable without one).
//
//   dst   The textbook eigen-solver: the 2-D discrete sine transform (the real-FFT DST-I of
//         sine_transform.h by rows and by strips of columns) diagonalises every constant
//         stencil, so X = S (S B S ./ λ) S / norm. analyze = plans, factorize = the eigenvalues'
//         factors (λ itself is formed on the fly), solve = two 2-D transforms (one when B is
//         non-zero only next to the frame, as for every mask system: its transform has a closed
//         form). Rows and strips are split between SolverOptions::threads threads (bit for bit
//         the same result). Exact for every non-singular stencil, definite or not. Use it as the
//         reference.
//   fast  The fastest exact solver: a sine transform along j (built on a real FFT) and
//         tridiagonal (Thomas) solves along i, vectorised across the modes; the right-hand side
//         is read row by row and only rows with a non-zero interior are transformed (a mask
//         system has two), so a solve is one inverse transform per row plus two streaming passes.
//         factorize keeps only the pivots that have not yet converged (a few % of the table).
//         When the stencil is a Kronecker product (c·d = e_i·e_j, e.g. the Coons mask α = −1/4)
//         it needs no transform: X = T_i⁻¹ B T_j⁻¹, a rank-4 product for a right-hand side on the
//         frame. A slow transform length (cols+1 with a prime factor above 13, or odd on a wide
//         grid: 1031, 1025 = 5²·41, 1001 = 7·11·13) is avoided by transforming the first L
//         columns only, L + 1 the nearest fast length below, and eliminating the other columns
//         by their Schur complement (capacitance matrix method), when that costs no accuracy (a
//         definite operator on the L columns, conditioned like the real one: capacitance.h);
//         otherwise such a grid takes the dst path. Where elimination without
//         pivoting would be unsafe (indefinite stencils) it falls back to the dst path, so it is
//         exact for every non-singular stencil; the default behind `auto`. With
//         SolverOptions::threads the threads split the rows of B and then the modes of the
//         forward elimination; one substitutes back and the others take the inverse transforms
//         of the rows it finishes (bit for bit the same result).
//
// Both report kSingular when an eigenvalue is zero to working precision (|λ| ≤ 1e-13·max|λ|),
// and both reuse the transformed basis right-hand sides across a sweep.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965); G. Farin & D. Hansford, Discrete Coons patches, CAGD 16 (1999) (eigenvalues
// of the mask family); R. E. Lynch, J. R. Rice & D. H. Thomas, Direct solution of partial
// difference equations by tensor product methods, Numer. Math. 6 (1964) (the Kronecker path);
// B. L. Buzbee, F. W. Dorr, J. A. George & G. H. Golub, The direct solution of the discrete
// Poisson equation on irregular regions, SIAM J. Numer. Anal. 8 (1971) (the interface columns).
#pragma once

#include <memory>

#include "linear_solver.h"

namespace coons::solvers {

//! The 2-D DST-I solver (registry name "dst").
std::unique_ptr<LinearSolver> make_dst_solver(const SolverOptions& options);

//! The fastest exact structured solver (registry name "fast").
std::unique_ptr<LinearSolver> make_fast_solver(const SolverOptions& options);

}  // namespace coons::solvers
