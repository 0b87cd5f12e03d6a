// The evaluator of the search over the C1 family's weight w (weight_search.h): for each w, the
// net N(w) solved by c1_family_stencil(w) on a stencil problem with two data rings, the
// objective's exact value E(N(w)) and its derivative dE/dw = ∇E(N)·dN/dw, where dN/dw comes from
// one more solve with the same factorisation: A(w)·dN/dw = −(dW_w/dw ⋆ N) at the free points
// (stencil_system.h: stencil_sensitivity_rhs). The system is assembled once with the box pattern
// (every w shares it): one symbolic analysis for every evaluation, then per w a refill of the
// values, one factorisation and two solves. Evaluated in the normalised frame of the net's outer
// boundary (normalised_frame.h), reported in the caller's units.
// Sizes: the assembled matrix (#free by #free, 25 entries a row) and two #free by 3 solves.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700 (masks as
// energy minimisers); P. Salvi, quadfit (5×5 masks with two rings).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "coons/mask/stencil_problem.h"
#include "coons/mask/stencil_system.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

//! Evaluates objective(N(w)) and dobjective/dw for the C1 family, reusing one analysis across w.
class WeightObjective {
 public:
  struct Evaluation {
    double parameter = 0;  //!< w
    double value = 0, derivative = 0;
    double derivative_noise = 0;  //!< not estimated here
    bool has_derivative = false;  //!< the derivative was asked for and computed
    ControlNet net;               //!< N(w), the data with the solved free points
    solvers::SolveSummary summary;
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };

  //! `solver` is a backend of the registry that works from the matrix. Precondition: the problem
  //! fits the 5×5 stencil (check_stencil_problem with c1_family_stencil has no issue; search_weight
  //! checks it and refuses otherwise).
  WeightObjective(const StencilProblem& problem, const Objective& objective, const solvers::SolverInfo& solver,
                  const solvers::SolverOptions& options = {});
  ~WeightObjective();
  WeightObjective(const WeightObjective&) = delete;
  WeightObjective& operator=(const WeightObjective&) = delete;

  //! One refill and factorisation; one solve for the value, one more for the derivative when
  //! asked (otherwise `derivative` is left 0).
  Evaluation evaluate(double w, bool with_derivative = true);

  [[nodiscard]] int evaluations() const { return evaluations_; }
  [[nodiscard]] int solves() const { return solves_; }
  //! Symbolic analyses made (1 after the first evaluation with free points, and it stays 1).
  [[nodiscard]] int analyses() const { return analyses_; }
  //! The frame the evaluations are made in; value = value_factor · value in the frame.
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return unit_; }

 private:
  StencilProblem problem_;  // in the frame
  NormalisedFrame unit_;
  std::unique_ptr<solvers::LinearSolver> solver_;
  std::optional<StencilSystem> system_;
  int evaluations_ = 0, solves_ = 0, analyses_ = 0;
};

}  // namespace coons
