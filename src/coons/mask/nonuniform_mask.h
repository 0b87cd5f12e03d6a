// The non-uniform 3×3 mask family of a B-spline net (docs/math.md §10): the index differences of
// the α family replaced by second divided differences over the Greville abscissae ξ_i (u) and
// η_j (v), each scaled so that it is the plain second difference when the abscissae are equally
// spaced:
//   D_ξ f_i = (2/m²) f[ξ_{i−1}, ξ_i, ξ_{i+1}],   D_η likewise with n,
//   L_α b_ij = −α D_ξ D_η b_ij − (α + 1/4)(D_ξ + D_η) b_ij = 0 at every interior point.
// α = −1/4: D_ξ D_η b = 0, solved by the Greville-weighted discrete Coons net; α = 0: the
// non-uniform Laplace analogue. On equally spaced abscissae L_α b = b − αK − (1/4 − α)E, the
// mask family of docs/math.md §3. Sizes: the net (m+1)×(n+1), ξ #m+1 and η #n+1 (strictly
// increasing), #interior = (m−1)(n−1) unknowns numbered as in assemble_mask_system.h.
// The system is assembled with row (i, j) scaled by ρ_ij = (m s_i/2)(n t_j/2), s_i = ξ_{i+1} − ξ_{i−1},
// t_j = η_{j+1} − η_{j−1} (1 when equally spaced), which makes the matrix symmetric; it is positive
// definite for α ∈ [−1/4, 0].
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) (the uniform family).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

//! The abscissae of both directions; valid when each runs strictly increasing from ξ_0 to ξ_m.
struct GrevilleGrid {
  Eigen::VectorXd xi;   //!< #m+1
  Eigen::VectorXd eta;  //!< #n+1
  [[nodiscard]] int m() const { return int(xi.size()) - 1; }
  [[nodiscard]] int n() const { return int(eta.size()) - 1; }
  //! At least two abscissae per direction, finite and strictly increasing; else the reason in *why.
  bool is_valid(std::string* why) const;
};

//! The weights of L_α at interior point (i, j) without the row scaling: w(k + 1, l + 1) multiplies
//! b_{i+k, j+l}, k, l ∈ {−1, 0, 1}. The entries sum to 0 (affine invariance).
Eigen::Matrix3d nonuniform_mask_weights(const GrevilleGrid& grid, double alpha, int i, int j);

struct NonUniformMaskSystem {
  Eigen::SparseMatrix<double> A;  //!< #interior square, symmetric (the rows scaled by ρ_ij)
  Eigen::MatrixX3d B;             //!< #interior by 3: −ρ_ij Σ (weights of frame points)·(points)
  //! ∂A/∂α and ∂B/∂α (both are affine in α): the sensitivity A dX/dα = dB − dA X.
  Eigen::SparseMatrix<double> dA;
  Eigen::MatrixX3d dB;
};

//! The system of the frame of `net` (its interior is ignored); net.m, net.n must match the grid.
NonUniformMaskSystem assemble_nonuniform_mask_system(const ControlNet& net, const GrevilleGrid& grid, double alpha);

struct NonUniformSolveResult {
  ControlNet net;  //!< frame of the input, interior solved (zero interior when the solve failed)
  solvers::SolveSummary summary;
  //! dnet/dα (zero frame), filled only when asked for and the solve succeeded (one more solve
  //! with the same factorisation).
  ControlNet derivative;
  //! Linear solves made with the factorisation: the near-singular estimate's (outside
  //! [−1/4, 0]), the net's and the derivative's.
  int solves = 0;
};

//! Solves L_α b = 0 for the interior with `solver` (any backend that takes an assembled matrix).
//! Outside α ∈ [−1/4, 0], where the system need not be definite, a positive `refused_ratio` first
//! estimates min|λ|/max|λ| with the factorisation (estimate_eigenvalue_ratio, near_singular.h);
//! at or below `refused_ratio` nothing is solved: status singular, the ratio in the message.
NonUniformSolveResult solve_nonuniform_mask_net(const ControlNet& frame, const GrevilleGrid& grid, double alpha,
                                                solvers::LinearSolver& solver, bool with_derivative = false,
                                                double refused_ratio = 0);

//! max over interior points and x, y, z of |L_α b_ij| with each equation's weights divided by the
//! largest of their magnitudes (on equal spacing, for |α| ≤ 1/2, the mask residual of mask_residual.h,
//! whose centre weight 1 is then the largest).
double nonuniform_mask_residual(const ControlNet& net, const GrevilleGrid& grid, double alpha);

}  // namespace coons
