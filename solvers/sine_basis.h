// The orthonormal 2-D discrete sine transform (DST-I) of grid data: the eigenbasis of every
// constant symmetric 9-point stencil (grid_stencil.h). Mode (p, q), p = 1..rows, q = 1..cols, sits
// at index (p−1)·cols + (q−1); its stencil eigenvalue is stencil_eigenvalue(s, p, q). The
// transform is its own inverse and preserves inner products.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965); FFTW's RODFT00.
#pragma once

#include <Eigen/Core>

namespace coons::solvers {

//! Y = Ŝ X column by column, X and Y #rows·cols by k (row-major grids), Ŝ orthonormal DST-I.
Eigen::MatrixXd sine_transform_2d(const Eigen::MatrixXd& X, int rows, int cols);

//! Y = S X, each column of X (length n) by the orthonormal 1-D DST-I; the 2-D transform of a
//! separable grid u ⊗ v is (S u) ⊗ (S v), which is what makes rank-structured data cheap.
Eigen::MatrixXd sine_transform_1d(const Eigen::MatrixXd& X);

}  // namespace coons::solvers
