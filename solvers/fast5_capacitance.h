// fast5, capacitance: the correction of the fast5 operator on its first and last column, after the
// per-mode banded solves (fast5_modes.h), is the capacitance matrix H⁻¹ + Σ_q t_q² M_q⁻¹
// (H = a·P_i + b·I, rank #rows per parity of the mode q). In the sine basis along i it is block
// diagonal by the parity of p: per block (about rows/2 × rows/2) a diagonal, a rank-one term and a
// low-rank term −G Gᵀ (G about rows/2 × cols/2), all in closed form from the eigenvalues
// λ_pq = a μ_p² ν_q² + b (μ_p + ν_q)². Each block is solved by conjugate gradients (O(rows·cols/4)
// flops per iteration, no transforms), preconditioned by the block with G replaced by a low-rank
// approximation: scaled by its diagonal, the block is I − W Wᵀ with W of numerical rank about 24
// at 1e−8 (N = 1023; 42 at 1e−15) and eigenvalues in [0.6, 1], so a cross approximation of
// diag^{−1/2}·G to 1e−8 (rank 20–28 from N = 255 to 1023) inverted by the Woodbury formula
// gives the solution to about 1e−8, and one correction by its residual (one pass over G) to about
// 1e−16 (against eight CG iterations to 1e−13 with the diagonal alone).
// Based on: P. E. Bjørstad, Fast numerical solution of the biharmonic Dirichlet problem on
// rectangles, SIAM J. Numer. Anal. 20 (1983) 59–71.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <vector>

#include "cross_approximation.h"

namespace coons::solvers::fast5_detail {

// One parity block of the capacitance matrix in the sine basis along i:
//   Cap·v = diag ⊙ v − kappa·u (uᵀv) − G (Gᵀv),   symmetric positive definite,
// and of H⁻¹ (H = a·P_i + b·I) in the same basis: h_inv ⊙ v − kappa·u (uᵀv).
struct CapacitanceBlock {
  std::vector<int> modes;    // modes p (0-based) along i of this block
  std::vector<int> columns;  // modes q (0-based) along j of its column parity, one per column of G
  Eigen::VectorXd diag, h_inv, u;
  double kappa = 0;
  Eigen::MatrixXd G;      // #modes by #columns, column-major: column k is c_q·Λ_q⁻¹σ (q = columns[k])
  Eigen::VectorXd c;      // c_q (#columns)
  Eigen::VectorXd sigma;  // σ_p = √2·(S_i e₁)_p of the block's modes
  // K(p, j) = Σ_q t_q s_j(q)/λ_pq over the block's columns q (#modes × 2), s_j the orthonormal sine
  // vector of the grid column j along j (fast5_boundary_values.h)
  Eigen::MatrixXd K;
  // The preconditioner P ≈ Cap: with s = diag^{−1/2}, s·P·s = I − W Wᵀ (W: #modes × (rank + 1),
  // √kappa·s⊙u and the cross approximation of s⊙G), P⁻¹ = s (I + W S⁻¹ Wᵀ) s, S = I − WᵀW
  // (its Cholesky factor below). No W (rank 0 columns): the diagonal alone.
  Eigen::VectorXd scale;
  Eigen::MatrixXd W, S_factor;

  //! out = Cap·V (V: #modes by #right-hand sides). G is read once, a column at a time, for all
  //! right-hand sides together.
  void apply(const Eigen::MatrixXd& V, Eigen::MatrixXd& out) const;
  //! gtv = Gᵀ V (V: #modes × m, gtv: #columns × m) and out = G x (x: #columns × m', out: #modes × m')
  //! in one pass over G, for an x whose row k depends on row k of Gᵀ V only: row(k, gtv, x) fills
  //! row k of x (sized by the caller) from row k of gtv, after which column k of G is not read
  //! again. The same values as the two products one after the other.
  template <class RowOfX>
  void apply_g_transpose_then_g(const Eigen::MatrixXd& V, const RowOfX& row, Eigen::MatrixXd& gtv, Eigen::MatrixXd& x,
                                Eigen::MatrixXd& out) const;
  //! V ← H⁻¹ V (rows of V are this block's modes).
  void apply_h_inverse(Eigen::MatrixXd& V) const;
  //! Builds the preconditioner from diag, kappa, u and `cross` ≈ diag^{−1/2}·G (see above); the
  //! diagonal alone when the Woodbury matrix S is not positive definite (an approximation far off,
  //! not seen on fast5's blocks).
  void build_preconditioner(const CrossApproximation& cross);
  //! Z = P⁻¹ R (rows of R are this block's modes).
  void precondition(const Eigen::MatrixXd& R, Eigen::MatrixXd& Z) const;
  //! X = Cap⁻¹ rhs to `tolerance` relative to each column: P⁻¹ rhs and one correction by its
  //! residual when that residual says the correction reaches the tolerance, otherwise preconditioned
  //! conjugate gradients from there, one column per right-hand side; returns the products with Cap.
  int solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& X, double tolerance) const;
};

//! What the four blocks of a·C + b·T on a rows × cols grid are built from: mu (#rows) and nu
//! (#cols) the eigenvalues of D along i and j, t = √2·S·e₁ along j (#cols); sigma = √2·S·e₁ along
//! i (#rows) and ts0, ts1 = t_q·s_0(q), t_q·s_1(q) (#cols, s_j the orthonormal sine vector of the
//! grid column j), formed once for all four (block_inputs).
struct BlockInputs {
  double a = 0, b = 0;
  Eigen::VectorXd mu, nu, t, sigma, ts0, ts1;
};
BlockInputs block_inputs(double a, double b, const Eigen::VectorXd& mu, const Eigen::VectorXd& nu,
                         const Eigen::VectorXd& t);

//! Block `index` = 2·(parity of q) + (parity of p) (one thread; the blocks are independent).
CapacitanceBlock capacitance_block(const BlockInputs& in, int index);

//! The four blocks, index 2·(parity of q) + (parity of p), of the fast5 operator a·C + b·T (see
//! BlockInputs), built on up to `threads` threads (OpenMP), the same on any count.
std::array<CapacitanceBlock, 4> capacitance_blocks(double a, double b, const Eigen::VectorXd& mu,
                                                   const Eigen::VectorXd& nu, const Eigen::VectorXd& t, int threads);

//! out(k, c) = G.col(k)·V.col(c) for k in [k0, k0 + 2) ∩ [0, #G) and every c (the bits of one
//! sum of eight partial sums each, whichever k0).
void dots_of_columns(const Eigen::MatrixXd& G, Eigen::Index k0, const Eigen::MatrixXd& V, Eigen::MatrixXd& out);
//! out.col(c) −= Σ_k (±)coef(k, c)·G.col(k) over k in [k0, k0 + 2) ∩ [0, #G), in the order of k
//! (− with negate).
void subtract_columns(const Eigen::MatrixXd& G, Eigen::Index k0, const Eigen::MatrixXd& coef, bool negate,
                      Eigen::MatrixXd& out);

template <class RowOfX>
void CapacitanceBlock::apply_g_transpose_then_g(const Eigen::MatrixXd& V, const RowOfX& row, Eigen::MatrixXd& gtv,
                                                Eigen::MatrixXd& x, Eigen::MatrixXd& out) const {
  gtv.resize(G.cols(), V.cols());
  out.setZero(G.rows(), x.cols());
  for (Eigen::Index k = 0; k < G.cols(); k += 2) {  // two columns of G, read once for both products
    dots_of_columns(G, k, V, gtv);
    for (Eigen::Index j = k; j < std::min(k + 2, G.cols()); ++j) row(j, gtv, x);
    subtract_columns(G, k, x, true, out);
  }
}

}  // namespace coons::solvers::fast5_detail
