#include "stencil_family_objective.h"

#include <utility>

#include "coons/mask/mask9.h"
#include "coons/mask/near_singular.h"
#include "coons/mask/stencil.h"

namespace coons {

StencilFamily c1_weight_family() {
  return {[](double w) { return c1_family_stencil(w); },
          [](double w) { return Eigen::MatrixXd(c1_family_stencil_derivative(w)); },
          nullptr};  // definite for every w ∈ [0, 1]
}

StencilFamily alpha_stencil_family() {
  // W(±1, 0) = W(0, ±1) = −(1/4 − α), W(±1, ±1) = −α, centre 1: d/dα is +1 on the edges, −1 on
  // the diagonals, 0 at the centre
  Eigen::MatrixXd d(3, 3);
  d << -1, 1, -1, 1, 0, 1, -1, 1, -1;
  return {[](double a) { return alpha_stencil(alpha_mask(a)); }, [d](double) { return d; },
          [](double a) { return a >= -0.25 && a <= 0.25; }};
}

StencilFamilyObjective::StencilFamilyObjective(const StencilProblem& problem, const Objective& objective,
                                               const solvers::SolverInfo& solver, const solvers::SolverOptions& options,
                                               StencilFamily family)
    : problem_(problem), unit_(normalised_frame(boundary_of(problem.net), objective)), family_(std::move(family)) {
  // the whole net (both rings of data) moves into the frame of its outer boundary: exact, the
  // scale is a power of two
  problem_.net.points = (problem.net.points.rowwise() - unit_.centre) / unit_.scale;
  solver_ = solvers::make_solver(solver.name, options);
}

StencilFamilyObjective::~StencilFamilyObjective() = default;

StencilFamilyObjective::Evaluation StencilFamilyObjective::evaluate(double t, bool with_derivative) {
  ++evaluations_;
  Evaluation e;
  e.parameter = t;
  e.net = problem_.net;
  if (!solver_) {
    e.summary.status = solvers::SolveStatus::kNotApplicable;
    e.summary.message = "no such solver";
    e.net = unit_.to_original(std::move(e.net));
    return e;
  }
  e.summary.solver = solver_->name();
  const Stencil stencil = family_.stencil(t);
  const ControlNet zero(problem_.net.m, problem_.net.n);  // a variation of the free points only
  const Objective& objective = unit_.objective;
  const double k = unit_.value_factor;  // a power of two: exact
  if (!system_) {
    StencilAssemblyOptions assembly;
    assembly.box_pattern = true;  // one pattern, one analysis, for every t
    system_ = assemble_stencil_system(problem_, stencil, assembly);
  } else {
    refill_stencil_system(problem_, stencil, *system_);  // same radius, box pattern: cannot fail
  }
  const FreeNumbering& numbering = system_->numbering;
  ControlNet net = problem_.net;
  if (numbering.size() > 0) {
    solvers::LinearOperator op;
    op.matrix = &system_->A;
    if (analyses_ == 0) {
      ++analyses_;
      if (solver_->analyze(op) != solvers::SolveStatus::kSuccess) {
        e.summary = solver_->summary();
        e.net = unit_.to_original(std::move(e.net));
        return e;
      }
    }
    if (solver_->factorize(op) != solvers::SolveStatus::kSuccess) {
      e.summary = solver_->summary();
      e.net = unit_.to_original(std::move(e.net));
      return e;
    }
    if (family_.definite && !family_.definite(t))
      if (auto refused = near_singular_refusal(system_->A, *solver_, kNearSingularEigenvalueRatio, &solves_)) {
        e.summary = std::move(*refused);
        e.net = unit_.to_original(std::move(e.net));
        return e;
      }
    Eigen::MatrixX3d X;
    e.summary = solver_->solve(system_->B, X);
    ++solves_;
    if (!e.summary.ok()) {
      e.net = unit_.to_original(std::move(e.net));
      return e;
    }
    net = fill_free_points(std::move(net), numbering, X);
  }
  e.value = k * evaluate_objective(objective, net, zero).value;
  if (with_derivative) {
    ControlNet dN = zero;
    if (numbering.size() > 0) {
      Eigen::MatrixX3d dX;
      const solvers::SolveSummary ds =
          solver_->solve(stencil_sensitivity_rhs(net, numbering, family_.derivative(t)), dX);
      ++solves_;
      if (!ds.ok()) {
        e.summary = ds;
        e.net = unit_.to_original(std::move(net));
        return e;
      }
      dN = fill_free_points(std::move(dN), numbering, dX);
    }
    e.derivative = k * evaluate_objective(objective, net, dN).derivative;
    e.has_derivative = true;
  }
  e.net = unit_.to_original(std::move(net));
  return e;
}

}  // namespace coons
