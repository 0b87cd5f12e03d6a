#include "solve_mask_net.h"

#include <utility>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"

namespace coons {

MaskSolveResult solve_mask_net(const Boundary& boundary, const Mask9& mask, const solvers::SolverInfo& solver,
                               const solvers::SolverOptions& options) {
  MaskSolveResult result;
  ControlNet frame = frame_net(boundary);
  const solvers::SolverInfo* info = &solver;
  auto backend = solvers::make_solver(solver.name, options);
  if (!info || !backend) {
    result.net = frame;
    result.summary.solver = solver.name;
    result.summary.status = solvers::SolveStatus::kNotApplicable;
    result.summary.message = "no solver named '" + solver.name + "' is built in";
    result.summary.relative_residual = 1;  // of X = 0, what a failed solve returns (docs/formats.md)
    return result;
  }
  const MaskSystem system = assemble_mask_system(frame, mask, info->needs_matrix);
  if (system.B.rows() == 0) {  // m or n = 1: nothing to solve
    result.net = frame;
    result.summary.solver = solver.name;
    return result;
  }
  solvers::LinearOperator op;
  if (info->needs_matrix) op.matrix = &system.A;
  op.stencil = system.stencil;
  Eigen::MatrixX3d X;
  result.summary = backend->compute_and_solve(op, system.B, X);
  result.net = result.summary.ok() ? fill_interior(std::move(frame), X) : std::move(frame);
  return result;
}

}  // namespace coons
