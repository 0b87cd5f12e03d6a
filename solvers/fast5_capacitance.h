// fast5, capacitance: the correction of the fast5 operator on its first and last column, after the
// per-mode banded solves (fast5_modes.h), is the capacitance matrix H⁻¹ + Σ_q t_q² M_q⁻¹
// (H = a·P_i + b·I, rank #rows per parity of the mode q). In the sine basis along i it is block
// diagonal by the parity of p: per block (about rows/2 × rows/2) a diagonal, a rank-one term and a
// low-rank term −G Gᵀ (G about rows/2 × cols/2), all in closed form from the eigenvalues
// λ_pq = a μ_p² ν_q² + b (μ_p + ν_q)². Each block is solved by conjugate gradients with its
// diagonal as preconditioner (O(rows·cols/4) flops per iteration, no transforms).
// Based on: P. E. Bjørstad, Fast numerical solution of the biharmonic Dirichlet problem on
// rectangles, SIAM J. Numer. Anal. 20 (1983) 59–71.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace coons::solvers::fast5_detail {

// One parity block of the capacitance matrix in the sine basis along i:
//   Cap·v = diag ⊙ v − kappa·u (uᵀv) − G (Gᵀv),   symmetric positive definite,
// and of H⁻¹ (H = a·P_i + b·I) in the same basis: h_inv ⊙ v − kappa·u (uᵀv).
struct CapacitanceBlock {
  std::vector<int> modes;  // modes p (0-based) along i of this block
  Eigen::VectorXd diag, h_inv, u;
  double kappa = 0;
  Eigen::MatrixXd G;  // #modes by #(modes q of the column parity), column-major

  //! out = Cap·V (V: #modes by #right-hand sides). G is read once, a column at a time, for all
  //! right-hand sides together.
  void apply(const Eigen::MatrixXd& V, Eigen::MatrixXd& out) const;
  //! V ← H⁻¹ V (rows of V are this block's modes).
  void apply_h_inverse(Eigen::MatrixXd& V) const;
  //! X = Cap⁻¹ rhs by conjugate gradients with the diagonal as preconditioner, one column per
  //! right-hand side, to `tolerance` relative to each column; returns the iterations.
  int solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& X, double tolerance) const;
};

//! The four blocks, index 2·(parity of q) + (parity of p), of the fast5 operator a·C + b·T on a
//! rows × cols grid: mu (#rows) and nu (#cols) the eigenvalues of D along i and j, t = √2·S·e₁
//! along j (#cols). The blocks are built on up to `threads` threads (OpenMP), the same on any count.
std::array<CapacitanceBlock, 4> capacitance_blocks(double a, double b, const Eigen::VectorXd& mu,
                                                   const Eigen::VectorXd& nu, const Eigen::VectorXd& t, int threads);

}  // namespace coons::solvers::fast5_detail
