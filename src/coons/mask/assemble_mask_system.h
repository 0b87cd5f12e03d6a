// The mask equations of the (m−1)×(n−1) interior of a net as one sparse linear system with three
// right-hand sides (x, y, z): A X = B, A = I − mask on the interior, B = the mask applied to the
// known frame. Unknown k is interior point (i, j) = (1 + k / (n−1), 1 + k % (n−1)).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/grid_stencil.h"

namespace coons {

struct MaskSystem {
  solvers::GridStencil stencil;   //!< the operator, matrix-free
  Eigen::SparseMatrix<double> A;  //!< the same, assembled (empty when not requested)
  Eigen::MatrixX3d B;             //!< #interior by 3
};

//! Assemble the system for the frame of `net` (its interior is ignored). With m or n = 1 the
//! system is empty (0 unknowns). The matrix is filled directly in compressed form.
MaskSystem assemble_mask_system(const ControlNet& net, const Mask9& mask, bool with_matrix = true);

//! Only the right-hand side: #interior by 3, non-zero only next to the frame (O(m + n) work).
Eigen::MatrixX3d mask_rhs(const ControlNet& net, const Mask9& mask);

//! `net` with its interior replaced by X (#interior by 3); pass an rvalue to fill it in place.
ControlNet fill_interior(ControlNet net, const Eigen::MatrixX3d& X);

//! The interior of `net` as #interior by 3 (the inverse of fill_interior).
Eigen::MatrixX3d interior_of(const ControlNet& net);

}  // namespace coons
