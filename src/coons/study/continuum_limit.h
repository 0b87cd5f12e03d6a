// The continuum problem behind the μ masks, solved without them (the Ritz method): for a boundary
// of degree (N, N), the minimiser p_μ of ∫∫‖p_uv‖² + μ∫∫‖∇p‖² over all polynomial surfaces of
// degree (N, N) with these boundary curves, then the μ that minimises an exact energy of p_μ
// (thin plate, E3: any Σ weight·E(a, b)). p = p₀ + Σ c_kl φ_k(u) φ_l(v), p₀ the bilinearly
// blended Coons patch of the boundary, φ_k (k = 2..N) the integrated Legendre polynomials, which
// vanish at 0 and 1 and whose derivatives are orthogonal: the 1-D stiffness K is diagonal and the
// mass M well conditioned, so degree 40 is no harder than degree 4 (a Bernstein basis would not
// be: its Gram matrices' condition grows like 4^N). With K V = M V Λ, VᵀMV = I, every μ costs one
// change of basis: (VᵀCV)_kl = −(VᵀRV)_kl / (λ_kλ_l + μ(λ_k + λ_l)) per coordinate (#N−1 by N−1).
// Integrals by Gauss–Legendre with N + 2 nodes (exact for these degrees).
// Based on: W. Ritz, Über eine neue Methode zur Lösung gewisser Variationsprobleme, J. reine angew.
// Math. 135 (1909); Ch. Schwab, p- and hp-Finite Element Methods (1998), §3.1 (integrated Legendre
// shape functions); R. P. Brent, Algorithms for Minimization without Derivatives (1973).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"

namespace coons {

//! The Ritz minimisers p_μ of one boundary of degree (N, N), N ≥ 2 (the boundary fixes the space).
class ContinuumProblem {
 public:
  explicit ContinuumProblem(const Boundary& boundary);

  [[nodiscard]] int degree() const { return degree_; }
  //! Σ weight·∫∫‖∂^a_u ∂^b_v p_μ‖² for the given terms (exact).
  [[nodiscard]] double energy(double mu, const std::vector<EnergyTerm>& terms) const;
  //! p_μ(u, v).
  [[nodiscard]] Eigen::RowVector3d evaluate(double mu, double u, double v) const;
  //! The squared diagonal of the boundary's bounding box: the size of an energy of order one
  //! (an energy far below it is rounding, not shape).
  [[nodiscard]] double energy_scale() const { return scale_; }

 private:
  //! coefficients c_kl of each coordinate (#N−1 by N−1)
  [[nodiscard]] std::vector<Eigen::MatrixXd> coefficients(double mu) const;

  int degree_ = 0;
  Eigen::VectorXd nodes_, weights_;
  std::vector<Eigen::MatrixXd> phi_;                //!< phi_[r](k, q) = φ_k^(r)(node q), r = 0..3
  std::vector<std::vector<Eigen::MatrixXd>> base_;  //!< base_[c][a*4+b] = ∂^a_u ∂^b_v p₀ at the nodes
  Eigen::MatrixXd V_;                               //!< K V = M V Λ
  Eigen::VectorXd lambda_;
  std::vector<Eigen::MatrixXd> twist_rhs_, dirichlet_rhs_;  //!< VᵀRV per coordinate
  ControlNet coons_;                                        //!< p₀
  double scale_ = 0;
};

struct ContinuumOptions {
  double mu_lower = 1e-3, mu_upper = 1e6;  //!< searched on a log scale; μ = 0 is checked as well
  int scan_points = 37;                    //!< log grid before Brent
  //! flat in μ when the energy's range is below this times max(|energy|, w·energy_scale()), w the
  //! largest weight of the terms
  double flat_tolerance = 1e-10;

  bool is_valid(std::string* why) const;
};

//! kSuccess: an interior optimum; kFlat: the energy does not depend on μ; kAtBound: the least
//! energy is at μ = 0 or at the upper bound (no interior optimum claimed).
enum class ContinuumStatus { kSuccess, kFlat, kAtBound };
const char* to_string(ContinuumStatus status);  //!< "success", "flat", "at_bound"

struct ContinuumOptimum {
  ContinuumStatus status = ContinuumStatus::kSuccess;
  int degree = 0;                               //!< N of the Ritz space
  std::optional<double> mu;                     //!< absent unless kSuccess
  double value = 0;                             //!< the energy at the optimum (or at the best scan point)
  std::vector<std::pair<double, double>> scan;  //!< (μ, energy), μ = 0 first
};

//! min over μ of energy(p_μ; terms): a log-scale scan, then Brent on log μ inside the bracket.
ContinuumOptimum continuum_optimum(const ContinuumProblem& problem, const std::vector<EnergyTerm>& terms,
                                   const ContinuumOptions& options = {});

//! A mask parameter from the exact energies: the μ for which the net is most nearly stationary for
//! the exact ∫∫‖p_uv‖² + μ∫∫‖∇p‖² over its interior control points, μ = −⟨g_tw, g_D⟩/⟨g_D, g_D⟩
//! (g the exact gradients with respect to the interior points; least squares in μ). nullopt when
//! g_D vanishes (a net stationary for the Dirichlet energy).
std::optional<double> exact_energy_mu(const ControlNet& net);

}  // namespace coons
