// A constant stencil of radius 1 (3×3) or 2 (5×5) on a rectangular grid of rows × cols points, with
// an optional free (active) mask: the operator of a grid system whose fixed points have been moved
// to the right-hand side. It acts on the free points only (zero values everywhere else):
//
//   (A x)(i,j) = Σ_{|di|,|dj| ≤ r} w(di,dj) · x(i+di, j+dj)     for free (i,j),
//
// with x = 0 outside the grid and at fixed points. Unknowns are numbered row-major over the free
// points (#free by k vectors); with no mask every point is free (#rows·cols unknowns, k = i·cols + j).
// The matrix is symmetric exactly when w(di,dj) = w(−di,−dj); nonsymmetric weights (e.g. a
// convection term) are allowed for the methods that do not need symmetry.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "grid_stencil.h"

namespace coons::solvers {

struct StencilOperator {
  int rows = 0;    //!< grid points along i
  int cols = 0;    //!< grid points along j
  int radius = 1;  //!< 1: 3×3 weights, 2: 5×5 weights
  //! (2r+1)² weights, row-major by (di, dj): weights[(di + r)·(2r+1) + (dj + r)] = w(di, dj).
  std::vector<double> weights;
  //! rows·cols entries, 1 = free (an unknown), 0 = fixed; empty means every point is free.
  std::vector<unsigned char> free;

  [[nodiscard]] int width() const { return 2 * radius + 1; }
  [[nodiscard]] double weight(int di, int dj) const {
    return weights[std::size_t(di + radius) * std::size_t(width()) + std::size_t(dj + radius)];
  }
  [[nodiscard]] bool is_free(int i, int j) const {
    return free.empty() || free[std::size_t(i) * std::size_t(cols) + std::size_t(j)] != 0;
  }
  //! w(d) = w(−d) for every offset (the matrix is then symmetric).
  [[nodiscard]] bool symmetric() const;
  //! Number of free points (= unknowns).
  [[nodiscard]] Eigen::Index size() const;
  //! True when sizes and weights are consistent; otherwise explains why in *why.
  bool is_valid(std::string* why) const;
};

//! A radius-1 operator from (2·1+1)² or a radius-2 operator from 25 weights, no mask.
StencilOperator make_stencil_operator(int rows, int cols, const std::vector<double>& weights);

//! The 9-point GridStencil as an operator (radius 1, every point free).
StencilOperator stencil_operator(const GridStencil& s);

//! The stencil as u(a)·v(b) when it is separable: |w(a, b) − u(a)·v(b)| ≤ 1e−12 max|w| with the
//! largest weight w(a₀, b₀) as the pivot, u(a) = w(a, b₀), v(b) = w(a₀, b) / w(a₀, b₀) (index a + r);
//! nullopt when it is not, or the operator is invalid or its weights all zero.
struct RankOneSplit {
  std::vector<double> u, v;  //!< 2r+1 values each
  int a0 = 0, b0 = 0;        //!< the pivot's offsets
};
std::optional<RankOneSplit> rank_one_split(const StencilOperator& op);

//! A stencil w(a, b) = scale · p(a) · q(b) whose factors p and q are small integers (|·| ≤ 2²⁰):
//! c1-coons, (1, −4, 6, −4, 1) ⊗ (1, −4, 6, −4, 1) / 36, and the α = −1/4 mask, (−1, 2, −1) ⊗
//! (−1, 2, −1) / 4. The products p(a)·q(b) and the sums of A x in this form are exact or nearly so,
//! where the stored weights are the products rounded after the division: their sum, 0 for the
//! exact stencil, is 2⁻⁵⁴ for c1-coons, which shifts the smallest eigenvalues (θ⁸/36 ≈ 2e−22 at
//! N = 1023) by about 5.6e−17.
struct IntegerSeparableForm {
  std::vector<double> along_i, along_j;  //!< p and q, 2r+1 integer values each (index a + r)
  double scale = 1;                      //!< w(a, b) ≈ scale · p(a) · q(b), to a few ulp of w
};

//! The form when rank_one_split() finds one and each of its factors, divided by its smallest
//! non-zero magnitude, is within 1e−9 relative of integers of magnitude ≤ 2²⁰; nullopt otherwise.
std::optional<IntegerSeparableForm> integer_separable_form(const StencilOperator& op);

//! For each grid point (row-major) its unknown number, or −1 at fixed points.
std::vector<Eigen::Index> free_numbering(const StencilOperator& op);

//! Y = A·X matrix-free. X, Y: #free by k. Y must not alias X.
void apply_stencil_operator(const StencilOperator& op, const Eigen::MatrixXd& X, Eigen::MatrixXd& Y);

//! The operator as a compressed sparse matrix over the free points (#free by #free).
Eigen::SparseMatrix<double> stencil_operator_matrix(const StencilOperator& op);

//! Why a backend cannot solve on this grid operator, given with `matrix` (nullptr: none): the
//! operator is invalid, has no free points, or the matrix has another number of rows. Empty when
//! it can.
std::string grid_operator_problem(const StencilOperator& op, const Eigen::SparseMatrix<double>* matrix);

}  // namespace coons::solvers
