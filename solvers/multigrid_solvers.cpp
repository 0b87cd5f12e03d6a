#include "multigrid_solvers.h"

#include <algorithm>
#include <array>
#include <exception>
#include <optional>
#include <string>

#if defined(_OPENMP)
#include <omp.h>
#endif

#include "eigen_iterative.h"
#include "gmres.h"
#include "multigrid.h"
#include "stencil_operator.h"

namespace coons::solvers {

namespace {

enum class Method { kStationary, kCg, kGmres };

// The grid operator of op: op.grid, else the 3×3 stencil; none when op has only a matrix.
std::optional<StencilOperator> grid_operator_of(const LinearOperator& op) {
  if (op.grid) return *op.grid;
  if (op.stencil) return stencil_operator(*op.stencil);
  return std::nullopt;
}

class MultigridBackend : public LinearSolver {
 public:
  MultigridBackend(std::string name, Method method, const SolverOptions& options)
      : LinearSolver(options), name_(std::move(name)), method_(method) {}
  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    const std::optional<StencilOperator> grid = grid_operator_of(op);
    if (!grid) {
      if (method_ == Method::kGmres && op.matrix) return SolveStatus::kSuccess;
      summary.message = method_ == Method::kGmres
                            ? "needs the assembled matrix or a grid stencil"
                            : "needs a grid stencil (3x3 or 5x5, with its free mask), not only a matrix";
      return SolveStatus::kNotApplicable;
    }
    if (std::string why = grid_operator_problem(*grid, op.matrix); !why.empty()) {
      summary.message = why;
      return SolveStatus::kNotApplicable;
    }
    if (method_ == Method::kCg && !grid->symmetric()) {
      summary.message = "conjugate gradients need a symmetric stencil (w(d) = w(-d)); use gmres";
      return SolveStatus::kNotApplicable;
    }
    if (method_ == Method::kStationary && !grid->symmetric()) {
      // Galerkin coarsening with R = Pᵀ diverged on upwinded convection from 127x127 on.
      summary.message = "multigrid here is built for symmetric stencils (w(d) = w(-d)); use gmres";
      return SolveStatus::kNotApplicable;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    const SolveStatus checked = do_analyze(op, summary);
    if (checked != SolveStatus::kSuccess) return checked;
    ilu_ = {};
    matrix_ = op.matrix;
    mg_ = Multigrid{};
    const std::optional<StencilOperator> grid = grid_operator_of(op);
    if (method_ == Method::kCg && !op.grid && op.stencil) {  // the exact spectrum is known
      const double lo = stencil_eigenvalue_range(*op.stencil).first;
      if (!(lo > 0)) {
        summary.message = "smallest eigenvalue of the operator is " + format_g(lo) +
                          ": conjugate gradients need a positive definite system";
        return SolveStatus::kNotPositiveDefinite;
      }
    }
    std::string message;
    if (grid && grid->symmetric()) {
      MultigridOptions mg_options;  // fourth-order (5×5) stencils: two sweeps per side pay off
      mg_options.pre_smoothing = mg_options.post_smoothing = grid->radius;
      mg_options.threads = options_.threads;
      const SolveStatus status = mg_.setup(*grid, mg_options, &message);
      if (status == SolveStatus::kSuccess) return status;
      if (method_ != Method::kGmres) {
        summary.message = message;
        return status;
      }
    }
    // gmres on a nonsymmetric stencil, or without (a working) hierarchy: ILUT of the matrix.
    if (!matrix_) {
      own_matrix_ = stencil_operator_matrix(*grid);
      matrix_ = &own_matrix_;
    }
    ilu_ = ilut_preconditioner(*matrix_, &message);
    if (!ilu_) {
      summary.message = message;
      return SolveStatus::kSingular;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const Eigen::Index n = B.rows();
    IterationOptions iteration;
    iteration.tolerance = options_.tolerance;
    iteration.out_of_time = [this] { return out_of_time(); };  // SolverOptions::time_limit_seconds
    std::array<Eigen::VectorXd, 3> x;
    std::array<IterationSummary, 3> s;
    std::array<std::exception_ptr, 3> errors;
    auto run = [&](int c) {
      try {  // (an exception must not leave a parallel region: it is rethrown below)
        x[std::size_t(c)] = Eigen::VectorXd::Zero(n);
        s[std::size_t(c)] = solve_column(B.col(c), x[std::size_t(c)], iteration);
      } catch (...) {
        errors[std::size_t(c)] = std::current_exception();
      }
    };
    // With threads ≥ 2 the columns of B, independent systems, are solved side by side, each on one
    // thread (the level loops inside a parallel region run on their thread: loop_threads in
    // multigrid_levels.h), and a column left over (two threads: the third) alone, with the level
    // loops on every thread. The level loops have several parallel regions per level and cycle,
    // whose waits stall when another program holds a core; side by side a column has none. But
    // two whole solves at once share the caches and the memory bus, and three columns on two
    // threads leave one thread idle for a third of the time, so the last column keeps the level
    // loops (measured 2026-11-24 at N = 1023, α = −0.1, on an idle machine: level loops only
    // 0.97-1.13 s, all three columns side by side 1.32 s, this split 0.95-1.09 s; docs/solvers.md).
    // Each column's solution does not depend on the threads, so X is that of one thread bit for bit.
    const int threads = mg_.ready() ? resolved_threads(options_.threads) : 1;
    int side_by_side = threads >= 2 ? std::min(threads, 3) : 1;
#if defined(_OPENMP)
    if (omp_in_parallel()) side_by_side = 1;
#pragma omp parallel for num_threads(side_by_side) if (side_by_side > 1) schedule(static, 1)
#else
    side_by_side = 1;
#endif
    for (int c = 0; c < side_by_side; ++c) run(c);
    for (int c = side_by_side; c < 3; ++c) run(c);
    for (const std::exception_ptr& error : errors)
      if (error) std::rethrow_exception(error);

    X.setZero(n, 3);
    SolveStatus status = SolveStatus::kSuccess;
    int iterations = 0;
    double worst = 0;              // the largest true relative residual over the columns
    for (int c = 0; c < 3; ++c) {  // in column order: the first failing column names the status
      IterationSummary& sc = s[std::size_t(c)];
      iterations = std::max(iterations, sc.iterations);
      worst = std::max(worst, sc.relative_residual);
      X.col(c) = x[std::size_t(c)];
      if (!sc.ok() && status == SolveStatus::kSuccess) {
        status = sc.status;
        // This column's message; relative_residual (below) is the worst column's.
        summary.message = "right-hand side " + std::to_string(c + 1) + " of 3: " + sc.message;
      }
    }
    summary.iterations = iterations;
    // The residual reached, whatever the status: a solve that stopped early reports what it got
    // (judge_solution replaces it by the recomputed true residual only on success).
    summary.relative_residual = worst;
    return status;
  }

  // One column: the backend's iteration on A x = b from x (zero), x set to 0 if it breaks down.
  IterationSummary solve_column(const Eigen::VectorXd& b, Eigen::VectorXd& x, IterationOptions iteration) const {
    const Eigen::Index n = b.size();
    IterationSummary s;
    switch (method_) {
      case Method::kStationary:
        iteration.max_iterations = options_.max_iterations > 0 ? options_.max_iterations : 500;
        s = mg_.solve(b, x, iteration);
        break;
      case Method::kCg:
        iteration.max_iterations = options_.max_iterations > 0 ? options_.max_iterations : 500;
        s = multigrid_cg(mg_, b, x, iteration);
        break;
      case Method::kGmres: {
        GmresOptions g;
        g.iteration = iteration;
        VectorMap apply, precondition;
        if (mg_.ready()) {
          g.iteration.max_iterations = options_.max_iterations > 0 ? options_.max_iterations : 500;
          apply = [this](const Eigen::VectorXd& in, Eigen::VectorXd& out) { mg_.apply(in, out); };
          precondition = [this](const Eigen::VectorXd& in, Eigen::VectorXd& out) { mg_.precondition(in, out); };
        } else {
          g.iteration.max_iterations = iteration_limit(options_, n, 20, 2e10);
          apply = [this](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = (*matrix_) * in; };
          precondition = ilu_;
        }
        s = gmres(apply, precondition, b, x, g);
        break;
      }
    }
    if (!x.allFinite()) {
      x.setZero();
      s.status = SolveStatus::kDiverged;
      s.message = "the iteration broke down (non-finite values)";
      s.relative_residual = 1;  // x = 0
    }
    return s;
  }

 private:
  std::string name_;
  Method method_;
  Multigrid mg_;
  VectorMap ilu_;
  const Eigen::SparseMatrix<double>* matrix_ = nullptr;
  Eigen::SparseMatrix<double> own_matrix_;  // assembled from the grid when no matrix was given
};

}  // namespace

std::unique_ptr<LinearSolver> make_mg(const SolverOptions& o) {
  return std::make_unique<MultigridBackend>("mg", Method::kStationary, o);
}
std::unique_ptr<LinearSolver> make_mg_cg(const SolverOptions& o) {
  return std::make_unique<MultigridBackend>("mg-cg", Method::kCg, o);
}
std::unique_ptr<LinearSolver> make_gmres(const SolverOptions& o) {
  return std::make_unique<MultigridBackend>("gmres", Method::kGmres, o);
}

}  // namespace coons::solvers
