// Closed-form Coons nets: Boolean sums of two ruled nets minus the bilinear net of the corners.
//
//   b[i][j] = w_v[j] b[i][0] + (1−w_v[j]) b[i][n] + w_u[i] b[0][j] + (1−w_u[i]) b[m][j]
//             − Σ corners (products of the weights)
//
// discrete_coons_net:  w_u[i] = 1 − i/m (docs/math.md §2). Its Bézier surface is the bilinearly
//                      blended Coons patch of the four boundary curves; it solves the α = −1/4 mask.
//   Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700; LN3.
// hermite_coons_net:   w_u[i] = η_i, the degree-m Bernstein coefficients of F₀(t) = 1 − 3t² + 2t³
//                      (docs/math.md §6); its surface is the partially bicubic (Hermite-blended) Coons
//                      patch. Needs m, n ≥ 3.
//   Based on: S. A. Coons, Surfaces for computer-aided design of space forms, MIT MAC-TR-41 (1967).
// Both cost O(mn) and touch each output point once.
#pragma once

#include <vector>

#include "control_net.h"

namespace coons {

//! The Boolean-sum net for blend weights w_u (#m+1, weight of the left side) and w_v (#n+1,
//! weight of the bottom side). Corners are taken from bottom and top.
ControlNet boolean_sum_net(const Boundary& boundary, const std::vector<double>& w_u, const std::vector<double>& w_v);

//! Linear blend weights 1 − i/k, i = 0..k.
std::vector<double> linear_blend_weights(int k);

//! Bernstein coefficients of F₀(t) = 1 − 3t² + 2t³ at degree k ≥ 3, i = 0..k.
std::vector<double> hermite_blend_weights(int k);

ControlNet discrete_coons_net(const Boundary& boundary);

//! Precondition: boundary.m ≥ 3 and boundary.n ≥ 3.
ControlNet hermite_coons_net(const Boundary& boundary);

}  // namespace coons
