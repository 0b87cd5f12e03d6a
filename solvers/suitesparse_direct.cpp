#include "suitesparse_direct.h"

#include <cholmod.h>
#include <umfpack.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "matrix_checks.h"

namespace coons::solvers {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

// A cholmod_sparse that borrows the lower triangle of a symmetric Eigen matrix (stype −1).
cholmod_sparse view_lower(const SpMat& A) {
  cholmod_sparse s{};
  s.nrow = size_t(A.rows());
  s.ncol = size_t(A.cols());
  s.nzmax = size_t(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.x = const_cast<double*>(A.valuePtr());
  s.stype = -1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

cholmod_dense view_dense(const Eigen::MatrixX3d& B) {
  cholmod_dense d{};
  d.nrow = size_t(B.rows());
  d.ncol = 3;
  d.nzmax = size_t(B.size());
  d.d = size_t(B.rows());
  d.x = const_cast<double*>(B.data());
  d.xtype = CHOLMOD_REAL;
  d.dtype = CHOLMOD_DOUBLE;
  return d;
}

const char* cholmod_ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL:
      return "natural";
    case CHOLMOD_GIVEN:
      return "given";
    case CHOLMOD_AMD:
      return "amd";
    case CHOLMOD_METIS:
      return "metis";
    case CHOLMOD_NESDIS:
      return "nested-dissection";
    case CHOLMOD_COLAMD:
      return "colamd";
    case CHOLMOD_POSTORDERED:
      return "natural-postordered";
    default:
      return "unknown";
  }
}

class Cholmod : public LinearSolver {
 public:
  Cholmod(bool supernodal, const SolverOptions& options) : LinearSolver(options), supernodal_(supernodal) {
    cholmod_start(&common_);
    common_.supernodal = supernodal ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    common_.final_ll = supernodal ? 1 : 0;
    common_.print = 0;
    common_.error_handler = nullptr;
    common_.nmethods = 1;
    switch (options.ordering) {
      case Ordering::kAuto:
      case Ordering::kAmd:
      case Ordering::kColamd:
        common_.method[0].ordering = CHOLMOD_AMD;
        break;  // COLAMD is for A·Aᵀ, AMD for A
      case Ordering::kMetis:
        common_.method[0].ordering = CHOLMOD_METIS;
        break;
      case Ordering::kNestedDissection:
        common_.method[0].ordering = CHOLMOD_NESDIS;
        break;
      case Ordering::kNatural:
        common_.method[0].ordering = CHOLMOD_NATURAL;
        break;
      case Ordering::kCholmodDefault:
        common_.nmethods = 0;
        break;  // CHOLMOD tries METIS and AMD
    }
    common_.postorder = 1;
  }
  ~Cholmod() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }
  [[nodiscard]] std::string name() const override { return supernodal_ ? "cholmod" : "cholmod-simplicial"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_sparse A = view_lower(*op.matrix);
    factor_ = cholmod_analyze(&A, &common_);
    if (!factor_ || common_.status < CHOLMOD_OK) {
      // a matrix with no entries fails the analysis (status -4): say that it is singular, and where
      if (const SolveStatus empty = check_preconditioner_matrix(*op.matrix, false, &summary.message);
          empty != SolveStatus::kSuccess)
        return empty;
      summary.message = "cholmod_analyze failed, status " + std::to_string(common_.status);
      return SolveStatus::kFailure;
    }
    summary.ordering = cholmod_ordering_name(factor_->ordering);
    summary.factor_nnz = static_cast<long long>(common_.lnz);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!op.matrix || !factor_) {
      summary.message = "needs the assembled matrix";
      return SolveStatus::kNotApplicable;
    }
    cholmod_sparse A = view_lower(*op.matrix);
    cholmod_factorize(&A, factor_, &common_);
    summary.factor_nnz = static_cast<long long>(common_.lnz);
    if (common_.status == CHOLMOD_NOT_POSDEF)
      return judge_stopped(*op.matrix, not_positive_definite_message(), summary);
    if (common_.status < CHOLMOD_OK) {
      summary.message = "cholmod_factorize failed, status " + std::to_string(common_.status);
      return SolveStatus::kFailure;
    }
    if (!supernodal_) {
      const SolveStatus status = judge_ldlt_diagonal(*op.matrix, summary);
      // zero pivots and no negative one: semidefinite and singular, or an indefinite A whose
      // negative eigenvalue the rounding of a pivot hid (−2e-15 counted as zero; review 2026-12-04)
      if (status == SolveStatus::kSingular) return judge_stopped(*op.matrix, summary.message, summary);
      return status;
    }
    if (const std::string zero = zero_supernodal_pivot(*op.matrix); !zero.empty())
      return judge_stopped(*op.matrix, zero, summary);
    return SolveStatus::kSuccess;
  }

  // The supernodal LLᵀ went through: a pivot L_jj² below kSingularPivot of its diagonal entry (as
  // eigen-llt tests it, is_zero_pivot) is "a pivot of L is (numerically) zero at column K (…)",
  // else "". (A singular Neumann Laplacian scaled D·A·D was solved as a success, where the other
  // Cholesky-type backends say singular; review of 2026-12-04.) Column j of supernode s holds
  // L_jj at px[s] + (j − super[s])·(nsrow + 1), nsrow = pi[s + 1] − pi[s].
  [[nodiscard]] std::string zero_supernodal_pivot(const Eigen::SparseMatrix<double>& A) const {
    if (!factor_->is_super) return "";
    const auto* super = static_cast<const int*>(factor_->super);
    const auto* pi = static_cast<const int*>(factor_->pi);
    const auto* px = static_cast<const int*>(factor_->px);
    const auto* x = static_cast<const double*>(factor_->x);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    const Eigen::VectorXd diagonal = A.diagonal();
    std::vector<double> pivots(factor_->n);
    double largest = 0;
    for (size_t s = 0; s < factor_->nsuper; ++s) {
      const int nsrow = pi[s + 1] - pi[s];
      for (int j = super[s]; j < super[s + 1]; ++j) {
        const double l = x[px[s] + std::size_t(j - super[s]) * std::size_t(nsrow + 1)];
        pivots[std::size_t(j)] = l * l;
        largest = std::max(largest, l * l);
      }
    }
    for (size_t j = 0; j < factor_->n; ++j)
      if (is_zero_pivot(pivots[j], diagonal(perm ? perm[j] : Eigen::Index(j)), largest))
        return "a pivot of L is (numerically) zero (its square below 1e-13 of its diagonal entry) at " +
               column_of_pivot(j);
    return "";
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    summary.iterations = 1;
    if (!solve_with_factor(B, X)) {
      summary.message = "cholmod_solve failed, status " + std::to_string(common_.status);
      return SolveStatus::kFailure;
    }
    return SolveStatus::kSuccess;
  }

  // X = A⁻¹B with the factor held (also the raised one of judge_stopped); false when cholmod_solve fails.
  bool solve_with_factor(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
    cholmod_dense b = view_dense(B);
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor_, &b, &common_);
    if (!x) return false;
    X = Eigen::Map<const Eigen::MatrixX3d>(static_cast<const double*>(x->x), B.rows(), 3);
    cholmod_free_dense(&x, &common_);
    return true;
  }

 private:
  // "column K (pivot P of the amd ordering)": P is a pivot in CHOLMOD's fill-reducing order,
  // L->Perm[P] the column K of the matrix it belongs to ("pivot P" when there is no Perm).
  [[nodiscard]] std::string column_of_pivot(std::size_t pivot) const {
    const auto* perm = static_cast<const int*>(factor_->Perm);
    if (pivot >= factor_->n || !perm) return "pivot " + std::to_string(pivot);
    return "column " + std::to_string(perm[pivot]) + " (pivot " + std::to_string(pivot) + " of the " +
           cholmod_ordering_name(factor_->ordering) + " ordering)";
  }

  // The supernodal LLᵀ stops at the failed pivot, L->minor.
  [[nodiscard]] std::string not_positive_definite_message() const {
    return "not positive definite at " + column_of_pivot(std::size_t(factor_->minor));
  }

  // The factorisation stopped at a pivot ≤ 0 (or LDLᵀ found zero pivots and no negative one; `stopped`
  // says which): singular or indefinite, which the factorisation of
  // A raised on its diagonal and inverse iteration with it tell apart (semidefinite_verdict, as
  // eigen-ldlt does). The raised factor stays behind, but a failed factorize() leaves nothing to
  // solve with.
  SolveStatus judge_stopped(const Eigen::SparseMatrix<double>& M, const std::string& stopped, SolveSummary& summary) {
    const Eigen::SparseMatrix<double> raised_matrix = raise_diagonal(M, kSemidefiniteShift);
    cholmod_sparse A = view_lower(raised_matrix);
    cholmod_factorize(&A, factor_, &common_);
    bool definite = common_.status == CHOLMOD_OK;
    if (definite && !supernodal_) {  // LDLᵀ: every entry of D positive
      const auto* p = static_cast<const int*>(factor_->p);
      const auto* x = static_cast<const double*>(factor_->x);
      for (size_t j = 0; j < factor_->n; ++j) definite = definite && x[p[j]] > 0;
    }
    std::optional<ScaledEigenvalue> raised;
    if (definite)
      raised = smallest_scaled_eigenvalue(M, [&](const Eigen::MatrixX3d& B) -> Eigen::MatrixX3d {
        Eigen::MatrixX3d X;
        if (!solve_with_factor(B, X)) X.setConstant(B.rows(), 3, std::numeric_limits<double>::quiet_NaN());
        return X;
      });
    common_.status = CHOLMOD_OK;  // (the diagnosis is over; the next factorisation starts afresh)
    return semidefinite_verdict(M, raised, stopped, &summary.message);
  }

  // Simplicial LDLᵀ keeps going through negative pivots: report them as eigen-ldlt does, and name
  // the first one's column as the supernodal message does (LLᵀ would have stopped there: the pivots
  // before it are those of a definite leading block).
  // A zero pivot as eigen-ldlt judges it (is_zero_pivot, matrix_checks.h).
  SolveStatus judge_ldlt_diagonal(const Eigen::SparseMatrix<double>& A, SolveSummary& summary) const {
    const auto* p = static_cast<const int*>(factor_->p);
    const auto* x = static_cast<const double*>(factor_->x);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    const Eigen::VectorXd diagonal = A.diagonal();
    double largest = 0;
    for (size_t j = 0; j < factor_->n; ++j) largest = std::max(largest, std::abs(x[p[j]]));
    long zero = 0, negative = 0;
    size_t first_zero = factor_->n, first_negative = factor_->n;
    for (size_t j = 0; j < factor_->n; ++j) {
      const double d = x[p[j]];
      if (is_zero_pivot(d, diagonal(perm ? perm[j] : Eigen::Index(j)), largest)) {
        if (zero++ == 0) first_zero = j;
      } else if (d < 0) {
        if (negative++ == 0) first_negative = j;
      }
    }
    // Negative pivots first: D has A's inertia, so they make A indefinite, and a zero pivot
    // among them is where elimination without pivoting landed (as eigen-ldlt judges, eigen_direct.cpp).
    if (negative) {
      summary.message = "not positive definite at " + column_of_pivot(first_negative) + "; " +
                        std::to_string(negative) + " negative pivot(s) in D" +
                        (zero ? " and " + std::to_string(zero) + " zero one(s)" : "");
      return SolveStatus::kNotPositiveDefinite;
    }
    if (zero) {
      summary.message = std::to_string(zero) +
                        " zero pivot(s) in D (below 1e-13 of their diagonal entry), the first at " +
                        column_of_pivot(first_zero);
      return SolveStatus::kSingular;
    }
    return SolveStatus::kSuccess;
  }

  bool supernodal_;
  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
};

const char* umfpack_ordering_name(double used) {
  switch (int(used)) {
    case UMFPACK_ORDERING_CHOLMOD:
      return "cholmod";
    case UMFPACK_ORDERING_AMD:
      return "amd";
    case UMFPACK_ORDERING_GIVEN:
      return "given";
    case UMFPACK_ORDERING_METIS:
      return "metis";
    case UMFPACK_ORDERING_NONE:
      return "natural";
    default:
      return "umfpack-default";
  }
}

class Umfpack : public LinearSolver {
 public:
  explicit Umfpack(const SolverOptions& options) : LinearSolver(options) {
    umfpack_di_defaults(control_);
    if (options.ordering == Ordering::kMetis)
      control_[UMFPACK_ORDERING] = UMFPACK_ORDERING_METIS;
    else if (options.ordering == Ordering::kNatural)
      control_[UMFPACK_ORDERING] = UMFPACK_ORDERING_NONE;
    else if (options.ordering == Ordering::kAmd || options.ordering == Ordering::kColamd)
      control_[UMFPACK_ORDERING] = UMFPACK_ORDERING_AMD;
  }
  ~Umfpack() override { release(); }
  [[nodiscard]] std::string name() const override { return "umfpack"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    release();
    const SpMat& A = *op.matrix;
    const int status = umfpack_di_symbolic(int(A.rows()), int(A.cols()), A.outerIndexPtr(), A.innerIndexPtr(),
                                           A.valuePtr(), &symbolic_, control_, info_);
    if (status != UMFPACK_OK) {
      // a matrix with no entries fails the analysis (status -5): say that it is singular, and where
      if (const SolveStatus empty = check_preconditioner_matrix(A, false, &summary.message);
          empty != SolveStatus::kSuccess)
        return empty;
      summary.message = "umfpack_di_symbolic failed, status " + std::to_string(status);
      return SolveStatus::kFailure;
    }
    summary.ordering = umfpack_ordering_name(info_[UMFPACK_ORDERING_USED]);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!op.matrix || !symbolic_) {
      summary.message = "needs the assembled matrix";
      return SolveStatus::kNotApplicable;
    }
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    matrix_ = op.matrix;
    const SpMat& A = *op.matrix;
    const int status =
        umfpack_di_numeric(A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(), symbolic_, &numeric_, control_, info_);
    summary.factor_nnz = static_cast<long long>(info_[UMFPACK_LNZ] + info_[UMFPACK_UNZ]);
    if (status == UMFPACK_WARNING_singular_matrix) {
      summary.message = "UMFPACK: the matrix is singular (rcond " + std::to_string(info_[UMFPACK_RCOND]) + ")";
      return SolveStatus::kSingular;
    }
    if (status != UMFPACK_OK) {
      summary.message = "umfpack_di_numeric failed, status " + std::to_string(status);
      return SolveStatus::kFailure;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const SpMat& A = *matrix_;
    X.resize(B.rows(), 3);
    summary.iterations = 1;
    for (int c = 0; c < 3; ++c) {
      const int status = umfpack_di_solve(UMFPACK_A, A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr(),
                                          X.col(c).data(), B.col(c).data(), numeric_, control_, info_);
      if (status != UMFPACK_OK) {
        summary.message = "umfpack_di_solve failed, status " + std::to_string(status);
        return status == UMFPACK_WARNING_singular_matrix ? SolveStatus::kSingular : SolveStatus::kFailure;
      }
    }
    return SolveStatus::kSuccess;
  }

 private:
  void release() {
    if (numeric_) umfpack_di_free_numeric(&numeric_);
    if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
  }

  double control_[UMFPACK_CONTROL]{};
  double info_[UMFPACK_INFO]{};
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  const SpMat* matrix_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> make_cholmod_supernodal(const SolverOptions& o) {
  return std::make_unique<Cholmod>(true, o);
}
std::unique_ptr<LinearSolver> make_cholmod_simplicial(const SolverOptions& o) {
  return std::make_unique<Cholmod>(false, o);
}
std::unique_ptr<LinearSolver> make_umfpack(const SolverOptions& o) { return std::make_unique<Umfpack>(o); }

}  // namespace coons::solvers
