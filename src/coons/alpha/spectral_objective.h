// The α family with any objective (discrete or exact energies, targets), evaluated in the sine
// basis that diagonalises every mask of the family: f(α), f'(α) and f''(α) cost no solve at all.
// Measured from the discrete Coons net N_C: N(α) = N_C + δ with δ̂ = (α + 1/4)·R̂/λ(α) per mode
// (R: the 5-point Laplacian of N_C, λ = 1 − 2β(x+y) − 4αxy), and a quadratic objective is
//   f(N_C + δ) = f(N_C) + 2ĉ·δ̂ + δ̂ᵀQ̂δ̂,   c = ∇f(N_C)/2.
// - Discrete energies: Q̂ is diagonal (symbols (2−2x)(2−2y), (2−2x)+(2−2y), …), so after 1-D
//   transforms of the sides an evaluation is one pass over the modes. R and c are sums of four
//   separable grids (N_C is a boolean sum of linear blends): the set-up needs no 2-D transform.
// - Exact energies and a target net: Q̂ is a sum of dense Kronecker products.
// - An analytic target: measured on the surface sampled from the modes (see the constructor).
// Units: spectral_objective.cpp (the set-up), spectral_evaluation.cpp (f, f', f'' at one α),
// spectral_quadratic.cpp (the Kronecker quadratics), spectral_modes.* (the per-mode loops and the
// named column blocks of the factors).
// On a 1023×1023 net a discrete-objective search costs about 4 solves, its optimal net included
// (experiments/E03_solver_scaling).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) (the eigenvectors of the
// mask family); R. W. Hockney, J. ACM 12 (1965) (sine-transform solvers).
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

class SpectralAlphaObjective {
 public:
  struct Value {
    double value = 0, derivative = 0, second_derivative = 0;
    double derivative_noise = 0;  //!< the rounding error of `derivative` (an estimate)
    bool ok = false;              //!< false when λ(α) vanishes for a mode (a singular α)
  };

  //! The objective's terms:
  //! - discrete energies: diagonal in the sine basis, one pass over the modes;
  //! - exact energies of the surface (Σ weight·∫‖∂^a_u ∂^b_v p‖²), whose Hessians K_a ⊗ K_b
  //!   (K_a = D_aᵀ G D_a, Bernstein Gram G) are dense in the sine basis: four
  //!   (rows×rows)(rows×cols)(cols×cols) products per term and coordinate per evaluation, as
  //!   evaluating the energy of a net costs, but still no solve;
  //! - the rms distance to a target net: its mean square is quadratic in the net with Hessian
  //!   (B_uᵀB_u ⊗ B_vᵀB_v)/k², B_u the Bernstein values at the k samples, so it is handled as the
  //!   exact energies are, then square-rooted;
  //! - the rms distance to an analytic target (sphere, cylinder, plane): the sampled surface is
  //!   S_C + P·Û·Qᵀ per coordinate (P = B_u S, Q = B_v S, Û = u∘R̂), two small products per
  //!   evaluation, then the distance, its gradient and Hessian at each sample.
  //! Precondition: m, n ≥ 2 and supports(objective).
  SpectralAlphaObjective(const Boundary& boundary, const Objective& objective);
  //! At least one term, and the target set when the objective uses one.
  static bool supports(const Objective& objective);

  [[nodiscard]] Value evaluate(double alpha) const;
  [[nodiscard]] int rows() const { return rows_; }
  [[nodiscard]] int cols() const { return cols_; }

 private:
  int rows_, cols_;
  double e0_ = 0;
  Eigen::VectorXd xi_, eta_;   // 1 − cos(pπ/(rows+1)), 1 − cos(qπ/(cols+1))
  Eigen::ArrayXd quad_, lin_;  // per mode: symbol·Σ_xyz R̂², 2·Σ_xyz ĉ·R̂ (discrete terms)
  //! S K_a S (rows × rows) and S K_b S (cols × cols) at the interior, held by the parity of the
  //! modes: a[p] couples the modes p, p + 2, p + 4, … (K is persymmetric, so the entries between
  //! the sine modes of different parity vanish; products of half size cost a quarter).
  struct KroneckerTerm {
    std::array<Eigen::MatrixXd, 2> a, b;
    double weight = 0;
  };
  //! q(N_C + δ) = constant + 2⟨ĉ, δ̂⟩ + Σ w⟨δ̂, K̂_a δ̂ K̂_b⟩, summed over x, y, z.
  struct Quadratic {
    double constant = 0;
    std::array<Eigen::MatrixXd, 3> c_hat;  // rows × cols (std::array: clang-tidy 14 misreads a C array member)
    double c_scale = 0;                    // ĉ's rounding error is about ε times this
    std::vector<KroneckerTerm> terms;
  };
  Quadratic exact_;  // the exact energies
  double target_weight_ = 0;
  Eigen::MatrixXd r_hat_[3];          // R̂ per coordinate (rows × cols), for the two above
  std::optional<Target> target_;      // the target, measured at its samples:
  Eigen::MatrixXd p_, q_;             //   B_u S (k × rows) and B_v S (k × cols)
  Eigen::MatrixXd coons_samples_[3];  //   the Coons net's surface at the samples (k × k), for a
                                      //   target net minus the target's surface there
  Quadratic exact_energies(const ControlNet& coons, const std::vector<EnergyTerm>& exact, const Eigen::MatrixXd (&A)[3],
                           const Eigen::MatrixXd (&B)[3]) const;
  //! The mean square distance to target_ and its first two derivatives, and the rounding error
  //! of the first, at U[c][r] = u^(r)∘R̂_c, from the differences at the samples themselves (the
  //! expansion ‖D_C‖² + 2⟨ĉ, δ̂⟩ + ⟨δ̂, Kδ̂⟩ of a target net lost q to cancellation below about
  //! ε‖D_C‖²: α* recovered from a net came out 1.7e-8 off with the value 0).
  std::array<double, 4> target_sums(const Eigen::MatrixXd (&U)[3][3]) const;
};

//! SpectralAlphaObjective with the interface search_mask_parameter expects (and no net).
class SpectralAlphaSearchObjective {
 public:
  struct Evaluation {
    double parameter = 0, value = 0, derivative = 0, second_derivative = 0;
    double derivative_noise = 0;    //!< |derivative| below this is zero within rounding
    bool has_derivative = true;     //!< always: the derivatives cost nothing extra
    solvers::SolveSummary summary;  //!< status singular when λ vanishes at this α
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };
  //! Precondition: SpectralAlphaObjective::supports(objective); m, n ≥ 2. Evaluates in the
  //! normalised frame (normalised_frame.h); values are reported in the caller's units.
  SpectralAlphaSearchObjective(const Boundary& boundary, Objective objective);
  Evaluation evaluate(double alpha, bool with_derivative = true);
  [[nodiscard]] const Boundary& boundary() const { return boundary_; }
  [[nodiscard]] const Objective& objective() const { return objective_; }
  //! The frame the evaluations are made in (value = value_factor · value in the frame).
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return unit_; }
  [[nodiscard]] int evaluations() const { return evaluations_; }
  [[nodiscard]] int solves() const { return 0; }
  //! Where the family's scale collapses: the search measures distances from α = −1/4 on a log
  //! scale (α* + 1/4 ≈ c/n², docs/math.md §4).
  [[nodiscard]] static double scale_origin() { return -0.25; }

 private:
  Boundary boundary_;
  Objective objective_;
  NormalisedFrame unit_;
  SpectralAlphaObjective spectral_;
  int evaluations_ = 0;
};

}  // namespace coons
