#include "linear_solver.h"

#if defined(_OPENMP)
#include <omp.h>
#endif
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <sstream>
#include <thread>
#include <utility>

#include "column_scaling.h"
#include "stencil_operator.h"

namespace coons::solvers {

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

std::string SolveSummary::brief_report() const {
  std::ostringstream out;
  out << solver << ": " << to_string(status) << ", " << iterations << " iteration" << (iterations == 1 ? "" : "s")
      << ", residual " << format_g(relative_residual) << ", " << analyze_seconds + factorize_seconds + solve_seconds
      << " s";
  if (!message.empty()) out << " (" << message << ")";
  return out.str();
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

namespace {
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The relative residual of X = 0 for a non-zero B: what a summary reports when analyze or
// factorize failed (a search copied such a summary and printed "singular, 0 iterations, residual
// 0" although nothing was solved) and what return_zero_solution reports.
constexpr double kUnsolvedResidual = 1;

// What a solve that could not run (no factorisation) returns: X = 0, and the relative residual of
// that X, max over the columns of ‖A·0 − b‖/‖b‖ = 1 (‖A·0‖ = 0 for a zero column), as every report
// promises for a failed solve (docs/formats.md, "The solver block").
void return_zero_solution(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) {
  X.setZero(B.rows(), 3);
  summary.relative_residual = B.isZero(0) ? 0 : kUnsolvedResidual;
}

// X = A⁻¹B by `solve` (a backend's do_solve), with each column of B whose largest magnitude is far
// from 1 scaled by a power of two to one in [1/2, 1) (e: rhs_exponents(B)) and X scaled back:
// exact, and no backend's squared norms underflow or overflow (column_scaling.h). A zero column
// stays zero.
template <class Solve>
SolveStatus solve_scaled(const ColumnExponents& e, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, Solve&& solve) {
  if (is_identity(e)) return solve(B, X);
  const SolveStatus status = solve(scaled_columns(B, e, -1), X);
  if (X.rows() == B.rows()) X = scaled_columns(std::move(X), e, +1);
  return status;
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
  solve_start_ = std::chrono::steady_clock::now();
  summary_.status = solve_scaled(rhs_scaling(B), B, X, [&](const Eigen::MatrixX3d& Bs, Eigen::MatrixX3d& Xs) {
    return do_solve(Bs, Xs, summary_);
  });
  summary_.solve_seconds = seconds_since(solve_start_);
  judge_solution(B, X);
  return summary_;
}

void LinearSolver::judge_solution(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
  if (!options_.compute_residual || X.rows() != B.rows()) return;
  // The verdict on the system as the backend saw it, B's columns scaled as solve_scaled scales
  // them (the same relative residuals, without underflow or overflow); X itself is changed only
  // by a refinement.
  const ColumnExponents e = rhs_exponents(B);
  const bool scaled = !is_identity(e);
  const auto judge_scaled = [&] {
    Eigen::MatrixX3d B_scaled, X_scaled;
    if (scaled) {
      B_scaled = scaled_columns(B, e, -1);
      X_scaled = scaled_columns(X, e, -1);
    }
    const Eigen::MatrixX3d& Bs = scaled ? B_scaled : B;
    Eigen::MatrixX3d& Xs = scaled ? X_scaled : X;
    if (exact()) {
      judge_exact_solve(op_, Bs, Xs, summary_);
      if (summary_.status == SolveStatus::kSingular) judge_ill_conditioned(Bs, Xs);
      return;
    }
    if (summary_.status == SolveStatus::kNotConverged) {
      // The X returned is an iterate: its true residual is the one to report, not the backend's
      // estimate (CG's recurrence reached 5.5e-127 for a tolerance of 1e-300, below any true one).
      const double r = relative_residual(op_, Bs, Xs);
      if (std::isfinite(r) && r != summary_.relative_residual) {
        // (after a time limit the columns not reached are 0: a true residual of 1 for an estimate of 1e-4)
        summary_.message += "; the X returned has the true relative residual " + format_g(r);
        summary_.relative_residual = r;
      }
      return;
    }
    if (!summary_.ok()) return;  // keeps the residual its message names (finish_iteration set it)
    // An iteration that stopped on its own test (often a recursively updated residual, which drifts
    // from the true one near the rounding floor): the true residual decides. Above the tolerance,
    // up to kRefinementRounds corrections X += A⁻¹(B − A X) by the same backend, then not_converged.
    double r = relative_residual(op_, Bs, Xs);
    int rounds = 0;
    while (std::isfinite(r) && r > options_.tolerance && rounds < kRefinementRounds && !out_of_time()) {
      ++rounds;
      Eigen::MatrixXd AX;
      if (!apply_operator(op_, Xs, AX)) break;
      const Eigen::MatrixX3d R = Bs - AX;
      Eigen::MatrixX3d D;
      SolveSummary correction = summary_;
      const SolveStatus status =
          solve_scaled(rhs_scaling(R), R, D,
                       [&](const Eigen::MatrixX3d& Rs, Eigen::MatrixX3d& Ds) { return do_solve(Rs, Ds, correction); });
      if (status != SolveStatus::kSuccess || !D.allFinite()) break;
      summary_.iterations += correction.iterations;
      const Eigen::MatrixX3d refined = Xs + D;
      const double next = relative_residual(op_, Bs, refined);
      if (!(next < r)) break;
      Xs = refined;
      if (scaled) X = scaled_columns(refined, e, +1);
      r = next;
    }
    if (!std::isfinite(r) || (scaled && !X.allFinite())) {  // (X scaled back can overflow)
      summary_.relative_residual = std::numeric_limits<double>::max();
      summary_.status = SolveStatus::kFailure;
      summary_.message = "the solution is not finite (overflow)";
      return;
    }
    summary_.relative_residual = r;
    if (r > options_.tolerance) {
      summary_.status = SolveStatus::kNotConverged;
      summary_.message = "not converged: the backend's own test passed, but the true relative residual is " +
                         format_g(r) + ", above the tolerance " + format_g(options_.tolerance) + " (after " +
                         std::to_string(rounds) + " refinement round" + (rounds == 1 ? "" : "s") + ")";
    }
  };
  // X scaled back can lose its bits below the normal doubles (a net of 1e-315: the scaled system
  // was solved to 6.5e-16, the X returned has 1.8e-7; 1e30 x = 1e-300: x = 1e-330 is 0, and
  // judged in scale as 0 it read "numerically singular"): then the residual reported and the
  // verdict are those of the X returned, and the reason is said.
  const auto underflowed = [&] {
    for (Eigen::Index c = 0; c < 3; ++c) {
      if (e[std::size_t(c)] == 0) continue;
      const auto x = X.col(c).array().abs();
      if ((x > 0 && x < std::numeric_limits<double>::min()).any()) return true;
      if (x.maxCoeff() == 0 && !B.col(c).isZero(0)) return true;
    }
    return false;
  };
  if (!scaled || !X.allFinite() || !underflowed()) judge_scaled();
  if (!scaled || !X.allFinite() || summary_.status == SolveStatus::kFailure) return;
  const double returned = relative_residual(op_, B, X);
  if (!std::isfinite(returned) || !(returned > summary_.relative_residual)) return;
  const double met = summary_.relative_residual;  // by the scaled system (above the limit when ill-conditioned)
  summary_.relative_residual = returned;
  const double accepted = exact() ? options_.singular_residual : options_.tolerance;
  if (summary_.ok() && returned > accepted && met <= accepted) {
    summary_.status = SolveStatus::kFailure;
    summary_.message = "the X returned has the relative residual " + format_g(returned) + ", above " +
                       format_g(accepted) +
                       ", where the system scaled by powers of two met it: X lies below the range of the doubles "
                       "(underflow)";
  }
}

void LinearSolver::judge_exact_solve(const LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X,
                                     SolveSummary& summary) const {
  if (!options_.compute_residual) return;
  const double r = relative_residual(op, B, X);
  if (!std::isfinite(r)) {
    summary.relative_residual = std::numeric_limits<double>::max();
    if (summary.ok()) {
      summary.status = SolveStatus::kFailure;
      summary.message = "the solution is not finite (overflow)";
    }
    return;
  }
  summary.relative_residual = r;
  if (summary.ok() && r > options_.singular_residual) {
    summary.status = SolveStatus::kSingular;
    summary.message = "true residual " + format_g(r) + " after an exact solve: the operator is numerically singular";
  }
}

void LinearSolver::judge_ill_conditioned(const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X) {
  // A large relative residual after an exact solve is what a singular operator gives, but also an
  // ill-conditioned one solved as well as doubles allow: the 10 × 10 Hilbert matrix (κ∞ = 3.5e13)
  // with b = e₁₀ has no double x with a relative residual below 9.6e−6. The two differ in κ: a
  // backward-stable solve (normwise backward error ‖r‖∞ / (‖A‖∞‖x‖∞ + ‖b‖∞) near ε) of an operator
  // whose condition estimate lies well below 1/ε is a solution, with κ·ε as its forward error bound.
  // The estimate ‖A‖∞ · max ‖A⁻¹g‖∞ / ‖g‖∞ over three fixed ±1 vectors g is a lower bound of κ∞,
  // usually within a small factor (it needs the matrix: grid operators keep the verdict).
  if (!op_.matrix || op_.matrix->rows() == 0) return;
  const Eigen::SparseMatrix<double>& A = *op_.matrix;
  Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(A.rows());
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it) row_sums(it.row()) += std::abs(it.value());
  const double norm_a = row_sums.maxCoeff();
  const Eigen::MatrixX3d R = B - A * X;
  double backward = 0;
  for (Eigen::Index c = 0; c < 3; ++c) {
    const double scale = norm_a * X.col(c).lpNorm<Eigen::Infinity>() + B.col(c).lpNorm<Eigen::Infinity>();
    if (scale > 0) backward = std::max(backward, R.col(c).lpNorm<Eigen::Infinity>() / scale);
  }
  constexpr double kStable = 1e-12;  // ‖r‖ / (‖A‖‖x‖ + ‖b‖) of a backward-stable solve: a few n·ε
  if (!(backward <= kStable)) return;
  Eigen::MatrixX3d G(A.rows(), 3), Y;
  for (Eigen::Index i = 0; i < G.rows(); ++i) {  // the signs of three fixed patterns
    G(i, 0) = 1;
    G(i, 1) = i % 2 == 0 ? 1 : -1;
    G(i, 2) = (i * 7 + 3) % 5 < 2 ? -1 : 1;
  }
  SolveSummary probe = summary_;
  const SolveStatus probed = solve_scaled(
      rhs_scaling(G), G, Y, [&](const Eigen::MatrixX3d& Gs, Eigen::MatrixX3d& Ys) { return do_solve(Gs, Ys, probe); });
  if (probed != SolveStatus::kSuccess || !Y.allFinite()) return;
  const double kappa = norm_a * Y.cwiseAbs().colwise().maxCoeff().maxCoeff();
  constexpr double kSingularKappa = 0.1 / std::numeric_limits<double>::epsilon();  // 4.5e14
  if (!(kappa < kSingularKappa)) {
    summary_.message += "; condition estimate " + format_g(kappa) + " (at least 1/(10 eps))";
    return;
  }
  summary_.status = SolveStatus::kSuccess;
  summary_.message = "ill-conditioned: relative residual " + format_g(summary_.relative_residual) +
                     " with normwise backward error " + format_g(backward) + ", condition estimate " + format_g(kappa) +
                     " (a lower bound): the solve is backward stable, its forward error up to about " +
                     format_g(kappa * std::numeric_limits<double>::epsilon());
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
    const bool full = Eigen::Index(op.grid->rows) * op.grid->cols == op.grid->size();
    const std::string width = std::to_string(op.grid->width());
    summary.message = "works on a 3x3 stencil of a full rectangle with one fixed ring only; this system is a " + width +
                      "x" + width + " stencil" +
                      (full ? std::string() : std::string(" on a free set (some interior points fixed)"));
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

Eigen::MatrixX3d combine_rhs(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::Index rows) {
  Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(rows, 3);
  for (std::size_t r = 0; r < basis.size() && r < weights.size(); ++r) B += weights[r] * basis[r];
  return B;
}

SolveStatus LinearSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                                         Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::MatrixX3d B = combine_rhs(basis, weights, op_.size());
  return solve_scaled(rhs_exponents(B), B, X,
                      [&](const Eigen::MatrixX3d& Bs, Eigen::MatrixX3d& Xs) { return do_solve(Bs, Xs, summary); });
}

std::unique_ptr<LinearSolver> LinearSolver::make_sweep_worker(const std::vector<Eigen::MatrixX3d>& /*basis*/,
                                                              const LinearOperator& /*op*/) {
  return nullptr;
}

void LinearSolver::sweep_member(const std::vector<Eigen::MatrixX3d>& basis, const SweepMember& member,
                                Eigen::MatrixX3d& X) {
  const std::size_t used = std::min(basis.size(), member.rhs_weights.size());
  const std::vector<double> weights(member.rhs_weights.begin(), member.rhs_weights.begin() + long(used));
  if (factorize(member.op) != SolveStatus::kSuccess) {
    return_zero_solution(combine_rhs(basis, weights, member.op.size()), X, summary_);
    return;
  }
  summary_.message.clear();
  summary_.relative_residual = 0;
  solve_start_ = std::chrono::steady_clock::now();
  summary_.status = do_sweep_solve(basis, weights, X, summary_);
  summary_.solve_seconds = seconds_since(solve_start_);
  if (options_.compute_residual) judge_solution(combine_rhs(basis, weights, member.op.size()), X);
}

void LinearSolver::sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis, const std::vector<SweepMember>& members,
                         const SweepSink& sink) {
  do_begin_sweep();
#if defined(_OPENMP)
  const std::size_t threads = std::min(std::size_t(resolved_threads(options_.threads)), members.size());
#else
  const std::size_t threads = 1;
#endif
  std::vector<std::unique_ptr<LinearSolver>> workers;
  for (std::size_t t = 0; threads >= 2 && t < threads; ++t) {
    auto worker = make_sweep_worker(rhs_basis, members.front().op);
    if (!worker) {
      workers.clear();
      break;
    }
    workers.push_back(std::move(worker));
  }
  if (!workers.empty()) {
    sweep_on_workers(workers, rhs_basis, members, sink);
    return;
  }
  Eigen::MatrixX3d X;
  for (std::size_t k = 0; k < members.size(); ++k) {
    sweep_member(rhs_basis, members[k], X);
    sink(k, X, summary_);
  }
}

void LinearSolver::sweep_on_workers(const std::vector<std::unique_ptr<LinearSolver>>& workers,
                                    const std::vector<Eigen::MatrixX3d>& basis, const std::vector<SweepMember>& members,
                                    const SweepSink& sink) {
  const int T = int(workers.size());
  std::vector<Eigen::MatrixX3d> X(workers.size());
  std::vector<std::exception_ptr> errors(workers.size());
  for (std::size_t first = 0; first < members.size(); first += workers.size()) {
    const int batch = int(std::min(workers.size(), members.size() - first));
#if defined(_OPENMP)
#pragma omp parallel for num_threads(batch) schedule(static, 1)
#endif
    for (int t = 0; t < batch; ++t) {
      const auto w = std::size_t(t);
      try {  // (an exception must not leave the parallel region: it is rethrown below)
        workers[w]->sweep_member(basis, members[first + w], X[w]);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    }
    for (int t = 0; t < batch; ++t) {
      const auto w = std::size_t(t);
      if (errors[w]) std::rethrow_exception(errors[w]);
      sink(first + w, X[w], workers[w]->summary_);
    }
  }
  // This solver holds no factorisation of its own now; its summary is the last member's.
  summary_ = workers[(members.size() - 1) % std::size_t(T)]->summary_;
  factorized_ = false;
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
