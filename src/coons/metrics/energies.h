// Exact energies of the Bézier surface of a net, by Bernstein Gram matrices (docs/math.md §5):
//   E(a,b) = ∫∫ ‖∂^a_u ∂^b_v p‖² = Σ_xyz tr(Cᵀ G^{m−a} C G^{n−b}),  C the derivative net.
// twist = E(1,1); Dirichlet = E(1,0) + E(0,1); thin plate = E(2,0) + 2E(1,1) + E(0,2);
// E3 = E(3,0) + 3E(2,1) + 3E(1,2) + E(0,3) (linearised curvature variation).
// Based on: H. P. Moreton, C. H. Séquin, Functional optimization for fair surface design,
// SIGGRAPH 1992; G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999).
#pragma once

#include <vector>

#include "coons/mask/mask9.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"

namespace coons {

//! E(a, b); 0 when a > m or b > n. The energies of one net here (E(a, b) and every sum of them with
//! weights ≥ 0) are never below 0 by rounding: a negative value within the rounding bound of its
//! computation is returned as 0 (clamp_rounding_negative). The forms of two nets are not clamped.
double surface_energy(const ControlNet& net, int a, int b);

//! `value`, or 0 where it is negative by no more than `rounding_bound`: for a quantity that is ≥ 0
//! in exact arithmetic (a sum of squares) which rounding took below 0. A value further below 0 is
//! returned as it is, so that a wrong sign still shows.
double clamp_rounding_negative(double value, double rounding_bound);

//! The symmetric bilinear form of E(a, b): Σ_xyz tr(C_Xᵀ G C_Y G), so that
//! E(X + hY) = E(X) + 2h·form(X, Y) + h²E(Y). X and Y must have the same degree.
double surface_energy_form(const ControlNet& X, const ControlNet& Y, int a, int b);

//! The named energies of this header as weights of E(a, b): thin plate = {(2,0):1, (1,1):2, (0,2):1}.
struct EnergyTerm {
  int a, b;
  double weight;
};
std::vector<EnergyTerm> twist_terms();
std::vector<EnergyTerm> dirichlet_terms();
std::vector<EnergyTerm> thin_plate_terms();
std::vector<EnergyTerm> e3_terms();

//! Σ weight·E(a, b), and Σ weight·form(X, Y; a, b).
double combined_energy(const ControlNet& net, const std::vector<EnergyTerm>& terms);
double combined_energy_form(const ControlNet& X, const ControlNet& Y, const std::vector<EnergyTerm>& terms);

double twist_energy(const ControlNet& net);
double dirichlet_energy(const ControlNet& net);
double thin_plate_energy(const ControlNet& net);
double e3_energy(const ControlNet& net);

//! Σ_{i<m, j<n} ‖b_{i+1,j+1} − b_{i+1,j} − b_{i,j+1} + b_ij‖².
double discrete_twist_energy(const ControlNet& net);
//! Σ‖b_{i+1,j} − b_ij‖² + Σ‖b_{i,j+1} − b_ij‖².
double discrete_dirichlet_energy(const ControlNet& net);
//! Σ‖Δ²_i b‖² + 2Σ‖Δ_iΔ_j b‖² + Σ‖Δ²_j b‖²: the thin-plate energy of the net itself (O(mn), for
//! nets too large for the exact energies).
double discrete_thin_plate_energy(const ControlNet& net);

//! The discrete energies as symmetric bilinear forms (E(X + hY) = E(X) + 2h·form(X, Y) + h²E(Y)).
enum class DiscreteEnergy { kTwist, kDirichlet, kThinPlate };
double discrete_energy_form(const ControlNet& X, const ControlNet& Y, DiscreteEnergy kind);

//! The same energies as Σ weight·‖Δ_i^a Δ_j^b b‖² over every whole-grid difference of orders
//! (a, b) ≤ 2 (thin plate: (2,0) + 2·(1,1) + (0,2)). Their Hessians are Kronecker products, which
//! the sine-basis and low-rank evaluations of the α search build on.
struct DifferenceTerm {
  int i_order = 0, j_order = 0;
  double weight = 1;
};
std::vector<DifferenceTerm> difference_terms(DiscreteEnergy kind);

//! ∂E/∂b of a discrete energy at `net`: a net of the same degree (boundary entries included).
ControlNet discrete_energy_gradient(const ControlNet& net, DiscreteEnergy kind);

//! Every metric of the `solve` report (docs/formats.md), computed once.
struct NetMetrics {
  double twist_energy = 0, thin_plate_energy = 0, dirichlet_energy = 0, e3_energy = 0;
  double discrete_twist_energy = 0, discrete_dirichlet_energy = 0, mask_residual = 0;
};
//! `threads` (0: every core) share out the Gram products of the exact energies (banded_gram.h):
//! the metrics are the same bit for bit for every count.
NetMetrics net_metrics(const ControlNet& net, const Mask9& mask, int threads = 1);
//! The same energies; mask_residual of `stencil` over the free points (mask_residual.h).
NetMetrics net_metrics(const ControlNet& net, const FreeGrid& free, const Stencil& stencil, int threads = 1);

}  // namespace coons
