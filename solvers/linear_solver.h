// The one life cycle of every linear-solver backend of coons, modelled on Eigen's sparse solvers
// (analyzePattern / factorize / solve) and Ceres's options and summary objects:
//
//   analyze(op)    depends only on the sparsity pattern or the grid size (orderings, plans);
//   factorize(op)  depends on the values (for mask systems: on α);
//   solve(B, X)    any number of times, B and X #unknowns by 3 (x, y and z at once).
//
// Backends never throw for numerical trouble: a failure is a status in the summary.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "column_scaling.h"
#include "grid_stencil.h"

namespace coons::solvers {

struct StencilOperator;  // stencil_operator.h: 3×3 or 5×5 stencils with a free mask

enum class SolveStatus {
  kSuccess,
  kNotConverged,         //!< iteration limit reached before the tolerance
  kDiverged,             //!< an iteration grew without bound (e.g. Jacobi for α < 0)
  kNotPositiveDefinite,  //!< a Cholesky-type method met a non-positive pivot
  kSingular,             //!< the operator is singular (to working precision)
  kNotApplicable,        //!< the backend cannot handle this operator (e.g. needs a grid stencil)
  kFailure,              //!< anything else, explained by the message
};

//! "success", "not_converged", "diverged", "not_positive_definite", "singular", ...
const char* to_string(SolveStatus status);

//! Fill-reducing orderings of the direct backends. kAuto is each backend's best choice here;
//! kCholmodDefault lets CHOLMOD try METIS and AMD itself and keep the better (its default).
enum class Ordering { kAuto, kNatural, kAmd, kColamd, kMetis, kNestedDissection, kCholmodDefault };
const char* to_string(Ordering ordering);

struct SolverOptions {
  double tolerance = 1e-12;  //!< iterative: stop at ‖Ax − b‖/‖b‖ ≤ tolerance
  //! iterative: the iteration limit; 0 is automatic and always finite (see iteration_limit()).
  int max_iterations = 0;
  //! iterative: stop after this many seconds of one solve (0: no time limit; the iteration
  //! limit holds either way). Hitting either limit is kNotConverged with the residual reached.
  double time_limit_seconds = 0;
  //! transform solvers: choose FFTW plans by timing (FFTW_MEASURE). Faster transforms, but the
  //! chosen algorithm, and so the last digits, may differ between runs. Off by default: plans
  //! are FFTW_ESTIMATE, and reruns give byte-identical results. (FFTW keeps measured plans as
  //! process-wide wisdom, which later estimated plans of the same size reuse: a program that
  //! wants identical results should not mix the two modes.)
  bool measure_fft_plans = false;
  //! threads for the backends that use them (dst: rows and column strips of its transforms; fast:
  //! sine modes and rows, in a sweep whole members; mg, mg-cg, gmres: the columns of B side by side, and
  //! with 2 threads the third column on the level loops). 1 by default; 0 means every core. dst, fast
  //! and mg give the same result bit for bit for every count. Ignored without OpenMP.
  int threads = 1;
  double sor_omega = 1.0;               //!< gauss-seidel: over-relaxation factor in (0, 2)
  Ordering ordering = Ordering::kAuto;  //!< direct: fill-reducing ordering
  bool compute_residual = true;         //!< compute the true residual after solve (costs one apply)
  double singular_residual = 1e-6;      //!< exact solvers: a larger true residual means "singular"
  //! every backend: after a successful solve, an estimate of κ∞(A) from three
  //! more solves by the same backend in SolveSummary::condition_estimate (a lower bound when those
  //! solves are exact), the normwise backward error, and a message when the forward error bound
  //! they give exceeds kForwardErrorNotice (a small residual does not show a large error). Off by
  //! default (the CLI turns it on for the reports it writes); needs compute_residual.
  bool estimate_condition = false;

  //! True when the options are usable; otherwise explains why in *why ("<field> <reason>").
  bool is_valid(std::string* why) const;
};

//! The fields of SolverOptions that can be unusable.
enum class SolverOptionsField {
  kNone,
  kTolerance,
  kMaxIterations,
  kTimeLimitSeconds,
  kSorOmega,
  kSingularResidual,
  kThreads
};
//! The field's name in SolverOptions ("tolerance", "max_iterations", ...; "" for kNone).
const char* to_string(SolverOptionsField field);

//! What makes solver options unusable: the first such field and why (reason without the field's
//! name, e.g. "must lie in (0, 1)"); field kNone when they are usable.
struct SolverOptionsProblem {
  SolverOptionsField field = SolverOptionsField::kNone;
  std::string reason;
};
SolverOptionsProblem options_problem(const SolverOptions& options);

//! Upper bound of SolverOptions::threads.
constexpr int kMaxThreads = 256;

//! A forward error bound κ·ε above this is said in the message of a successful solve
//! (SolverOptions::estimate_condition): the answer may be wrong in its sixth digit.
constexpr double kForwardErrorNotice = 1e-6;

//! The number of threads `threads` asks for: itself when positive, the machine's cores for 0
//! (at least 1, at most kMaxThreads).
int resolved_threads(int threads);

//! The calling thread's index in an OpenMP parallel region (0 outside one, or without OpenMP):
//! the slot of its per-thread scratch in the threaded backends.
int thread_index();

//! The number of threads of the enclosing OpenMP parallel region (1 outside one, or without OpenMP).
int team_size();

struct SolveSummary {
  std::string solver;  //!< registry name of the backend
  SolveStatus status = SolveStatus::kSuccess;
  std::string message;           //!< empty on success, otherwise why
  int iterations = 0;            //!< 1 for direct and transform solvers
  double relative_residual = 0;  //!< max over columns of ‖A x − b‖ / ‖b‖ (‖b‖ = 0: ‖A x‖)
  double analyze_seconds = 0, factorize_seconds = 0, solve_seconds = 0;
  std::string ordering;      //!< fill-reducing ordering used, if any
  long long factor_nnz = 0;  //!< non-zeros of the factor(s), 0 when there is none
  //! A lower bound of κ∞(A) = ‖A‖∞‖A⁻¹‖∞ when it was estimated (SolverOptions::estimate_condition,
  //! or an ill-conditioned verdict), else 0.
  double condition_estimate = 0;
  //! max over columns of ‖b − A x‖∞ / (‖A‖∞‖x‖∞ + ‖b‖∞) when the condition was estimated, else 0:
  //! near ε for a backward-stable exact solve, up to the tolerance for an iteration.
  double normwise_backward_error = 0;

  [[nodiscard]] bool ok() const { return status == SolveStatus::kSuccess; }
  //! κ·max(ε, normwise backward error): about the largest relative forward error of the solution
  //! (κ·ε for a backward-stable exact solve; 0 when not estimated).
  [[nodiscard]] double forward_error_bound() const;
  [[nodiscard]] std::string brief_report() const;
};

//! The operator handed to a backend: the assembled matrix and/or its grid stencil.
//! Either may be absent; a backend that needs the missing one reports kNotApplicable.
//! The matrix is borrowed: it must outlive the factorize/solve calls that use it.
struct LinearOperator {
  const Eigen::SparseMatrix<double>* matrix = nullptr;
  std::optional<GridStencil> stencil;
  //! Borrowed like the matrix: a 3×3 or 5×5 stencil with a free mask (the multigrid backends).
  const StencilOperator* grid = nullptr;

  [[nodiscard]] Eigen::Index size() const;
};

class LinearSolver {
 public:
  explicit LinearSolver(SolverOptions options) : options_(options) {}
  virtual ~LinearSolver() = default;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  [[nodiscard]] virtual std::string name() const = 0;
  //! Direct and transform solvers are exact: a large true residual after them means the
  //! operator is numerically singular. Iterative solvers judge convergence themselves.
  [[nodiscard]] virtual bool exact() const { return true; }

  //! Pattern / grid dependent set-up. Returns the status (also kept for summary()).
  SolveStatus analyze(const LinearOperator& op);
  //! Value dependent set-up; analyze() is called first if it was not called for this size.
  SolveStatus factorize(const LinearOperator& op);
  //! X = A⁻¹ B for the last factorized operator. B is left unchanged.
  SolveSummary solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X);
  //! analyze + factorize + solve.
  SolveSummary compute_and_solve(const LinearOperator& op, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X);

  //! One member of a sweep: an operator (same grid and pattern for every member) and the
  //! weights of its right-hand side in the sweep's basis: B = Σ_r rhs_weights[r] · basis[r].
  struct SweepMember {
    LinearOperator op;
    std::vector<double> rhs_weights;
  };
  using SweepSink = std::function<void(std::size_t member, const Eigen::MatrixX3d& X, const SolveSummary& summary)>;

  //! Solve a family of systems that share everything but the values (e.g. an α sweep, whose
  //! right-hand side is affine in α), reusing what does not depend on the values: the analysis
  //! for direct solvers, the transforms of the basis right-hand sides for structured ones.
  //! sink(k, X_k, summary_k) is called for each member in order, from the calling thread, never
  //! concurrently. The one loop of every backend: per member factorize (a failure is passed on
  //! with X = 0), do_sweep_solve, and the same verdict on the true residual as solve().
  //! With SolverOptions::threads ≥ 2 a backend that offers sweep workers (fast) solves that
  //! many members side by side, one per thread with one-thread kernels, each through the same
  //! loop body; X_k and summary_k (but its timings) are those of the one-thread sweep, bit for bit.
  //! After such a sweep summary() is the last member's, and solve() needs a factorize() first.
  void sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis, const std::vector<SweepMember>& members,
             const SweepSink& sink);

  [[nodiscard]] const SolverOptions& options() const { return options_; }
  //! The summary of the last call (statuses of analyze/factorize are kept here too).
  [[nodiscard]] const SolveSummary& summary() const { return summary_; }

 protected:
  virtual SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) = 0;
  virtual SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) = 0;
  //! Fills X; sets iterations (and may set the status). Iterative backends end with
  //! finish_iteration(), which gives every one the same verdict and message.
  virtual SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) = 0;
  //! The exponents by which solve() scales the columns of B before do_solve(B) (column_scaling.h);
  //! the default reads B once (rhs_exponents). A backend that reads all of B anyway may override
  //! it to find them in that pass and keep what it read for the do_solve() on this B that comes
  //! next (called just before it, with B itself when every exponent is 0).
  virtual ColumnExponents rhs_scaling(const Eigen::MatrixX3d& B) { return rhs_exponents(B); }

  //! X for a factorized sweep member whose right-hand side is Σ_r weights[r]·basis[r] (weights
  //! cut to the basis size). The default forms it and calls do_solve(); structured backends
  //! override it to reuse transforms of the basis across members.
  virtual SolveStatus do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                                     Eigen::MatrixX3d& X, SolveSummary& summary);
  //! Called at the start of every sweep (to forget what a previous sweep cached).
  virtual void do_begin_sweep() {}
  //! A backend that can solve several members of a sweep at once (SolverOptions::threads ≥ 2)
  //! returns here a new solver of its kind for one thread (options.threads = 1), analyzed for op's
  //! grid, that reads what this solver keeps of the sweep's basis (made once, shared read-only).
  //! sweep() asks for one per thread before it starts, from the calling thread. nullptr (the
  //! default, and on any failure) keeps the members one after another, threads inside each solve.
  virtual std::unique_ptr<LinearSolver> make_sweep_worker(const std::vector<Eigen::MatrixX3d>& basis,
                                                          const LinearOperator& op);

  //! True, with "needs the assembled matrix" in the summary, when op has no matrix (the caller
  //! returns kNotApplicable); lacks_stencil the same for the grid stencil.
  static bool lacks_matrix(const LinearOperator& op, SolveSummary& summary);
  static bool lacks_stencil(const LinearOperator& op, SolveSummary& summary);

  //! How an iteration ended, for finish_iteration().
  struct IterationEnd {
    int iterations = 0;
    int limit = 0;           //!< the iteration limit in force
    double initial = 1;      //!< relative residual at the start (x = 0: 1)
    double residual = 1;     //!< relative residual reached (estimate or true)
    bool converged = false;  //!< the backend's own test passed
    bool timed_out = false;  //!< stopped by options.time_limit_seconds
    bool diverged = false;   //!< stopped because the residual grew without bound
    //! A residual that ends above its start is divergence for a stationary iteration (Jacobi,
    //! Gauss–Seidel), not for a Krylov method, whose residual norm may rise before it falls (CG
    //! after one step on a definite system: 2.28).
    bool krylov = false;
    //! Convergence is guaranteed (SOR with 0 < ω < 2 on a positive definite system, Ostrowski–Reich):
    //! its residual may also rise before it falls (ω = 1.9 at α = −1/4: 1.85 after one sweep, 2.2
    //! after 5, 0.12 after 500), so a residual above its start at the limit is not divergence.
    bool convergent = false;
    //! stopped because the method broke down (a zero divisor in its recurrence); the residual is
    //! that of the last finite iterate
    bool breakdown = false;
    //! stopped because the residual stopped falling (at the rounding floor of the system, where a
    //! tolerance such as 1e-300 cannot be met): kNotConverged, not hours spent on an iteration
    //! limit of 2^31. Non-empty: how that showed ("no smaller residual in the last 3000 iterations").
    std::string stagnation;
  };
  //! The one verdict of every iterative backend: success when converged; kDiverged when the
  //! residual grew (1e8-fold, to overflow, or, stationary iterations only, ends above its start) —
  //! X is then set to zero;
  //! otherwise kNotConverged, naming the limit that stopped it. Sets iterations, the residual
  //! reached (finite: an overflowed one is reported as the largest double and said so) and a
  //! message that agrees with both.
  SolveStatus finish_iteration(const IterationEnd& end, Eigen::MatrixX3d& X, SolveSummary& summary) const;
  //! True once the current solve has run options.time_limit_seconds (never without a limit).
  [[nodiscard]] bool out_of_time() const;
  //! After an exact solve: the true residual (when options.compute_residual) and the verdict
  //! solve() gives (not finite → kFailure; above options.singular_residual → kSingular). For
  //! backends that solve outside solve() too (structured sweeps).
  void judge_exact_solve(const LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X,
                         SolveSummary& summary) const;
  //! After judge_exact_solve said kSingular on an assembled matrix: kSuccess, with a message that
  //! says "ill-conditioned", when the solve is backward stable (normwise backward error ≤ 1e−12)
  //! and a condition estimate (a lower bound from three more solves) lies below 0.1/ε; otherwise
  //! the verdict stays and the message gains the estimate.
  void judge_ill_conditioned(const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X);
  //! After a successful solve of B (X the solution) with options.estimate_condition, on the
  //! assembled matrix or the grid stencil: the condition estimate and the normwise backward error
  //! in the summary, and the "ill-conditioned" message when the forward error bound exceeds
  //! kForwardErrorNotice.
  void note_condition(const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X);
  //! norm_a (‖A‖∞ of the operator factorized) · max ‖A⁻¹g‖∞ / ‖g‖∞ over three fixed ±1 vectors g
  //! (three more solves by this backend): a lower bound of κ∞(A) when they are exact, usually
  //! within a small factor; NaN when a solve fails (an iteration that does not converge on them).
  [[nodiscard]] double condition_lower_bound(double norm_a);
  //! The larger of condition_lower_bound(norm_a) and `solution_bound` (‖A‖∞‖x‖∞ / (‖b‖∞ + ‖r‖∞) of
  //! a solve, also a lower bound of κ∞ for a regular A); NaN when the probes fail.
  [[nodiscard]] double condition_estimate(double norm_a, double solution_bound);

  //! The operator of the last factorize (set when do_factorize returns; do_solve may read it).
  [[nodiscard]] const LinearOperator& factorized_operator() const { return op_; }

  SolverOptions options_;

 private:
  // The verdict on X after do_solve or do_sweep_solve (see solve()).
  void judge_solution(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X);
  // Corrections judge_solution tries when an iteration's true residual misses the tolerance.
  static constexpr int kRefinementRounds = 2;
  // One member of a sweep on this solver: factorize, do_sweep_solve and the verdict, into X and
  // summary_ (X = 0 when factorize fails).
  void sweep_member(const std::vector<Eigen::MatrixX3d>& basis, const SweepMember& member, Eigen::MatrixX3d& X);
  // The members side by side on `workers`, batch by batch, then the sink in member order.
  void sweep_on_workers(const std::vector<std::unique_ptr<LinearSolver>>& workers,
                        const std::vector<Eigen::MatrixX3d>& basis, const std::vector<SweepMember>& members,
                        const SweepSink& sink);

  SolveSummary summary_;
  std::chrono::steady_clock::time_point solve_start_;
  LinearOperator op_;  // the operator of the last factorize (for the residual)
  Eigen::Index analyzed_size_ = -1;
  bool factorized_ = false;
};

//! The iteration limit of an iterative backend: options.max_iterations when positive; otherwise
//! automatic and finite: per_unknown · unknowns, but no more than work / unknowns (so that the
//! whole iteration costs at most about `work` point updates), 2,000,000 at the most and 100 at
//! the least. The Krylov backends use (20, 2e10), the mask iterations (1000, 1e8): a 64×64 net
//! (3844 unknowns) stops Gauss–Seidel after 26,000 sweeps, about a second.
int iteration_limit(const SolverOptions& options, Eigen::Index unknowns, int per_unknown, double work);

//! A number as printf's %g prints it (1e-12, not 0.000000).
std::string format_g(double value);

//! Σ_r weights[r]·basis[r] (#rows of the first member; zero without terms).
Eigen::MatrixX3d combine_rhs(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::Index rows);

//! max over columns of ‖A x − b‖/‖b‖, with A from the matrix or, when absent, the stencil.
double relative_residual(const LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X);
//! AX = op·X through op's matrix, else its stencil, else its grid operator; false when it has none.
bool apply_operator(const LinearOperator& op, const Eigen::MatrixX3d& X, Eigen::MatrixXd& AX);

}  // namespace coons::solvers
