#include "centred_solve.h"

#include <cmath>
#include <string>

#include "solvers/registry.h"

namespace coons {

void finish_centred_solve(solvers::LinearSolver& solver, const solvers::LinearOperator& op,
                          const std::function<Eigen::MatrixX3d()>& given_rhs, const Eigen::RowVector3d& centre,
                          Eigen::MatrixX3d& X, solvers::SolveSummary& summary) {
  if (!summary.ok()) return;
  X.rowwise() += centre;
  if (centre.isZero(0) || X.rows() == 0) return;
  const Eigen::MatrixX3d B = given_rhs();
  double r = solvers::relative_residual(op, B, X);
  const double tolerance = solver.options().tolerance;
  // Only the iterative backends stop at the tolerance; the exact ones' residuals (1e-10 for
  // c1-coons at N = 1023) stay as they are: refined, an ill-conditioned net lost digits.
  const solvers::SolverInfo* info = solvers::find_solver(solver.name());
  const bool iterative = info && info->family == solvers::SolverFamily::kIterative;
  constexpr int kRounds = 2;
  for (int round = 0; iterative && round < kRounds && std::isfinite(r) && r > tolerance; ++round) {
    Eigen::MatrixXd AX;
    if (!solvers::apply_operator(op, X, AX)) break;
    const Eigen::MatrixX3d R = B - AX;
    Eigen::MatrixX3d D;
    const solvers::SolveSummary correction = solver.solve(R, D);
    if (!correction.ok() || !D.allFinite()) break;
    const Eigen::MatrixX3d refined = X + D;
    const double next = solvers::relative_residual(op, B, refined);
    if (!(next < r)) break;
    summary.iterations += correction.iterations;
    X = refined;
    r = next;
  }
  summary.relative_residual = r;
  if (iterative && r > tolerance) {
    summary.status = solvers::SolveStatus::kNotConverged;
    summary.message =
        "the system moved to the data's centre was solved, but the system as given has relative "
        "residual " +
        solvers::format_g(r) + ", above the tolerance " + solvers::format_g(tolerance) +
        " (after up to two refinement rounds)";
  }
}

}  // namespace coons
