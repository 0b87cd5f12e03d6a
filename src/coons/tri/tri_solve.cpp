#include "coons/tri/tri_solve.h"

#include <Eigen/SparseCore>
#include <utility>

#include "coons/mask/near_singular.h"

namespace coons::tri {

TriBackendCheck check_tri_backend(const solvers::SolverInfo& info, const TriMask& mask) {
  if (!solvers::accepts_matrix(info))
    return {false, info.name + " works on the rectangular grid stencil only, not on triangular systems"};
  if (info.definite_only && mask.c != 0.0)
    return {false, info.name +
                       " is only for symmetric positive definite systems; the triangular "
                       "mask system is not symmetric for c != 0"};
  return {true, {}};
}

std::vector<std::string> tri_applicable_solvers(const TriMask& mask) {
  std::vector<std::string> names;
  for (const auto& info : solvers::available_solvers())
    if (check_tri_backend(info, mask).applicable) names.push_back(info.name);
  return names;
}

bool TriSolveOptions::is_valid(std::string* why) const {
  if (!mask.is_valid(why) || !solver_options.is_valid(why)) return false;
  if (!solver) {
    if (why) *why = "no solver backend given";
    return false;
  }
  return true;
}

const solvers::SolverInfo& default_tri_solver() {
  const solvers::SolverInfo* info = solvers::find_solver("umfpack");
  if (!info) info = solvers::find_solver("eigen-lu");
  return *info;  // eigen-lu is always built
}

bool in_regular_c_range(int n, const TriMask& mask) {
  const std::optional<double> star = bubble_singular_c(n);
  return (!star || mask.c > *star) && mask.c <= 1.0 / 3.0;
}

solvers::SolveSummary solve_tri_system(const TriMaskSystem& sys, solvers::LinearSolver& solver, Eigen::MatrixX3d& X) {
  solvers::LinearOperator op;
  op.matrix = &sys.A;
  X = Eigen::MatrixX3d::Zero(sys.B.rows(), 3);
  // Every member is checked, inside the regular range too: c*ₙ + 3.3e-10 at n = 6 (min|λ|/‖A‖₁
  // about 1.0e-10) came back `success` with a net 4.7e-7 off and coordinates of 5e8, while
  // c*ₙ − 1e-8 (2.1e-9) was refused as singular.
  const double unsolved = sys.B.isZero(0) ? 0 : 1;  // the relative residual of X = 0
  if (solver.analyze(op) != solvers::SolveStatus::kSuccess || solver.factorize(op) != solvers::SolveStatus::kSuccess) {
    solvers::SolveSummary failed = solver.summary();
    failed.relative_residual = unsolved;
    return failed;
  }
  if (auto refused = near_singular_refusal(sys.A, solver, kNearSingularEigenvalueRatio)) {
    refused->relative_residual = unsolved;
    return *refused;
  }
  return solver.solve(sys.B, X);
}

TriSolveResult solve_tri_net(const TriNet& frame, const TriSolveOptions& options) {
  TriSolveResult result{frame, {}};
  result.summary.solver = options.solver ? options.solver->name : std::string();
  std::string why;
  if (!options.is_valid(&why)) {
    result.summary.status = solvers::SolveStatus::kFailure;
    result.summary.message = why;
    result.summary.relative_residual = 1;  // of X = 0, what a failed solve returns (docs/formats.md)
    return result;
  }
  const TriBackendCheck check = check_tri_backend(*options.solver, options.mask);
  if (!check.applicable) {
    result.summary.status = solvers::SolveStatus::kNotApplicable;
    result.summary.message = check.reason;
    result.summary.relative_residual = 1;
    return result;
  }
  if (interior_size(frame.n) == 0) return result;  // nothing to solve (n < 3)
  // solved about the boundary's centre (boundary_centre), the data kept bit for bit
  const Eigen::RowVector3d centre = boundary_centre(frame);
  TriNet centred = frame;
  centred.points.rowwise() -= centre;
  const TriMaskSystem sys = assemble_tri_mask_system(centred, options.mask);
  auto solver = solvers::make_solver(options.solver->name, options.solver_options);
  Eigen::MatrixX3d X;
  result.summary = solve_tri_system(sys, *solver, X);
  if (result.summary.ok()) result.net = fill_interior(std::move(result.net), X.rowwise() + centre);
  return result;
}

TriSolveResult solve_tri_net(const TriBoundary& boundary, const TriSolveOptions& options) {
  return solve_tri_net(frame_net(boundary), options);
}

}  // namespace coons::tri
