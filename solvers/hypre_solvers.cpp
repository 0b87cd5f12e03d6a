// hypre-amg: BoomerAMG-preconditioned PCG or GMRES on the assembled matrix through hypre's IJ
// interface (hypre_solvers.h); the Struct backends are in hypre_struct.cpp.
#include "hypre_solvers.h"

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "hypre_common.h"
#include "matrix_checks.h"

namespace coons::solvers {

namespace {

bool is_symmetric(const Eigen::SparseMatrix<double>& A) {
  const Eigen::SparseMatrix<double> At = A.transpose();
  return (A - At).norm() <= 1e-14 * A.norm();
}

class HypreAmgBackend : public hypre_detail::HypreBackend {
 public:
  explicit HypreAmgBackend(const SolverOptions& options) : HypreBackend(options) {}
  ~HypreAmgBackend() override { release(); }
  HypreAmgBackend(const HypreAmgBackend&) = delete;
  HypreAmgBackend& operator=(const HypreAmgBackend&) = delete;

  [[nodiscard]] std::string name() const override { return "hypre-amg"; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    if (op.matrix->rows() != op.matrix->cols() || op.matrix->rows() == 0) {
      summary.message = "needs a square, non-empty matrix";
      return SolveStatus::kNotApplicable;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    const SolveStatus checked = do_analyze(op, summary);
    if (checked != SolveStatus::kSuccess) return checked;
    // PCG for symmetric matrices unless the stencil's exact spectrum says indefinite; else GMRES.
    bool definite_known_false = false;
    if (!op.grid && op.stencil) definite_known_false = !(stencil_eigenvalue_range(*op.stencil).first > 0);
    gmres_ = definite_known_false || !is_symmetric(*op.matrix);
    if (const SolveStatus usable = check_preconditioner_matrix(*op.matrix, true, &summary.message);
        usable != SolveStatus::kSuccess)
      return usable;
    release();
    const HYPRE_Int error = build(*op.matrix);
    if (error != 0) {
      summary.message = "hypre's set-up failed (error flag " + std::to_string(error) + ")";
      return SolveStatus::kFailure;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const std::size_t local = rows_.size();
    std::vector<double> values(local), gathered;
    auto solve = [&](int c) {
      for (std::size_t p = 0; p < local; ++p) values[p] = B(rows_[p], c);
      set_vector(b_, values);
      std::fill(values.begin(), values.end(), 0.0);
      set_vector(x_, values);
      ColumnSolve out;
      if (gmres_) {
        out.method = "GMRES";
        out.error = HYPRE_ParCSRGMRESSolve(solver_, parcsr_, par_b_, par_x_);
        HYPRE_GMRESGetNumIterations(solver_, &out.iterations);
        HYPRE_GMRESGetFinalRelativeResidualNorm(solver_, &out.residual);
      } else {
        out.error = HYPRE_ParCSRPCGSolve(solver_, parcsr_, par_b_, par_x_);
        HYPRE_PCGGetNumIterations(solver_, &out.iterations);
        HYPRE_PCGGetFinalRelativeResidualNorm(solver_, &out.residual);
      }
      return out;
    };
    auto read = [&](int c) {
      if (local > 0) HYPRE_IJVectorGetValues(x_, HYPRE_Int(local), rows_.data(), values.data());
      hypre_detail::all_gather_blocks(values, B.rows(), 1, gathered);
      X.col(c) = Eigen::Map<const Eigen::VectorXd>(gathered.data(), B.rows());
    };
    return solve_columns(B, X, summary, solve, read);
  }

 private:
  void set_vector(HYPRE_IJVector v, const std::vector<double>& values) const {
    if (!rows_.empty()) HYPRE_IJVectorSetValues(v, HYPRE_Int(rows_.size()), rows_.data(), values.data());
    HYPRE_IJVectorAssemble(v);
  }

  // This rank's block of rows of A as an IJ (ParCSR) matrix, the two vectors, AMG and the Krylov
  // method, set up once.
  HYPRE_Int build(const Eigen::SparseMatrix<double>& A) {
    MPI_Comm comm = hypre_detail::communicator();
    const auto [first, last] = block_of(A.rows(), mpi_rank(), mpi_size());
    const auto lower = HYPRE_BigInt(first), upper = HYPRE_BigInt(last - 1);
    rows_.resize(std::size_t(last - first));
    std::iota(rows_.begin(), rows_.end(), lower);

    const Eigen::SparseMatrix<double, Eigen::RowMajor> R =
        A.middleRows(Eigen::Index(first), Eigen::Index(last - first));
    std::vector<HYPRE_Int> counts(rows_.size());
    for (std::size_t p = 0; p < rows_.size(); ++p)
      counts[p] = HYPRE_Int(R.outerIndexPtr()[p + 1] - R.outerIndexPtr()[p]);
    std::vector<HYPRE_BigInt> columns(R.innerIndexPtr(), R.innerIndexPtr() + R.nonZeros());

    HYPRE_IJMatrixCreate(comm, lower, upper, lower, upper, &A_);
    HYPRE_IJMatrixSetObjectType(A_, HYPRE_PARCSR);
    if (!counts.empty()) HYPRE_IJMatrixSetRowSizes(A_, counts.data());
    HYPRE_IJMatrixInitialize(A_);
    if (!rows_.empty())
      HYPRE_IJMatrixSetValues(A_, HYPRE_Int(rows_.size()), counts.data(), rows_.data(), columns.data(), R.valuePtr());
    HYPRE_IJMatrixAssemble(A_);
    HYPRE_IJMatrixGetObject(A_, reinterpret_cast<void**>(&parcsr_));
    for (auto [v, par] : {std::pair{&b_, &par_b_}, std::pair{&x_, &par_x_}}) {
      HYPRE_IJVectorCreate(comm, lower, upper, v);
      HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
      HYPRE_IJVectorInitialize(*v);
      HYPRE_IJVectorAssemble(*v);
      HYPRE_IJVectorGetObject(*v, reinterpret_cast<void**>(par));
    }

    HYPRE_BoomerAMGCreate(&amg_);
    HYPRE_BoomerAMGSetPrintLevel(amg_, 0);
    HYPRE_BoomerAMGSetCoarsenType(amg_, 10);  // HMIS
    HYPRE_BoomerAMGSetInterpType(amg_, 6);    // extended+i
    HYPRE_BoomerAMGSetPMaxElmts(amg_, 4);
    HYPRE_BoomerAMGSetStrongThreshold(amg_, 0.25);
    HYPRE_BoomerAMGSetRelaxType(amg_, 8);  // l1 symmetric hybrid Gauss-Seidel: a symmetric V-cycle
    HYPRE_BoomerAMGSetNumSweeps(amg_, 1);
    HYPRE_BoomerAMGSetMaxIter(amg_, 1);
    HYPRE_BoomerAMGSetTol(amg_, 0.0);
    HYPRE_Int error = 0;
    if (gmres_) {
      HYPRE_ParCSRGMRESCreate(comm, &solver_);
      HYPRE_GMRESSetKDim(solver_, 50);
      HYPRE_GMRESSetTol(solver_, options_.tolerance);
      HYPRE_GMRESSetMaxIter(solver_, limit());
      // Logging 0: with it, hypre prints an "ERROR detected by Hypre" banner on stdout (inside a
      // JSON report) on overflowing input. Iterations and the final residual are kept without it.
      HYPRE_GMRESSetLogging(solver_, 0);
      HYPRE_GMRESSetPrintLevel(solver_, 0);
      HYPRE_ParCSRGMRESSetPrecond(solver_, HYPRE_BoomerAMGSolve, HYPRE_BoomerAMGSetup, amg_);
      error = HYPRE_ParCSRGMRESSetup(solver_, parcsr_, par_b_, par_x_);
    } else {
      HYPRE_ParCSRPCGCreate(comm, &solver_);
      HYPRE_PCGSetTol(solver_, options_.tolerance);
      HYPRE_PCGSetTwoNorm(solver_, 1);  // stop at ‖r‖₂ ≤ tolerance·‖b‖₂
      HYPRE_PCGSetMaxIter(solver_, limit());
      // Logging 0: with it, hypre prints an "ERROR detected by Hypre" banner on stdout (inside a
      // JSON report) on overflowing input. Iterations and the final residual are kept without it.
      HYPRE_PCGSetLogging(solver_, 0);
      HYPRE_PCGSetPrintLevel(solver_, 0);
      HYPRE_ParCSRPCGSetPrecond(solver_, HYPRE_BoomerAMGSolve, HYPRE_BoomerAMGSetup, amg_);
      error = HYPRE_ParCSRPCGSetup(solver_, parcsr_, par_b_, par_x_);
    }
    HYPRE_ClearAllErrors();
    return error;
  }

  void release() {
    if (solver_) (gmres_built_ ? HYPRE_ParCSRGMRESDestroy : HYPRE_ParCSRPCGDestroy)(solver_);
    if (amg_) HYPRE_BoomerAMGDestroy(amg_);
    if (x_) HYPRE_IJVectorDestroy(x_);
    if (b_) HYPRE_IJVectorDestroy(b_);
    if (A_) HYPRE_IJMatrixDestroy(A_);
    solver_ = amg_ = nullptr;
    x_ = b_ = nullptr;
    A_ = nullptr;
    parcsr_ = nullptr;
    par_b_ = par_x_ = nullptr;
    gmres_built_ = gmres_;
  }

  bool gmres_ = false;              // the method of the next build
  bool gmres_built_ = false;        // the method of the solver held now
  std::vector<HYPRE_BigInt> rows_;  // this rank's rows
  HYPRE_IJMatrix A_ = nullptr;
  HYPRE_ParCSRMatrix parcsr_ = nullptr;
  HYPRE_IJVector b_ = nullptr, x_ = nullptr;
  HYPRE_ParVector par_b_ = nullptr, par_x_ = nullptr;
  HYPRE_Solver solver_ = nullptr, amg_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> make_hypre_amg(const SolverOptions& o) { return std::make_unique<HypreAmgBackend>(o); }

}  // namespace coons::solvers
