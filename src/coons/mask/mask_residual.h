// How well a net satisfies a mask: the largest deviation of a solved point from the mask-weighted
// sum of its neighbours (0 for the exact solution of the mask system).
//   mask_residual(net, Mask9)               the 3×3 family at every interior point (the classical
//                                           problem: one data ring);
//   mask_residual(net, free, Stencil)       any 3×3 or 5×5 stencil at the free points of a grid:
//                                           max |Σ W(a, b) b_{i+a, j+b}| (W(0, 0) = 1), so for the
//                                           alpha stencil on the interior it is the first one.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include "coons/mask/mask9.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"

namespace coons {

//! max over interior points and x, y, z of |b_ij − mask(b)_ij|; 0 when there is no interior.
double mask_residual(const ControlNet& net, const Mask9& mask);

//! max over the free points and x, y, z of |Σ W(a, b) b_{i+a, j+b}|; 0 when nothing is free.
//! `free` has the net's shape; a free point whose stencil leaves the net is skipped (a checked
//! problem has none: check_stencil_problem).
double mask_residual(const ControlNet& net, const FreeGrid& free, const Stencil& stencil);

}  // namespace coons
