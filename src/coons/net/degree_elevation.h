// Exact degree elevation of Bézier curves and boundaries: the curves do not change, only the
// number of control points, so one shape can be studied at degrees 3 … 16 and more.
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), §6.1 (degree elevation).
#pragma once

#include <Eigen/Core>

#include "coons/net/control_net.h"

namespace coons {

//! The control points of the same curve at degree `degree` ≥ the current one (#degree+1 by 3).
Eigen::MatrixX3d elevate_curve(const Eigen::MatrixX3d& P, int degree);

//! The boundary with bottom/top elevated to degree m and left/right to degree n (m, n ≥ current).
Boundary elevate_boundary(const Boundary& boundary, int m, int n);

}  // namespace coons
