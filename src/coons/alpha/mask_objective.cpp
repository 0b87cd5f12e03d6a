#include "mask_objective.h"

#include <algorithm>
#include <utility>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"

namespace coons {

MaskObjective::MaskObjective(const Boundary& boundary, Objective objective, MaskFamily family,
                             const solvers::SolverInfo& solver, const solvers::SolverOptions& options)
    : boundary_(boundary),
      unit_(normalised_frame(boundary, objective)),
      frame_(frame_net(unit_.boundary)),
      objective_(std::move(objective)),
      family_(std::move(family)) {
  needs_matrix_ = solver.needs_matrix;
  solver_ = solvers::make_solver(solver.name, options);
}

MaskObjective::~MaskObjective() = default;

MaskObjective::Evaluation MaskObjective::evaluate(double p, bool with_derivative) {
  const MaskPoint mp = family_(p);
  std::vector<double> gradient;
  Evaluation e =
      evaluate_mask(mp.mask, with_derivative ? std::vector<Mask9>{mp.derivative} : std::vector<Mask9>{}, gradient);
  e.parameter = p;
  e.derivative = gradient.empty() ? 0.0 : gradient[0];
  e.has_derivative = with_derivative && e.ok();
  return e;
}

MaskObjective::Evaluation MaskObjective::evaluate_mask(const Mask9& mask, const std::vector<Mask9>& directions,
                                                       std::vector<double>& gradient) {
  ++evaluations_;
  Evaluation e;
  e.net = frame_;
  gradient.assign(directions.size(), 0.0);
  if (!solver_) {
    e.summary.status = solvers::SolveStatus::kNotApplicable;
    e.summary.message = "no such solver";
    return e;
  }
  const int rows = std::max(frame_.m - 1, 0), cols = std::max(frame_.n - 1, 0);
  const ControlNet zero(frame_.m, frame_.n);  // the variation of a net with a fixed boundary
  const Objective& objective = unit_.objective;
  const double k = unit_.value_factor;  // a power of two: exact
  if (rows * cols == 0) {
    e.value = k * evaluate_objective(objective, e.net, zero).value;
    e.net = unit_.to_original(std::move(e.net));
    return e;
  }
  solvers::LinearOperator op;
  op.stencil = mask_stencil(mask, rows, cols);
  if (needs_matrix_) {
    if (A_.rows() == 0)
      A_ = solvers::stencil_matrix(*op.stencil);
    else
      solvers::refill_stencil_matrix(*op.stencil, A_);
    op.matrix = &A_;
  }
  if (solver_->factorize(op) != solvers::SolveStatus::kSuccess) {
    e.summary = solver_->summary();
    e.net = unit_.to_original(std::move(e.net));
    return e;
  }
  Eigen::MatrixX3d X, dX;
  e.summary = solver_->solve(mask_rhs(frame_, mask), X);
  ++solves_;
  if (!e.summary.ok()) {
    e.net = unit_.to_original(std::move(e.net));
    return e;
  }
  ControlNet net = fill_interior(frame_, X);
  e.value = k * evaluate_objective(objective, net, zero).value;
  for (size_t d = 0; d < directions.size(); ++d) {
    const solvers::SolveSummary ds = solver_->solve(mask_sensitivity_rhs(net, directions[d]), dX);
    ++solves_;
    if (!ds.ok()) {
      e.summary = ds;
      break;
    }
    gradient[d] = k * evaluate_objective(objective, net, fill_interior(zero, dX)).derivative;
  }
  e.net = unit_.to_original(std::move(net));
  return e;
}

}  // namespace coons
