#include "linear_solver.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "stencil_operator.h"

namespace coons::solvers {

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSuccess: return "success";
    case SolveStatus::kNotConverged: return "not_converged";
    case SolveStatus::kDiverged: return "diverged";
    case SolveStatus::kNotPositiveDefinite: return "not_positive_definite";
    case SolveStatus::kSingular: return "singular";
    case SolveStatus::kNotApplicable: return "not_applicable";
    case SolveStatus::kFailure: return "failure";
  }
  return "failure";
}

const char* to_string(Ordering ordering) {
  switch (ordering) {
    case Ordering::kAuto: return "auto";
    case Ordering::kNatural: return "natural";
    case Ordering::kAmd: return "amd";
    case Ordering::kColamd: return "colamd";
    case Ordering::kMetis: return "metis";
    case Ordering::kNestedDissection: return "nested-dissection";
    case Ordering::kCholmodDefault: return "cholmod-default";
  }
  return "auto";
}

bool SolverOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (!(tolerance > 0 && tolerance < 1)) return fail("tolerance must lie in (0, 1)");
  if (max_iterations < 0) return fail("max_iterations must be >= 0");
  if (!(sor_omega > 0 && sor_omega < 2)) return fail("sor_omega must lie in (0, 2)");
  if (!(singular_residual > 0)) return fail("singular_residual must be positive");
  return true;
}

std::string SolveSummary::brief_report() const {
  std::ostringstream out;
  out << solver << ": " << to_string(status) << ", " << iterations << " iteration"
      << (iterations == 1 ? "" : "s") << ", residual " << relative_residual << ", "
      << analyze_seconds + factorize_seconds + solve_seconds << " s";
  if (!message.empty()) out << " (" << message << ")";
  return out.str();
}

Eigen::Index LinearOperator::size() const {
  if (matrix) return matrix->rows();
  if (stencil) return stencil->size();
  if (grid) return grid->size();
  return 0;
}

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

SolveStatus LinearSolver::analyze(const LinearOperator& op) {
  summary_ = SolveSummary{};
  summary_.solver = name();
  factorized_ = false;
  const auto start = std::chrono::steady_clock::now();
  summary_.status = do_analyze(op, summary_);
  summary_.analyze_seconds = seconds_since(start);
  analyzed_size_ = summary_.ok() ? op.size() : -1;
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
  op_ = op;
  return summary_.status;
}

SolveSummary LinearSolver::solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
  if (!factorized_) {
    if (summary_.ok()) {
      summary_.status = SolveStatus::kFailure;
      summary_.message = "solve() called before a successful factorize()";
    }
    X.setZero(B.rows(), 3);
    return summary_;
  }
  if (B.rows() != op_.size()) {
    SolveSummary bad = summary_;
    bad.status = SolveStatus::kFailure;
    bad.message = "right-hand side has " + std::to_string(B.rows()) + " rows, operator " +
                  std::to_string(op_.size());
    return bad;
  }
  summary_.message.clear();
  const auto start = std::chrono::steady_clock::now();
  summary_.status = do_solve(B, X, summary_);
  summary_.solve_seconds = seconds_since(start);
  if (options_.compute_residual && X.rows() == B.rows()) {
    summary_.relative_residual = relative_residual(op_, B, X);
    if (!std::isfinite(summary_.relative_residual)) {
      summary_.relative_residual = HUGE_VAL;
      if (summary_.ok()) {
        summary_.status = SolveStatus::kFailure;
        summary_.message = "the solution is not finite";
      }
    } else if (summary_.ok() && exact() &&
               summary_.relative_residual > options_.singular_residual) {
      summary_.status = SolveStatus::kSingular;
      summary_.message = "true residual " + std::to_string(summary_.relative_residual) +
                         " after an exact solve: the operator is numerically singular";
    }
  }
  return summary_;
}

SolveSummary LinearSolver::compute_and_solve(const LinearOperator& op, const Eigen::MatrixX3d& B,
                                             Eigen::MatrixX3d& X) {
  if (analyze(op) != SolveStatus::kSuccess || factorize(op) != SolveStatus::kSuccess) {
    X.setZero(B.rows(), 3);
    return summary_;
  }
  return solve(B, X);
}

void LinearSolver::sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis,
                         const std::vector<SweepMember>& members, const SweepSink& sink) {
  Eigen::MatrixX3d B, X;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const SweepMember& member = members[k];
    B.setZero(member.op.size(), 3);
    for (std::size_t r = 0; r < rhs_basis.size() && r < member.rhs_weights.size(); ++r)
      B += member.rhs_weights[r] * rhs_basis[r];
    if (factorize(member.op) != SolveStatus::kSuccess) {
      X.setZero(B.rows(), 3);
      sink(k, X, summary_);
      continue;
    }
    sink(k, X, solve(B, X));
  }
}

double relative_residual(const LinearOperator& op, const Eigen::MatrixX3d& B,
                         const Eigen::MatrixX3d& X) {
  if (B.rows() == 0) return 0;
  Eigen::MatrixXd AX;
  if (op.matrix) {
    AX = (*op.matrix) * X;
  } else if (op.stencil) {
    apply_stencil(*op.stencil, X, AX);
  } else if (op.grid) {
    apply_stencil_operator(*op.grid, X, AX);
  } else {
    return NAN;
  }
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    const double b = B.col(k).norm();
    const double r = (AX.col(k) - B.col(k)).norm();
    worst = std::max(worst, b > 0 ? r / b : r);
  }
  return worst;
}

}  // namespace coons::solvers
