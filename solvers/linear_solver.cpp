// LinearSolver's life cycle (analyze, factorize, solve), the names of its enums, its options'
// checks and the residual of an operator. The verdict on a solution is in solution_verdicts.cpp,
// sweeps of a family in linear_solver_sweep.cpp.
#include "linear_solver.h"

#if defined(_OPENMP)
#include <omp.h>
#endif
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <thread>

#include "linear_solver_steps.h"
#include "stencil_operator.h"

namespace coons::solvers {

using detail::kUnsolvedResidual;
using detail::return_zero_solution;
using detail::seconds_since;
using detail::solve_scaled;

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSuccess:
      return "success";
    case SolveStatus::kNotConverged:
      return "not_converged";
    case SolveStatus::kDiverged:
      return "diverged";
    case SolveStatus::kNotPositiveDefinite:
      return "not_positive_definite";
    case SolveStatus::kSingular:
      return "singular";
    case SolveStatus::kNotApplicable:
      return "not_applicable";
    case SolveStatus::kFailure:
      return "failure";
  }
  return "failure";
}

const char* to_string(Ordering ordering) {
  switch (ordering) {
    case Ordering::kAuto:
      return "auto";
    case Ordering::kNatural:
      return "natural";
    case Ordering::kAmd:
      return "amd";
    case Ordering::kColamd:
      return "colamd";
    case Ordering::kMetis:
      return "metis";
    case Ordering::kNestedDissection:
      return "nested-dissection";
    case Ordering::kCholmodDefault:
      return "cholmod-default";
  }
  return "auto";
}

const char* to_string(SolverOptionsField field) {
  switch (field) {
    case SolverOptionsField::kNone:
      return "";
    case SolverOptionsField::kTolerance:
      return "tolerance";
    case SolverOptionsField::kMaxIterations:
      return "max_iterations";
    case SolverOptionsField::kTimeLimitSeconds:
      return "time_limit_seconds";
    case SolverOptionsField::kSorOmega:
      return "sor_omega";
    case SolverOptionsField::kSingularResidual:
      return "singular_residual";
    case SolverOptionsField::kThreads:
      return "threads";
  }
  return "";
}

SolverOptionsProblem options_problem(const SolverOptions& o) {
  using F = SolverOptionsField;
  if (!(o.tolerance > 0 && o.tolerance < 1)) return {F::kTolerance, "must lie in (0, 1)"};
  if (o.max_iterations < 0) return {F::kMaxIterations, "must be >= 0"};
  if (!(o.time_limit_seconds >= 0) || !std::isfinite(o.time_limit_seconds))
    return {F::kTimeLimitSeconds, "must be finite and >= 0"};
  if (!(o.sor_omega > 0 && o.sor_omega < 2)) return {F::kSorOmega, "must lie in (0, 2)"};
  if (!(o.singular_residual > 0)) return {F::kSingularResidual, "must be positive"};
  if (o.threads < 0 || o.threads > kMaxThreads) return {F::kThreads, "must lie in 0 .. 256 (0: every core)"};
  return {};
}

bool SolverOptions::is_valid(std::string* why) const {
  const SolverOptionsProblem problem = options_problem(*this);
  if (problem.field == SolverOptionsField::kNone) return true;
  if (why) *why = std::string(to_string(problem.field)) + " " + problem.reason;
  return false;
}

int resolved_threads(int threads) {
  if (threads > 0) return std::min(threads, kMaxThreads);
  const auto cores = int(std::thread::hardware_concurrency());
  return std::clamp(cores, 1, kMaxThreads);
}

int thread_index() {
#if defined(_OPENMP)
  return omp_get_thread_num();
#else
  return 0;
#endif
}

int team_size() {
#if defined(_OPENMP)
  return omp_get_num_threads();
#else
  return 1;
#endif
}

std::string SolveSummary::brief_report() const {
  std::ostringstream out;
  out << solver << ": " << to_string(status) << ", " << iterations << " iteration" << (iterations == 1 ? "" : "s")
      << ", residual " << format_g(relative_residual) << ", " << analyze_seconds + factorize_seconds + solve_seconds
      << " s";
  if (!message.empty()) out << " (" << message << ")";
  return out.str();
}

double SolveSummary::forward_error_bound() const {
  return condition_estimate * std::max(std::numeric_limits<double>::epsilon(), normwise_backward_error);
}

std::string format_g(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

int iteration_limit(const SolverOptions& options, Eigen::Index unknowns, int per_unknown, double work) {
  if (options.max_iterations > 0) return options.max_iterations;
  const double n = double(std::max<Eigen::Index>(unknowns, 1));
  const double limit = std::min({double(per_unknown) * n, work / n, 2e6});
  return int(std::max(limit, 100.0));
}

Eigen::Index LinearOperator::size() const {
  if (matrix) return matrix->rows();
  if (stencil) return stencil->size();
  if (grid) return grid->size();
  return 0;
}

SolveStatus LinearSolver::analyze(const LinearOperator& op) {
  summary_ = SolveSummary{};
  summary_.solver = name();
  factorized_ = false;
  const auto start = std::chrono::steady_clock::now();
  // Options no backend can use (the CLI refuses them as bad input; a library caller gets the
  // reason here, where every backend starts, instead of an iteration with a tolerance of 2)
  if (std::string why; !options_.is_valid(&why)) {
    summary_.status = SolveStatus::kFailure;
    summary_.message = "invalid solver options: " + why;
  } else {
    summary_.status = do_analyze(op, summary_);
  }
  summary_.analyze_seconds = seconds_since(start);
  analyzed_size_ = summary_.ok() ? op.size() : -1;
  if (!summary_.ok()) summary_.relative_residual = kUnsolvedResidual;
  return summary_.status;
}

SolveStatus LinearSolver::factorize(const LinearOperator& op) {
  if (analyzed_size_ != op.size()) {
    if (analyze(op) != SolveStatus::kSuccess) return summary_.status;
  }
  summary_.status = SolveStatus::kSuccess;
  summary_.message.clear();
  summary_.iterations = 0;
  summary_.relative_residual = 0;
  summary_.solve_seconds = 0;
  const auto start = std::chrono::steady_clock::now();
  summary_.status = do_factorize(op, summary_);
  summary_.factorize_seconds = seconds_since(start);
  factorized_ = summary_.ok();
  if (!factorized_) summary_.relative_residual = kUnsolvedResidual;
  op_ = op;
  return summary_.status;
}

SolveSummary LinearSolver::solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
  if (!factorized_) {
    if (summary_.ok()) {
      summary_.status = SolveStatus::kFailure;
      summary_.message = "solve() called before a successful factorize()";
    }
    return_zero_solution(B, X, summary_);
    return summary_;
  }
  if (B.rows() != op_.size()) {
    SolveSummary bad = summary_;
    bad.status = SolveStatus::kFailure;
    bad.message = "right-hand side has " + std::to_string(B.rows()) + " rows, operator " + std::to_string(op_.size());
    return bad;
  }
  summary_.message.clear();
  summary_.relative_residual = 0;
  summary_.condition_estimate = 0;
  summary_.normwise_backward_error = 0;
  solve_start_ = std::chrono::steady_clock::now();
  summary_.status = solve_scaled(rhs_scaling(B), B, X, [&](const Eigen::MatrixX3d& Bs, Eigen::MatrixX3d& Xs) {
    return do_solve(Bs, Xs, summary_);
  });
  summary_.solve_seconds = seconds_since(solve_start_);
  judge_solution(B, X);
  return summary_;
}

bool LinearSolver::lacks_matrix(const LinearOperator& op, SolveSummary& summary) {
  if (op.matrix) return false;
  summary.message = "needs the assembled matrix";
  return true;
}

bool LinearSolver::lacks_stencil(const LinearOperator& op, SolveSummary& summary) {
  if (op.stencil) return false;
  if (op.grid) {
    // a grid stencil it cannot take: say which part of it (the backend needs a GridStencil)
    const StencilOperator& g = *op.grid;
    const bool full = Eigen::Index(g.rows) * g.cols == g.size();
    const std::string width = std::to_string(g.width());
    const bool mirrored = g.width() != 3 || (g.weight(-1, 0) == g.weight(1, 0) && g.weight(0, -1) == g.weight(0, 1) &&
                                             g.weight(-1, -1) == g.weight(-1, 1) && g.weight(-1, -1) == g.weight(1, 1));
    summary.message =
        "works on a 3x3 stencil with one weight per pair of neighbours along i, one along j and one for the four "
        "diagonals, on a full rectangle; this system is a " +
        width + "x" + width + " stencil" + (mirrored ? "" : " that is not symmetric under reflection in i and in j") +
        (full ? "" : " on a free set (some interior points fixed)");
    return true;
  }
  summary.message = "needs the grid stencil (matrix-free)";
  return true;
}

bool LinearSolver::out_of_time() const {
  return options_.time_limit_seconds > 0 && seconds_since(solve_start_) >= options_.time_limit_seconds;
}

SolveStatus LinearSolver::finish_iteration(const IterationEnd& end, Eigen::MatrixX3d& X, SolveSummary& summary) const {
  summary.iterations = end.iterations;
  const bool overflow = !std::isfinite(end.residual);
  summary.relative_residual = overflow ? std::numeric_limits<double>::max() : end.residual;
  if (end.converged && !overflow) return SolveStatus::kSuccess;
  const std::string after =
      " after " + std::to_string(end.iterations) + " iteration" + (end.iterations == 1 ? "" : "s");
  if (end.diverged || overflow || (!end.krylov && !end.convergent && end.residual > end.initial)) {
    X.setZero();
    summary.message = "diverged: the residual grew from " + format_g(end.initial) + " to " +
                      (overflow ? std::string("overflow (reported as the largest double)") : format_g(end.residual)) +
                      after;
    return SolveStatus::kDiverged;
  }
  const std::string why =
      end.breakdown   ? "the method broke down, a zero divisor in its recurrence; the last finite iterate is returned"
      : end.timed_out ? "time limit " + format_g(options_.time_limit_seconds) + " s reached"
      : !end.stagnation.empty() ? "stagnated: " + end.stagnation
                                : "iteration limit " + std::to_string(end.limit) + " reached";
  summary.message = "not converged: residual " + format_g(end.residual) + after + " (" + why + "; tolerance " +
                    format_g(options_.tolerance) + ")";
  return SolveStatus::kNotConverged;
}

SolveSummary LinearSolver::compute_and_solve(const LinearOperator& op, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
  if (analyze(op) == SolveStatus::kSuccess) factorize(op);
  return solve(B, X);  // without a factorisation: X = 0 and the status of the step that failed
}

bool apply_operator(const LinearOperator& op, const Eigen::MatrixX3d& X, Eigen::MatrixXd& AX) {
  if (op.matrix) {
    AX = (*op.matrix) * X;
  } else if (op.stencil) {
    apply_stencil(*op.stencil, X, AX);
  } else if (op.grid) {
    apply_stencil_operator(*op.grid, X, AX);
  } else {
    return false;
  }
  return true;
}

double relative_residual(const LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X) {
  if (B.rows() == 0) return 0;
  Eigen::MatrixXd AX;
  if (!apply_operator(op, X, AX)) return NAN;
  AX -= B;
  return max_relative_norm(AX, B);  // no underflow or overflow of ‖·‖²
}

}  // namespace coons::solvers
