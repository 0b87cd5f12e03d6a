#include "eigen_iterative.h"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <type_traits>

#include "column_scaling.h"
#include "iteration_summary.h"
#include "matrix_checks.h"

namespace coons::solvers {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A positive definite operator is required by CG; with the stencil we know exactly.
bool stencil_not_definite(const LinearOperator& op, SolveSummary& summary) {
  if (!op.stencil || op.stencil->size() == 0) return false;
  const double lo = stencil_eigenvalue_range(*op.stencil).first;
  if (lo > 0) return false;
  summary.message = "smallest eigenvalue of the operator is " + format_g(lo) +
                    ": conjugate gradients need a positive definite system";
  return true;
}

template <class Krylov>
struct IsConjugateGradient : std::false_type {};
template <class Matrix, int UpLo, class Preconditioner>
struct IsConjugateGradient<Eigen::ConjugateGradient<Matrix, UpLo, Preconditioner>> : std::true_type {};

template <class Krylov>
class EigenIterative : public LinearSolver {
 public:
  EigenIterative(std::string name, bool definite_only, const SolverOptions& options)
      : LinearSolver(options), name_(std::move(name)), definite_only_(definite_only) {}
  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    // (Eigen 3.4's IterativeSolverBase::analyzePattern reads the preconditioner's info() before
    // IncompleteLUT has set it, an uninitialised load that UBSan reports. Preconditioners whose
    // analysis is worth keeping (IncompleteCholesky's AMD ordering) analyse here; the others are
    // computed whole in factorize.)
    if constexpr (kAnalyzeApart) krylov_.analyzePattern(*op.matrix);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    if (definite_only_ && stencil_not_definite(op, summary)) return SolveStatus::kNotPositiveDefinite;
    if (const SolveStatus usable = check_preconditioner_matrix(*op.matrix, true, &summary.message);
        usable != SolveStatus::kSuccess)
      return usable;
    krylov_.setTolerance(options_.tolerance);
    limit_ = iteration_limit(options_, op.matrix->rows(), 20, 2e10);
    SolverOptions automatic = options_;
    automatic.max_iterations = 0;
    automatic_limit_ = iteration_limit(automatic, op.matrix->rows(), 20, 2e10);
    if constexpr (kAnalyzeApart)
      krylov_.factorize(*op.matrix);  // the preconditioner's numeric phase
    else
      krylov_.compute(*op.matrix);
    if (krylov_.info() != Eigen::Success) {
      if (definite_only_) {  // incomplete Cholesky met a non-positive pivot
        summary.message = "the preconditioner could not be computed";
        return SolveStatus::kNotPositiveDefinite;
      }
      // Empty rows were refused above; IncompleteLUT fails only when a row's sum of squares is 0,
      // which for nonzero entries is underflow (entries below about 1e-154), not singularity:
      // diag(1e-200, 1e-200) is perfectly conditioned.
      summary.message =
          "the incomplete-LU preconditioner could not be computed (a row norm underflows: entries below "
          "about 1e-154)";
      return SolveStatus::kNotApplicable;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    // Within the automatic iteration limit and without a time limit, one Eigen solve per column.
    // Otherwise the columns are solved in chunks of iterations, each restarting from the last
    // iterate, with the true residual measured between them: under a time limit a first chunk of 16
    // iterations, then chunks sized to fill 0.9 of the column's time left at the cost per iteration
    // measured so far (the clock is read between them, so a solve stops within about twice the
    // limit, and restarts, which slow CG down, stay few: doubling from 16 left CG at 2.7e-4 where
    // it had reached 1.1e-7 in 1 s; a first chunk of 1000 ran 70 s for a limit of
    // 1 s where an iteration of bicgstab cost 23 ms), else chunks of the automatic limit. A column
    // whose true residual is near the rounding floor (kStagnationFloor) and has not fallen by 10 %
    // over kStallChunks windows (a chunk, or under a time limit min(limit, 1000) iterations) has
    // stalled there (a tolerance of
    // 1e-300 with 2^31 iterations would otherwise run for hours), and its lowest iterate is kept.
    // A Krylov residual that ends 1e8 times above its start has diverged (bicgstab reached 1e137).
    const bool timed = options_.time_limit_seconds > 0;
    const int first_chunk = timed                       ? std::min(limit_, 16)
                            : limit_ > automatic_limit_ ? std::max(automatic_limit_, 1000)
                                                        : limit_;
    const int stall_window = timed ? std::min(limit_, 1000) : first_chunk;
    const SpMat& A = *factorized_operator().matrix;
    X.setZero(B.rows(), 3);
    IterationEnd end;
    end.limit = limit_;
    end.krylov = true;
    end.converged = true;
    end.residual = 0;
    int stalled = 0;  // the most iterations without a new low of a column that stagnated
    // Under a time limit each column that needs solving gets its share of it, so that every column
    // returns an iterate: the first one took the whole limit, and the X returned had two zero
    // columns and a true relative residual of 1 where the first had reached 1.4e-4.
    const auto started = std::chrono::steady_clock::now();
    int columns = 0, column = 0;
    for (int c = 0; c < 3; ++c) columns += B.col(c).isZero(0) ? 0 : 1;
    for (int c = 0; c < 3; ++c) {
      // A zero column has the solution zero. (Eigen's BiCGSTAB returns at once for it but leaves
      // its iteration count at the limit, which would be reported as the iterations of the solve.)
      if (B.col(c).isZero(0)) continue;  // (not squaredNorm() == 0, which a column of 1e-170s passes)
      const double deadline = options_.time_limit_seconds * double(++column) / double(columns);
      int used = 0;
      double error = 0;
      Eigen::VectorXd x = Eigen::VectorXd::Zero(B.rows());
      Eigen::VectorXd lowest_x = x;
      double lowest = 1;  // of x = 0
      int lowest_at = 0;
      int chunk = first_chunk;
      const double column_start = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      for (;;) {
        const int allowed = std::min(chunk, limit_ - used);
        krylov_.setMaxIterations(allowed);
        const Eigen::VectorXd guess = x;
        x = krylov_.solveWithGuess(B.col(c), x);
        int done = updates_done(allowed, guess, x);
        const bool breakdown = !x.allFinite() && guess.allFinite() && B.col(c).allFinite();
        if (breakdown) {
          done = last_finite_iterate(B.col(c), guess, done, x);
          end.breakdown = true;
        }
        used += done;
        error = krylov_.error();
        // (A call that did no update will not do one on the next call either: Eigen's BiCGSTAB
        // returns at once, not converged, when ‖b‖² is not finite. After a breakdown the next
        // call would break down again.)
        if (krylov_.info() != Eigen::NoConvergence || !x.allFinite() || used >= limit_ || done == 0 || breakdown) break;
        const double true_residual = relative_norm(B.col(c) - A * x, B.col(c));
        if (true_residual < lowest) {
          if (true_residual < 0.9 * lowest) lowest_at = used;  // progress, not a hair at the floor
          lowest = true_residual;
          lowest_x = x;
        }
        if (used - lowest_at >= kStallChunks * stall_window && lowest <= kStagnationFloor) {
          x = lowest_x;
          error = lowest;
          stalled = std::max(stalled, used - lowest_at);
          end.stagnation = "the residual fell by less than 10 % in the last " + std::to_string(stalled) + " iterations";
          break;
        }
        const double now = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
        if (timed && now >= deadline) {
          end.timed_out = true;
          if (lowest < true_residual) {  // the best iterate seen, X = 0 (residual 1) included
            x = lowest_x;
            error = lowest;
          }
          break;
        }
        if (timed) {  // the next chunk fills 0.9 of the time left, at the cost per iteration so far
          const double per_iteration = (now - column_start) / double(std::max(used, 1));
          const double fits = 0.9 * (deadline - now) / std::max(per_iteration, 1e-12);
          chunk = int(std::clamp(fits, 16.0, double(std::max(limit_ - used, 16))));
        }
      }
      X.col(c) = x;
      end.iterations = std::max(end.iterations, used);
      const IterationOptions defaults;
      if (krylov_.info() != Eigen::Success && x.allFinite() && std::isfinite(error)) {
        const double true_residual = relative_norm(B.col(c) - A * x, B.col(c));
        if (!(true_residual < defaults.divergence)) {
          end.diverged = true;
          error = true_residual;
        }
      }
      if (!x.allFinite() || !std::isfinite(error)) {
        end.diverged = true;
        end.residual = HUGE_VAL;
      } else {
        end.residual = std::max(end.residual, error);
      }
      if (krylov_.info() != Eigen::Success || !end.stagnation.empty()) end.converged = false;
      if (end.timed_out) end.converged = false;
      if (end.diverged) {
        end.converged = false;
        break;
      }
    }
    return finish_iteration(end, X, summary);
  }

 private:
  // After a breakdown (Eigen's BiCGSTAB divides by ρ = 0 once its residual vanishes, e.g. after one
  // step with an exact preconditioner, and the NaN spreads to x): the last finite iterate from
  // `guess`. Eigen's iterations are deterministic, so the largest count below `broken` whose
  // iterate is finite is found by bisection; x is set to it through a call of 0 iterations, which
  // leaves error() its true relative residual and info() Success when that passes the tolerance.
  // Returns the count.
  int last_finite_iterate(const Eigen::VectorXd& b, const Eigen::VectorXd& guess, int broken, Eigen::VectorXd& x) {
    int finite = 0;
    Eigen::VectorXd best = guess;
    while (broken - finite > 1) {
      const int mid = finite + (broken - finite) / 2;
      krylov_.setMaxIterations(mid);
      Eigen::VectorXd y = krylov_.solveWithGuess(b, guess);
      if (y.allFinite()) {
        finite = mid;
        best = std::move(y);
      } else {
        broken = mid;
      }
    }
    // Eigen's BiCGSTAB resets its iteration counter on its first restart (i = 0), so the count it
    // reports after a breakdown can be 1 where the iterate after one step was finite, and the
    // bisection above then ends on the guess: on the 4-unknown dome at tolerance 1e-300 (exact
    // preconditioner, so w = 0 after one step and the restart divides by it) it returned x = 0,
    // residual 1, beside the exact iterate after one step. The first limits are then tried one by
    // one and the finite iterate of lowest residual kept.
    if (finite == 0) {
      const SpMat& A = *factorized_operator().matrix;
      double lowest = relative_norm(b - A * guess, b);
      for (int limit = 1; limit <= kFirstLimitsTried; ++limit) {
        krylov_.setMaxIterations(limit);
        Eigen::VectorXd y = krylov_.solveWithGuess(b, guess);
        if (!y.allFinite()) continue;
        if (const double r = relative_norm(b - A * y, b); r < lowest) {
          lowest = r;
          best = std::move(y);
          finite = limit;
        }
      }
    }
    krylov_.setMaxIterations(0);
    x = krylov_.solveWithGuess(b, best);
    return finite;
  }
  static constexpr int kFirstLimitsTried = 64;

  // The iterations (updates of x, one product with A each) of the last Eigen solve. Eigen's
  // conjugate_gradient leaves its loop by `break` right after the update that passes its test,
  // before counting that update (Eigen 3.4, ConjugateGradient.h): a CG that converges reports one
  // iteration fewer than it did — 0 for a solve that took one step — unless it returned before any
  // update (a guess that already passes: x is then the guess, unchanged). BiCGSTAB counts
  // each iteration it completes.
  int updates_done(int allowed, const Eigen::VectorXd& guess, const Eigen::VectorXd& x) const {
    const int counted = int(krylov_.iterations());
    if constexpr (!kConjugateGradient) return counted;
    const bool stopped_on_test = krylov_.info() == Eigen::Success && counted < allowed;
    const bool returned_at_once = counted == 0 && guess == x;
    return stopped_on_test && !returned_at_once ? counted + 1 : counted;
  }

  static constexpr int kStallChunks = 3;
  static constexpr bool kConjugateGradient = IsConjugateGradient<Krylov>::value;
  static constexpr bool kAnalyzeApart = !std::is_same_v<typename Krylov::Preconditioner, Eigen::IncompleteLUT<double>>;
  std::string name_;
  bool definite_only_;
  int limit_ = 0;
  int automatic_limit_ = 0;  // the limit with max_iterations = 0 (iteration_limit)
  Krylov krylov_;
};

using Cg = Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::IdentityPreconditioner>;
using CgJacobi = Eigen::ConjugateGradient<SpMat, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>>;
using CgIc = Eigen::ConjugateGradient<SpMat, Eigen::Lower,
                                      Eigen::IncompleteCholesky<double, Eigen::Lower, Eigen::AMDOrdering<int>>>;
using Bicgstab = Eigen::BiCGSTAB<SpMat, Eigen::IncompleteLUT<double>>;

}  // namespace

std::unique_ptr<LinearSolver> make_cg(const SolverOptions& o) {
  return std::make_unique<EigenIterative<Cg>>("cg", true, o);
}
std::unique_ptr<LinearSolver> make_cg_jacobi(const SolverOptions& o) {
  return std::make_unique<EigenIterative<CgJacobi>>("cg-jacobi", true, o);
}
std::unique_ptr<LinearSolver> make_cg_ic(const SolverOptions& o) {
  return std::make_unique<EigenIterative<CgIc>>("cg-ic", true, o);
}
std::unique_ptr<LinearSolver> make_bicgstab(const SolverOptions& o) {
  return std::make_unique<EigenIterative<Bicgstab>>("bicgstab", false, o);
}

}  // namespace coons::solvers
