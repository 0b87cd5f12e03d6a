// The evaluator of the searches over a one-parameter family of stencils on a stencil problem (any
// data rings, any free set; family_search.h): the C1 family's weight w (c1_family_stencil) or the
// 3×3 α family (alpha_stencil(alpha_mask(α))). For each parameter t, the net N(t) solved by the
// family's stencil W_t, the objective's exact value E(N(t)) and its derivative dE/dt = ∇E(N)·dN/dt,
// where dN/dt comes from one more solve with the same factorisation: A(t)·dN/dt = −(dW_t/dt ⋆ N)
// at the free points (stencil_system.h: stencil_sensitivity_rhs). The system is assembled once
// with the box pattern (every t shares it): one symbolic analysis for every evaluation, then per t
// a refill of the values, one factorisation and two solves. Evaluated in the normalised frame of
// the net's outer boundary (normalised_frame.h), reported in the caller's units.
// Outside the family's definite range (the α family beyond [−1/4, 1/4]) a near-singular system is
// a failed evaluation, never a value (near_singular.h).
// Sizes: the assembled matrix (#free by #free, 9 or 25 entries a row) and two #free by 3 solves.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700 (masks as
// energy minimisers); P. Salvi, quadfit (5×5 masks with two rings).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/mask/stencil_system.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

//! A one-parameter family of stencils of one radius: W_t and dW_t/dt (centre 0), and where its
//! systems are positive definite on every free set (absent: everywhere). Outside that, an
//! evaluation whose system is near-singular (near_singular.h) is refused.
struct StencilFamily {
  std::function<Stencil(double)> stencil;
  std::function<Eigen::MatrixXd(double)> derivative;
  std::function<bool(double)> definite;
};
//! The C1 family over its weight w ∈ [0, 1] (5×5).
StencilFamily c1_weight_family();
//! The 3×3 α family, β = 1/4 − α (Farin–Hansford's masks).
StencilFamily alpha_stencil_family();

//! Evaluates objective(N(t)) and dobjective/dt over a stencil family, reusing one analysis across t.
class StencilFamilyObjective {
 public:
  struct Evaluation {
    double parameter = 0;  //!< t
    double value = 0, derivative = 0;
    double derivative_noise = 0;  //!< not estimated here
    bool has_derivative = false;  //!< the derivative was asked for and computed
    ControlNet net;               //!< N(w), the data with the solved free points
    solvers::SolveSummary summary;
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };

  //! `solver` is a backend of the registry that works from the matrix. Precondition: the problem
  //! fits the family's stencil (check_stencil_problem has no issue; the searches of
  //! family_search.h check it and refuse otherwise).
  StencilFamilyObjective(const StencilProblem& problem, const Objective& objective, const solvers::SolverInfo& solver,
                         const solvers::SolverOptions& options = {}, StencilFamily family = c1_weight_family());
  ~StencilFamilyObjective();
  StencilFamilyObjective(const StencilFamilyObjective&) = delete;
  StencilFamilyObjective& operator=(const StencilFamilyObjective&) = delete;

  //! One refill and factorisation; one solve for the value, one more for the derivative when
  //! asked (otherwise `derivative` is left 0). Where the family is not definite at t, the
  //! factorisation first estimates min|λ|/max|λ| (estimate_eigenvalue_ratio, a few more solves);
  //! at or below kNearSingularEigenvalueRatio the evaluation fails (singular, near_singular_summary).
  Evaluation evaluate(double t, bool with_derivative = true);

  [[nodiscard]] int evaluations() const { return evaluations_; }
  [[nodiscard]] int solves() const { return solves_; }
  //! Symbolic analyses made (1 after the first evaluation with free points, and it stays 1).
  [[nodiscard]] int analyses() const { return analyses_; }
  //! The frame the evaluations are made in; value = value_factor · value in the frame.
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return unit_; }

 private:
  StencilProblem problem_;  // in the frame
  NormalisedFrame unit_;
  StencilFamily family_;
  std::unique_ptr<solvers::LinearSolver> solver_;
  std::optional<StencilSystem> system_;
  int evaluations_ = 0, solves_ = 0, analyses_ = 0;
};

}  // namespace coons
