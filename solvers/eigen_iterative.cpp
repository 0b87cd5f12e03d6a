#include "eigen_iterative.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/IterativeLinearSolvers>

namespace coons::solvers {

int iteration_limit(const SolverOptions& options, Eigen::Index unknowns, int per_unknown) {
  if (options.max_iterations > 0) return options.max_iterations;
  return int(std::min<Eigen::Index>(std::max<Eigen::Index>(2000, per_unknown * unknowns), 2'000'000));
}

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A positive definite operator is required by CG; with the stencil we know exactly.
bool stencil_not_definite(const LinearOperator& op, SolveSummary& summary) {
  if (!op.stencil || op.stencil->size() == 0) return false;
  const double lo = stencil_eigenvalue_range(*op.stencil).first;
  if (lo > 0) return false;
  summary.message = "smallest eigenvalue of the operator is " + std::to_string(lo) +
                    ": conjugate gradients need a positive definite system";
  return true;
}

template <class Krylov>
class EigenIterative : public LinearSolver {
 public:
  EigenIterative(std::string name, bool definite_only, const SolverOptions& options)
      : LinearSolver(options), name_(std::move(name)), definite_only_(definite_only) {}
  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (!op.matrix) {
      summary.message = "needs the assembled matrix";
      return SolveStatus::kNotApplicable;
    }
    krylov_.analyzePattern(*op.matrix);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!op.matrix) {
      summary.message = "needs the assembled matrix";
      return SolveStatus::kNotApplicable;
    }
    if (definite_only_ && stencil_not_definite(op, summary)) return SolveStatus::kNotPositiveDefinite;
    krylov_.setTolerance(options_.tolerance);
    krylov_.setMaxIterations(iteration_limit(options_, op.matrix->rows()));
    krylov_.factorize(*op.matrix);  // the preconditioner's numeric phase
    if (krylov_.info() != Eigen::Success) {
      summary.message = "the preconditioner could not be computed";
      return definite_only_ ? SolveStatus::kNotPositiveDefinite : SolveStatus::kSingular;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    X.resize(B.rows(), 3);
    SolveStatus status = SolveStatus::kSuccess;
    int iterations = 0;
    double worst_error = 0;
    for (int c = 0; c < 3; ++c) {
      X.col(c) = krylov_.solve(B.col(c));
      iterations = std::max(iterations, int(krylov_.iterations()));
      worst_error = std::max(worst_error, krylov_.error());
      if (krylov_.info() == Eigen::NoConvergence) status = SolveStatus::kNotConverged;
      else if (krylov_.info() != Eigen::Success && status == SolveStatus::kSuccess) status = SolveStatus::kFailure;
    }
    summary.iterations = iterations;
    if (!X.allFinite()) {
      summary.message = "the iteration broke down (non-finite values)";
      X.setZero();
      return SolveStatus::kDiverged;
    }
    if (status == SolveStatus::kNotConverged)
      summary.message = "estimated residual " + std::to_string(worst_error) + " after " +
                        std::to_string(iterations) + " iterations (tolerance " +
                        std::to_string(options_.tolerance) + ")";
    return status;
  }

 private:
  std::string name_;
  bool definite_only_;
  Krylov krylov_;
};

using Cg = Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::IdentityPreconditioner>;
using CgJacobi = Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>>;
using CgIc = Eigen::ConjugateGradient<SpMat, Eigen::Lower, Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>;
using Bicgstab = Eigen::BiCGSTAB<SpMat, Eigen::IncompleteLUT<double>>;

}  // namespace

std::unique_ptr<LinearSolver> make_cg(const SolverOptions& o) { return std::make_unique<EigenIterative<Cg>>("cg", true, o); }
std::unique_ptr<LinearSolver> make_cg_jacobi(const SolverOptions& o) { return std::make_unique<EigenIterative<CgJacobi>>("cg-jacobi", true, o); }
std::unique_ptr<LinearSolver> make_cg_ic(const SolverOptions& o) { return std::make_unique<EigenIterative<CgIc>>("cg-ic", true, o); }
std::unique_ptr<LinearSolver> make_bicgstab(const SolverOptions& o) { return std::make_unique<EigenIterative<Bicgstab>>("bicgstab", false, o); }

}  // namespace coons::solvers
