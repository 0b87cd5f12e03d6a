// How well a net satisfies a 3×3 mask: the largest deviation of an interior point from the
// mask-weighted sum of its eight neighbours (0 for the exact solution of the mask system).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"

namespace coons {

//! max over interior points and x, y, z of |b_ij − mask(b)_ij|; 0 when there is no interior.
double mask_residual(const ControlNet& net, const Mask9& mask);

}  // namespace coons
