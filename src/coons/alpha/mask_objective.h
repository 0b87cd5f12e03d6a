// The evaluator of the solve-based α search: for each parameter p of a mask family, one
// factorisation, two solves (the net N and its sensitivity dN/dp = A⁻¹·[dmask-weighted neighbour
// sums of N], docs/math.md §3) and the objective's exact value and derivative, in the normalised
// frame of the boundary (normalised_frame.h), reported in the caller's units.
// Sizes: the assembled matrix (when the backend needs one) and two #interior by 3 solves.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <Eigen/SparseCore>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "coons/alpha/normalised_frame.h"
#include "coons/alpha/objective.h"
#include "coons/mask/mask_families.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

using MaskFamily = std::function<MaskPoint(double)>;

//! Evaluates objective(net(p)) and its derivative, reusing the solver's analysis across p.
class MaskObjective {
 public:
  struct Evaluation {
    double parameter = 0;
    double value = 0, derivative = 0;
    double derivative_noise = 0;  //!< not estimated here
    bool has_derivative = false;  //!< the derivative was asked for and computed
    ControlNet net;
    solvers::SolveSummary summary;
    [[nodiscard]] bool ok() const { return summary.ok(); }
  };

  //! `solver` is a backend of the registry ("auto" is resolved by the caller).
  MaskObjective(const Boundary& boundary, Objective objective, MaskFamily family, const solvers::SolverInfo& solver,
                const solvers::SolverOptions& options = {});
  ~MaskObjective();

  //! One factorisation; one solve for the value, and one more for the derivative when asked
  //! (otherwise `derivative` is left 0).
  Evaluation evaluate(double parameter, bool with_derivative = true);

  //! The objective at an explicit mask and its gradient along several weight directions
  //! (one factorisation, 1 + #directions solves). Used by multi-parameter searches.
  Evaluation evaluate_mask(const Mask9& mask, const std::vector<Mask9>& directions, std::vector<double>& gradient);
  [[nodiscard]] int evaluations() const { return evaluations_; }
  [[nodiscard]] int solves() const { return solves_; }
  [[nodiscard]] const Boundary& boundary() const { return boundary_; }
  [[nodiscard]] const Objective& objective() const { return objective_; }
  //! The frame the evaluations are made in (normalised_frame.h); values, derivatives and nets
  //! are reported in the caller's units (value = value_factor · value in the frame).
  [[nodiscard]] const NormalisedFrame& unit_frame() const { return unit_; }

 private:
  Boundary boundary_;
  NormalisedFrame unit_;
  ControlNet frame_;  // the frame net of unit_.boundary
  Objective objective_;
  MaskFamily family_;
  bool needs_matrix_ = true;
  std::unique_ptr<solvers::LinearSolver> solver_;
  Eigen::SparseMatrix<double> A_;
  int evaluations_ = 0, solves_ = 0;
};

}  // namespace coons
