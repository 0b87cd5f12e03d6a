// The fast solver's path for Kronecker-product stencils, c·d = e_i·e_j (the Coons mask α = −1/4
// among them): the stencil is then T_i ⊗ T_j with T_i = tridiag(e_i/c, 1) of order rows and
// T_j = tridiag(e_j, c) of order cols, so X = T_i⁻¹ B T_j⁻¹ needs no transform. A column whose
// right-hand side has K − 2 full rows (row_form.h) is a sum of K outer products; with more than
// kMaxRank full rows it is solved by eliminations over whole rows.
// Sizes: rows + cols for the factors, K·(rows + cols) per rank-K solve.
// Based on: R. E. Lynch, J. R. Rice & D. H. Thomas, Direct solution of partial difference
// equations by tensor product methods, Numer. Math. 6 (1964).
#pragma once

#include <vector>

#include "grid_stencil.h"
#include "row_form.h"
#include "sine_transform.h"

namespace coons::solvers::detail {

class KroneckerSolve {
 public:
  //! Full rows up to which a column is written as a sum of outer products.
  static constexpr int kMaxRank = 8;

  //! c·d = e_i·e_j to rounding (and c ≠ 0).
  static bool applies(const GridStencil& s);
  //! Factors T_i and T_j; false when either is unsafe to eliminate without pivoting.
  bool factor(const GridStencil& s);
  //! One column x = T_i⁻¹ B T_j⁻¹ (rows × cols, row-major): from the row form f when it has at
  //! most kMaxRank full rows, otherwise from b itself (b may be null in the first case).
  void solve(const RowForm& f, const double* b, double* x);

 private:
  // X = Σ_k u_k v_kᵀ with (u, v) = (T_i⁻¹ first, T_j⁻¹ e_0), (T_i⁻¹ last, T_j⁻¹ e_{C−1}) and
  // (T_i⁻¹ e_r, T_j⁻¹ B_r) for each full row r.
  void solve_rank(const RowForm& f, double* x);
  // Y = T_i⁻¹ B by elimination along i over whole rows, then each row X_i = Y_i T_j⁻¹.
  void solve_dense(const double* b, double* x);

  int R_ = 0, C_ = 0;
  Tridiagonal ti_, tj_;
  std::vector<double> tj_e0_, tj_e1_, u_, v_, y_;
};

}  // namespace coons::solvers::detail
