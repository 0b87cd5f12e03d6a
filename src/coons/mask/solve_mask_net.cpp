#include "solve_mask_net.h"

#include <cmath>
#include <utility>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/centred_solve.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
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
  // A mask that reproduces constants is solved for the boundary moved to its centre and the
  // interior moved back: the net does not depend on where the boundary lies, its digits do (a net
  // at 1e12 kept 4 of them, and cg reported success 24 % of the shape off).
  // (the centre of the data the mask couples to the interior: stencil_problem.h)
  const Eigen::RowVector3d centre = mask.reproduces_constants()
                                        ? data_centre(rings_problem(frame, 1), {alpha_stencil(mask)})
                                        : Eigen::RowVector3d::Zero();
  ControlNet centred = frame;
  for (Eigen::Index k = 0; k < centred.points.rows(); ++k) centred.points.row(k) -= centre;
  const MaskSystem system = assemble_mask_system(centred, mask, info->needs_matrix);
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
  finish_centred_solve(
      *backend, op, [&] { return mask_rhs(frame, mask); }, weight_sum(alpha_stencil(mask).weights), centre, X,
      result.summary);
  result.net = result.summary.ok() ? fill_interior(std::move(frame), X) : std::move(frame);
  return result;
}

}  // namespace coons
