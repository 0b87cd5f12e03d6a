#include "eigen_direct.h"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>

#include "matrix_checks.h"

namespace coons::solvers {
namespace {

using SpMat = Eigen::SparseMatrix<double>;

using Ldlt = Eigen::SimplicialLDLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>>;
using Llt = Eigen::SimplicialLLT<SpMat, Eigen::Lower, Eigen::AMDOrdering<int>>;
using Lu = Eigen::SparseLU<SpMat, Eigen::COLAMDOrdering<int>>;

using Permutation = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

// a_kk of the permuted matrix P A Pᵀ the factor holds (row i of A is row P(i) there), for
// is_zero_pivot (matrix_checks.h).
Eigen::VectorXd permuted_diagonal(const SpMat& A, const Permutation& P) {
  const Eigen::VectorXd a = A.diagonal();
  Eigen::VectorXd out(a.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) out(P.size() == a.size() ? P.indices()(i) : i) = a(i);
  return out;
}

// LDLᵀ without pivoting is only stable on definite matrices: a negative entry of D is reported
// as "not positive definite", a zero one, when no entry is negative, as "singular". A pivot that is
// exactly zero during the factorisation proves nothing more than "not definite": [[0, 1], [1, 0]]
// is regular. D has A's inertia (Sylvester), so a regular indefinite A has negative pivots: a
// near-zero pivot among them is where elimination without pivoting landed, not a singular A (a
// regular indefinite 5×5 stencil system was called singular), while a semidefinite A, whose D has
// none, is singular when a pivot vanishes.
SolveStatus judge(const Ldlt& f, const SpMat& A, SolveSummary& summary) {
  if (f.info() != Eigen::Success) {
    summary.message = "LDLT met a zero pivot (it does not pivot)";  // and judge_stopped says what A is
    return SolveStatus::kNotPositiveDefinite;
  }
  // L's unit diagonal is implicit (only its strictly lower part is stored) and D is kept apart:
  // its n entries count as the diagonal of the factor, as in LLᵀ (a 1×1 matrix has one, not 0).
  summary.factor_nnz = static_cast<long long>(f.matrixL().nestedExpression().nonZeros()) + f.vectorD().size();
  const Eigen::VectorXd d = f.vectorD(), a = permuted_diagonal(A, f.permutationP());
  const double largest = d.cwiseAbs().maxCoeff();
  Eigen::Index zero = 0, negative = 0;
  for (Eigen::Index k = 0; k < d.size(); ++k) {
    if (is_zero_pivot(d(k), a(k), largest))
      ++zero;
    else if (d(k) < 0)
      ++negative;
  }
  if (negative > 0) {
    summary.message = std::to_string(negative) + " negative pivot(s) in D" +
                      (zero > 0 ? " and " + std::to_string(zero) + " zero one(s): the matrix is indefinite" : "");
    return SolveStatus::kNotPositiveDefinite;
  }
  if (zero > 0) {
    summary.message = std::to_string(zero) + " zero pivot(s) in D (below 1e-13 of their diagonal entry)";
    return SolveStatus::kSingular;
  }
  return SolveStatus::kSuccess;
}

SolveStatus judge(const Llt& f, const SpMat& A, SolveSummary& summary) {
  if (f.info() != Eigen::Success) {
    summary.message = "Cholesky met a non-positive pivot";
    return SolveStatus::kNotPositiveDefinite;
  }
  const auto& L = f.matrixL().nestedExpression();
  summary.factor_nnz = static_cast<long long>(L.nonZeros());
  const Eigen::VectorXd d = L.diagonal().cwiseAbs2(), a = permuted_diagonal(A, f.permutationP());  // d: LDLᵀ's pivots
  const double largest = d.maxCoeff();
  bool zero = false;
  for (Eigen::Index k = 0; k < d.size(); ++k) zero = zero || is_zero_pivot(d(k), a(k), largest);
  if (zero) {
    summary.message = "a pivot of L is (numerically) zero (its square below 1e-13 of its diagonal entry)";
    return SolveStatus::kSingular;
  }
  return SolveStatus::kSuccess;
}

// Eigen's SparseLU says "THE MATRIX IS STRUCTURALLY SINGULAR ... ZERO COLUMN AT k" for any zero
// pivot, also of a matrix whose pattern is regular ([[1, 1], [1, 1]]); k counts the elimination
// steps of the COLAMD-permuted matrix, not a column of A. Said as what it is.
std::string lu_failure(const std::string& eigen) {
  const std::string zero_column = "THE MATRIX IS STRUCTURALLY SINGULAR ... ZERO COLUMN AT ";
  if (eigen.rfind(zero_column, 0) == 0)
    return "SparseLU: a zero pivot at elimination step " + eigen.substr(zero_column.size()) +
           " (of the column-permuted matrix): singular, in its values or in its pattern";
  return "SparseLU: " + eigen;
}

SolveStatus judge(const Lu& f, const SpMat& /*A*/, SolveSummary& summary) {
  if (f.info() != Eigen::Success) {
    summary.message = lu_failure(f.lastErrorMessage());
    return SolveStatus::kSingular;
  }
  summary.factor_nnz = static_cast<long long>(f.nnzL()) + static_cast<long long>(f.nnzU());
  return SolveStatus::kSuccess;
}

// Shared by the three Eigen backends: each one only says how to factor and how to judge it.
template <class Factor>
class EigenDirect : public LinearSolver {
 public:
  EigenDirect(std::string name, std::string ordering, const SolverOptions& options)
      : LinearSolver(options), name_(std::move(name)), ordering_(std::move(ordering)) {}
  [[nodiscard]] std::string name() const override { return name_; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    factor_.analyzePattern(*op.matrix);
    summary.ordering = ordering_;
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_matrix(op, summary)) return SolveStatus::kNotApplicable;
    // SparseLU sizes U from fillratio·(nnz + 1)/n, 0 when nnz + 1 < n/20, and then never returns
    // from factorize (Eigen 3.4); such a matrix has an empty row or column, singular anyway.
    if constexpr (std::is_same_v<Factor, Lu>)
      if (const SolveStatus empty = check_preconditioner_matrix(*op.matrix, false, &summary.message);
          empty != SolveStatus::kSuccess)
        return empty;
    factor_.factorize(*op.matrix);
    const SolveStatus status = judge(factor_, *op.matrix, summary);
    if constexpr (!std::is_same_v<Factor, Lu>)
      // stopped at a pivot, or zero pivots and no negative one: semidefinite and singular, or an
      // indefinite A whose negative eigenvalue the rounding of a pivot hid (−2e-15 counted as zero)
      if (factor_.info() != Eigen::Success || status == SolveStatus::kSingular)
        return judge_stopped(*op.matrix, summary);
    return status;
  }

  // The factorisation stopped at a pivot ≤ 0 (LLᵀ) or = 0 (LDLᵀ), or found zero pivots (below
  // kSingularPivot of their diagonal entry) and no negative one: singular or indefinite, which
  // the factorisation of A raised on its diagonal and inverse iteration with it tell apart
  // (semidefinite_verdict). The raised factor stays behind, but a failed factorize() leaves
  // nothing to solve with.
  SolveStatus judge_stopped(const SpMat& A, SolveSummary& summary) {
    factor_.factorize(raise_diagonal(A, kSemidefiniteShift));
    bool definite = factor_.info() == Eigen::Success;
    if constexpr (std::is_same_v<Factor, Ldlt>) definite = definite && (factor_.vectorD().array() > 0).all();
    std::optional<ScaledEigenvalue> raised;
    if (definite)
      raised = smallest_scaled_eigenvalue(
          A, [&](const Eigen::MatrixX3d& B) -> Eigen::MatrixX3d { return factor_.solve(B); });
    return semidefinite_verdict(A, raised, summary.message, &summary.message);
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    X = factor_.solve(B);
    summary.iterations = 1;
    if (factor_.info() != Eigen::Success) {
      summary.message = "Eigen solve failed";
      return SolveStatus::kFailure;
    }
    return SolveStatus::kSuccess;
  }

 private:
  std::string name_, ordering_;
  Factor factor_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_eigen_ldlt(const SolverOptions& options) {
  return std::make_unique<EigenDirect<Ldlt>>("eigen-ldlt", "amd", options);
}

std::unique_ptr<LinearSolver> make_eigen_llt(const SolverOptions& options) {
  return std::make_unique<EigenDirect<Llt>>("eigen-llt", "amd", options);
}

std::unique_ptr<LinearSolver> make_eigen_lu(const SolverOptions& options) {
  return std::make_unique<EigenDirect<Lu>>("eigen-lu", "colamd", options);
}

}  // namespace coons::solvers
