// A constant symmetric 9-point stencil on a rectangular grid with zero (Dirichlet) values outside:
// the operator of every mask system of coons, described without reference to Bézier nets.
//
//   (A x)(i,j) = c·x(i,j) + e_i·(x(i−1,j) + x(i+1,j)) + e_j·(x(i,j−1) + x(i,j+1))
//              + d·(x(i−1,j−1) + x(i+1,j−1) + x(i−1,j+1) + x(i+1,j+1))
//
// on 0 ≤ i < rows, 0 ≤ j < cols, unknowns numbered row-major (k = i·cols + j).
// Its eigenvectors are sin(pπ(i+1)/(rows+1))·sin(qπ(j+1)/(cols+1)), so the 2-D discrete sine
// transform diagonalises it (Based on: Farin & Hansford, Discrete Coons patches, CAGD 16 (1999)).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace coons::solvers {

struct GridStencil {
  int rows = 0;       //!< grid points along i
  int cols = 0;       //!< grid points along j
  double center = 1;  //!< c
  double edge_i = 0;  //!< e_i, weight of the two neighbours along i
  double edge_j = 0;  //!< e_j, weight of the two neighbours along j
  double diag = 0;    //!< d, weight of the four diagonal neighbours

  [[nodiscard]] Eigen::Index size() const { return Eigen::Index(rows) * cols; }
};

//! Eigenvalue of the stencil operator for the sine mode (p, q), 1 ≤ p ≤ rows, 1 ≤ q ≤ cols.
double stencil_eigenvalue(const GridStencil& s, int p, int q);

//! Smallest and largest eigenvalue over all modes (exact, from the closed form).
std::pair<double, double> stencil_eigenvalue_range(const GridStencil& s);

//! Y = A·X matrix-free. X, Y: #size by k. Y must not alias X.
void apply_stencil(const GridStencil& s, const Eigen::MatrixXd& X, Eigen::MatrixXd& Y);

//! The stencil as a compressed sparse matrix (#size by #size, symmetric, column-major), filled
//! directly in index order: no triplets, no search. The pattern is always the full 9-point
//! pattern (zero weights stored as explicit zeros), so that it does not depend on the values and
//! one symbolic analysis serves every α.
Eigen::SparseMatrix<double> stencil_matrix(const GridStencil& s);

//! Overwrite the values of a matrix made by stencil_matrix(s_old) with those of s (same size).
void refill_stencil_matrix(const GridStencil& s, Eigen::SparseMatrix<double>& A);

}  // namespace coons::solvers
