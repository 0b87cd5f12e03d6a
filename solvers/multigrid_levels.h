// The levels of Multigrid (multigrid.h) and the operations on one level: internal to the
// solvers layer. Vectors are grid vectors (rows·cols, zero at fixed points) of one level.
// Based on: U. Trottenberg, C. W. Oosterlee, A. Schüller, Multigrid, Academic Press (2001)
// (Galerkin coarse operators PᵀAP, line relaxation), as multigrid.h.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <memory>
#include <vector>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "multigrid.h"

namespace coons::solvers {

struct Multigrid::Level {
  int rows = 0, cols = 0, radius = 1;
  int offset_i = 1, offset_j = 1;  // point (I, J) sits on the finer level's (2I + offset_i, 2J + offset_j)
  int reach = 1;                   // interpolation from this level to the next finer: 1 linear, 3 cubic
  bool constant = false;           // one stencil for every point (the finest level)
  std::vector<double> coef;        // width² weights per point (or once when constant)
  // The finest level of an integer separable stencil (integer_separable_form): coef = p ⊗ q, and
  // residual() and apply_level() sum along j with q and then along i with p, which resolves the
  // products with smooth vectors that the (2r+1)² sum loses to cancellation. Empty otherwise.
  std::vector<double> factor_i, factor_j;
  std::vector<unsigned char> free;  // rows·cols
  // The stencil most interior points share (the fine level's one; on a Galerkin level the sums are
  // the same, so equal bit for bit), and per row the longest stretch [common_lo, common_hi) of free
  // interior points that have it: the kernels take the weights from registers there, without a
  // bounds or mask check per point (multigrid_kernels.h).
  std::vector<double> common;
  std::vector<int> common_lo, common_hi;
  // Banded LU (no pivoting) of the row and column line blocks, stored once per distinct line (on
  // a rectangle all lines but those near the boundary are equal, so the factors stay in cache):
  // line[m] = the distinct line u of line m; at position t of u (length n), for k = 1 … radius,
  // lower[(u·radius + k − 1)·n + t] = L(t, t−k), upper[…] = U(t, t+k), inv_pivot[u·n + t] = 1 / U(t, t).
  struct LineLU {
    std::vector<double> lower, upper, inv_pivot;
    std::vector<int> line;
  };
  LineLU row_lu, col_lu;
  int first_i = 0, first_j = 0;  // the first row and column with a free point: line colours count from them
  Eigen::Index unknowns = 0;
  int threads = 1;  // OpenMP threads of the line and point loops (1 below 2048 points)
  // The coarsest level only: the direct solve over its free points.
  std::vector<Eigen::Index> number;
  std::unique_ptr<Eigen::SparseLU<Eigen::SparseMatrix<double>>> direct;

  [[nodiscard]] int width() const { return 2 * radius + 1; }
  [[nodiscard]] Eigen::Index points() const { return Eigen::Index(rows) * cols; }
  [[nodiscard]] const double* at(Eigen::Index p) const {
    return constant ? coef.data() : coef.data() + p * width() * width();
  }
};

namespace mg_detail {

using Level = Multigrid::Level;
using Vector = Eigen::VectorXd;

//! The threads of a level loop: L.threads, but 1 inside a parallel region (a backend solving its
//! right-hand-side columns side by side, one per thread), so that a nested team never
//! oversubscribes the cores whatever OMP_MAX_ACTIVE_LEVELS says.
inline int loop_threads(const Level& L) {
#if defined(_OPENMP)
  if (omp_in_parallel()) return 1;
#endif
  return L.threads;
}

//! r = b − A x on the free points (0 at fixed points); in the factored form when L has factors.
void residual(const Level& L, const Vector& b, const Vector& x, Vector& r);
//! y = A x on the free points.
void apply_level(const Level& L, const Vector& x, Vector& y);
//! Factorises the row and column line blocks; false on a zero pivot.
bool factor_lines(Level& L);
//! One alternating multicolour line Gauss–Seidel sweep: forward (rows of colour 0 … radius, then
//! columns likewise) or its adjoint (the reverse order). work: a grid-sized scratch vector.
void smooth(const Level& L, const Vector& b, Vector& x, Vector& work, bool forward);
//! r_c = Pᵀ r and x += P x_c between a level and the next coarser one.
void restrict_to(const Level& F, const Level& Cl, const Vector& r, Vector& rc);
void prolong_add(const Level& F, const Level& Cl, const Vector& xc, Vector& x);
//! The next coarser level with the Galerkin operator Pᵀ A P (reach 1: bilinear, 3: bicubic).
//! When F.common is set (find_common_stencil(F) first, as Multigrid::setup does), the stencil of
//! the deep interior (coarse points whose fine neighbourhood lies in the grid, free, with F's
//! common stencil) is summed once and copied there, equal bit for bit to the point-by-point sums.
Level galerkin_coarse(const Level& F, int reach);
//! L.common and the stretches of it on each row (empty stretches when no stencil repeats).
void find_common_stencil(Level& L);
//! The sparse LU of the coarsest level; false when it is singular.
bool setup_direct(Level& L);
void solve_direct(const Level& L, const Vector& b, Vector& x);

}  // namespace mg_detail
}  // namespace coons::solvers
