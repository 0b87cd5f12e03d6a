// The triangular mask family at every interior point b = b[i][j][k] (i, j, k ≥ 1) of a degree-n net:
//   b = a·(b[i±1][j∓1][k] + b[i±1][j][k∓1] + b[i][j±1][k∓1])          (the 6 neighbours)
//     + c·(b[i+2][j−1][k−1] + b[i−1][j+2][k−1] + b[i−1][j−1][k+2]),    6a + 3c = 1,
// with c the parameter (c = −1/6, a = 1/4: the quadratic-precision member; c = 0: the triangular
// Laplace mask). As a linear system A X = B: A = I − mask on the interior, #interior square,
// non-symmetric unless c = 0; X, B #interior by 3 (x, y, z); unknowns numbered in the row order of
// docs/formats.md "Triangular nets" restricted to the interior (interior_index in tri_net.h).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <optional>
#include <string>

#include "coons/tri/tri_net.h"

namespace coons::tri {

struct TriMask {
  double c = -1.0 / 6.0;  //!< weight of the three far points (2,−1,−1), (−1,2,−1), (−1,−1,2)

  //! Weight of each of the six neighbours: a = (1 − 3c)/6.
  [[nodiscard]] double a() const { return (1.0 - 3.0 * c) / 6.0; }
  //! True for a finite c; otherwise explains why.
  bool is_valid(std::string* why) const;

  static TriMask quadratic_precision() { return TriMask{-1.0 / 6.0}; }
  static TriMask laplace() { return TriMask{0.0}; }
};

//! One stencil entry: index offset (Δi, Δj, Δk) and whether it carries weight a (else c).
struct TriStencilEntry {
  std::array<int, 3> offset;
  bool neighbour;
};
//! The 9 entries of the mask: the six neighbours first, then the three far points.
const std::array<TriStencilEntry, 9>& tri_stencil();

struct TriMaskSystem {
  Eigen::SparseMatrix<double> A;  //!< #interior square, I − mask (column-major, compressed)
  Eigen::MatrixX3d B;             //!< #interior by 3: the mask applied to the known boundary
};

//! Assemble A and B for the boundary of `net` (its interior is ignored). The matrix is written
//! column by column straight into compressed storage (no triplets). n < 3 gives an empty system.
TriMaskSystem assemble_tri_mask_system(const TriNet& net, const TriMask& mask);

//! The member c*ₙ = −1/6 − 1/(2(n − 3)) of degree n ≥ 4, at which the bubble b_ijk = i·j·k is a
//! null vector of A (the system is singular there; docs/math.md, triangular nets); none for n < 4.
std::optional<double> bubble_singular_c(int n);

//! ∂B/∂c − (∂A/∂c) X for the solved net: the right-hand side of A·∂X/∂c (one extra solve gives the
//! derivative of the interior with respect to c): −½·Σ neighbours + Σ far points, #interior by 3.
Eigen::MatrixX3d tri_mask_sensitivity_rhs(const TriNet& solved);

//! The interior of `net` as #interior by 3 (unknown order), and its inverse.
Eigen::MatrixX3d interior_of(const TriNet& net);
TriNet fill_interior(TriNet net, const Eigen::MatrixX3d& X);

//! max over interior points and x, y, z of |b − mask(b)|; 0 when there is no interior.
double tri_mask_residual(const TriNet& net, const TriMask& mask);

//! The member of the family that `net` satisfies best: the residual r(c) = b − a(c)ΣN − cΣC is affine
//! in c, so c minimising Σ‖r(c)‖² over the interior is closed-form. The net solves the system of c
//! exactly when residual = 0. determined = false when r does not depend on c (then c = 0).
struct TriMaskFit {
  double c = 0;
  double residual = 0;  //!< tri_mask_residual(net, {c}): max |r(c)| over interior points and x, y, z
  bool determined = true;
};
TriMaskFit fit_tri_mask(const TriNet& net);

}  // namespace coons::tri
