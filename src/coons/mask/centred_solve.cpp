#include "centred_solve.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "solvers/registry.h"

namespace coons {

namespace {

// Per column: ‖b − A x‖ / ‖b‖ (‖b‖ = 0: ‖A x‖), and the rounding floor of that ratio, an estimate
// of the rounding of b − A x itself: 2ε·(W·‖x‖ + ‖b‖) / ‖b‖, W = Σ|w| ≥ ‖|A|‖₂ (the bound
// (non-zero weights + 1)·ε instead of 2ε is about ten times what rounding does). A smooth net's mask
// equations cancel: the dome at degree 80 has ‖B_z‖ = 0.0022 and a floor of 3e-11, above the
// default tolerance 1e-12, which the exact solvers' nets do not meet either (cholmod 2e-12).
struct ColumnResiduals {
  std::array<double, 3> relative{}, floor{};
  [[nodiscard]] double largest() const { return std::max({relative[0], relative[1], relative[2]}); }
  [[nodiscard]] bool within(double tolerance) const {
    for (int c = 0; c < 3; ++c)
      if (!(relative[c] <= std::max(tolerance, floor[c]))) return false;
    return true;
  }
};

bool residuals(const solvers::LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X,
               double weight_sum, ColumnResiduals& out) {
  Eigen::MatrixXd AX;
  if (!solvers::apply_operator(op, X, AX)) return false;
  const double eps = std::numeric_limits<double>::epsilon();
  for (int c = 0; c < 3; ++c) {
    const double r = (B.col(c) - AX.col(c)).stableNorm(), b = B.col(c).stableNorm();
    const double rounding = 2 * eps * (weight_sum * X.col(c).stableNorm() + b);
    out.relative[std::size_t(c)] = b > 0 ? r / b : r;
    out.floor[std::size_t(c)] = b > 0 ? rounding / b : rounding;
  }
  return std::isfinite(out.largest());
}

bool is_iterative(const std::string& backend) {
  const solvers::SolverInfo* info = solvers::find_solver(backend);
  return info && info->family == solvers::SolverFamily::kIterative;
}

// The verdict on the system as given: its residual reported; an iterative backend above the
// tolerance and the rounding floor ends not_converged, one within the floor keeps success.
void settle(const ColumnResiduals& r, double tolerance, bool iterative, solvers::SolveSummary& summary) {
  summary.relative_residual = r.largest();
  if (!iterative || r.largest() <= tolerance) return;
  double floor = 0;
  for (double f : r.floor) floor = std::max(floor, f);
  if (r.within(tolerance)) {
    summary.message = "the system as given has relative residual " + solvers::format_g(r.largest()) +
                      ", within its rounding floor " + solvers::format_g(floor) + " (tolerance " +
                      solvers::format_g(tolerance) + ")";
    return;
  }
  summary.status = solvers::SolveStatus::kNotConverged;
  summary.message =
      "the system moved to the data's centre was solved, but the system as given has relative "
      "residual " +
      solvers::format_g(r.largest()) + ", above the tolerance " + solvers::format_g(tolerance) +
      " and its rounding floor " + solvers::format_g(floor);
}

}  // namespace

void finish_centred_solve(solvers::LinearSolver& solver, const solvers::LinearOperator& op,
                          const std::function<Eigen::MatrixX3d()>& given_rhs, double weight_sum,
                          const Eigen::RowVector3d& centre, Eigen::MatrixX3d& X, solvers::SolveSummary& summary) {
  if (!summary.ok()) return;
  X.rowwise() += centre;
  if (centre.isZero(0) || X.rows() == 0) return;
  const Eigen::MatrixX3d B = given_rhs();
  ColumnResiduals r;
  if (!residuals(op, B, X, weight_sum, r)) return;
  const double tolerance = solver.options().tolerance;
  // Only the iterative backends stop at the tolerance; the exact ones' residuals (1e-10 for
  // c1-coons at N = 1023) stay as they are: refined, an ill-conditioned net lost digits.
  const bool iterative = is_iterative(solver.name());
  constexpr int kRounds = 2;
  int rounds = 0;
  std::string stopped;  // why a round was not taken (said in the message: it was silent)
  for (; iterative && rounds < kRounds && !r.within(tolerance); ++rounds) {
    Eigen::MatrixXd AX;
    if (!solvers::apply_operator(op, X, AX)) break;
    const Eigen::MatrixX3d R = B - AX;
    Eigen::MatrixX3d D;
    const solvers::SolveSummary correction = solver.solve(R, D);
    if (!correction.ok() || !D.allFinite()) {
      stopped = std::string("the correction solve of round ") + std::to_string(rounds + 1) + " ended " +
                solvers::to_string(correction.status);
      break;
    }
    const Eigen::MatrixX3d refined = X + D;
    ColumnResiduals next;
    if (!residuals(op, B, refined, weight_sum, next)) break;
    if (!(next.largest() < r.largest())) {
      stopped = "round " + std::to_string(rounds + 1) + " of refinement did not lower it (" +
                solvers::format_g(next.largest()) + ")";
      break;
    }
    summary.iterations += correction.iterations;
    X = refined;
    r = next;
  }
  settle(r, tolerance, iterative, summary);
  if (summary.status != solvers::SolveStatus::kNotConverged) return;
  if (rounds > 0)
    summary.message += " (after " + std::to_string(rounds) + " refinement round" + (rounds == 1 ? "" : "s") + ")";
  if (!stopped.empty()) summary.message += "; " + stopped;
}

void judge_centred_member(const std::string& backend, double tolerance, const solvers::LinearOperator& op,
                          const Eigen::MatrixX3d& given_rhs, double weight_sum, const Eigen::MatrixX3d& X,
                          solvers::SolveSummary& summary) {
  if (!summary.ok() || X.rows() == 0) return;
  ColumnResiduals r;
  if (residuals(op, given_rhs, X, weight_sum, r)) settle(r, tolerance, is_iterative(backend), summary);
}

double weight_sum(const Eigen::MatrixXd& weights) { return weights.cwiseAbs().sum(); }

}  // namespace coons
