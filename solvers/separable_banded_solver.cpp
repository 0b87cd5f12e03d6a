#include "separable_banded_solver.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace coons::solvers {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Y ← P⁻¹ Y along i: rows of Y are whole grid rows (contiguous, vectorised across j).
void solve_along_rows(const BandedLdlt& f, Eigen::Ref<RowMajor> Y) {
  const Eigen::Index k = Y.rows();
  for (Eigen::Index r = 1; r < k; ++r) {
    Y.row(r) -= f.l1[r - 1] * Y.row(r - 1);
    if (r >= 2) Y.row(r) -= f.l2[r - 2] * Y.row(r - 2);
  }
  for (Eigen::Index r = 0; r < k; ++r) Y.row(r) /= f.d[r];
  for (Eigen::Index r = k - 2; r >= 0; --r) {
    Y.row(r) -= f.l1[r] * Y.row(r + 1);
    if (r + 2 < k) Y.row(r) -= f.l2[r] * Y.row(r + 2);
  }
}

// Y ← Y Q⁻¹ (Q symmetric), i.e. a banded solve along j in every row, kBlock rows at a time so
// that the inner loop runs across rows.
void solve_along_cols(const BandedLdlt& f, Eigen::Ref<RowMajor> Y) {
  constexpr Eigen::Index kBlock = 16;
  const Eigen::Index rows = Y.rows(), k = Y.cols();
  const double* l1 = f.l1.data();
  const double* l2 = f.l2.data();
  const double* d = f.d.data();
  for (Eigen::Index r0 = 0; r0 < rows; r0 += kBlock) {
    const Eigen::Index r1 = std::min(rows, r0 + kBlock);
    for (Eigen::Index c = 1; c < k; ++c)
      for (Eigen::Index r = r0; r < r1; ++r) {
        double v = Y(r, c) - l1[c - 1] * Y(r, c - 1);
        if (c >= 2) v -= l2[c - 2] * Y(r, c - 2);
        Y(r, c) = v;
      }
    for (Eigen::Index c = 0; c < k; ++c)
      for (Eigen::Index r = r0; r < r1; ++r) Y(r, c) /= d[c];
    for (Eigen::Index c = k - 2; c >= 0; --c)
      for (Eigen::Index r = r0; r < r1; ++r) {
        double v = Y(r, c) - l1[c] * Y(r, c + 1);
        if (c + 2 < k) v -= l2[c] * Y(r, c + 2);
        Y(r, c) = v;
      }
  }
}

// Each column of B is a rows × cols grid R (row-major): X = P⁻¹ R Q⁻¹.
void solve_separable(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols,
                     const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
  X.resize(B.rows(), 3);
  RowMajor Y(rows, cols);
  for (int c = 0; c < 3; ++c) {
    Y = Eigen::Map<const RowMajor>(B.col(c).data(), rows, cols);
    solve_along_rows(fi, Y);
    solve_along_cols(fj, Y);
    Eigen::Map<RowMajor>(X.col(c).data(), rows, cols) = Y;
  }
}

class SeparableBandedSolver final : public LinearSolver {
 public:
  SeparableBandedSolver(const SeparableBandedOperator& op, const SolverOptions& options)
      : LinearSolver(options), op_(op) {}

  [[nodiscard]] std::string name() const override { return "separable-banded"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (op.size() != op_.size()) {
      summary.message = "the operator has " + std::to_string(op.size()) +
                        " unknowns, the separable grid " + std::to_string(op_.rows) + " x " +
                        std::to_string(op_.cols);
      return SolveStatus::kNotApplicable;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator&, SolveSummary& summary) override {
    if (banded_ldlt(op_.along_i, op_.rows, fi_) != SolveStatus::kSuccess ||
        banded_ldlt(op_.along_j, op_.cols, fj_) != SolveStatus::kSuccess) {
      summary.message = "a zero pivot in the banded LDL^T of a factor";
      return SolveStatus::kSingular;
    }
    summary.factor_nnz = 3LL * (op_.rows + op_.cols);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    solve_separable(fi_, fj_, op_.rows, op_.cols, B, X);
    summary.iterations = 1;
    return SolveStatus::kSuccess;
  }

 private:
  SeparableBandedOperator op_;
  BandedLdlt fi_, fj_;
};

}  // namespace

SolveStatus banded_ldlt(const std::array<double, 3>& a, int k, BandedLdlt& f) {
  f.d.resize(k);
  f.l1.resize(std::max(0, k - 1));
  f.l2.resize(std::max(0, k - 2));
  const double scale = std::max({std::abs(a[0]), std::abs(a[1]), std::abs(a[2])});
  for (int r = 0; r < k; ++r) {
    double d = a[0];
    if (r >= 1) d -= f.l1[r - 1] * f.l1[r - 1] * f.d[r - 1];
    if (r >= 2) d -= f.l2[r - 2] * f.l2[r - 2] * f.d[r - 2];
    if (!(std::abs(d) > 1e-14 * scale)) return SolveStatus::kSingular;
    f.d[r] = d;
    if (r + 1 < k) {
      double l = a[1];
      if (r >= 1) l -= f.l2[r - 1] * f.d[r - 1] * f.l1[r - 1];
      f.l1[r] = l / d;
    }
    if (r + 2 < k) f.l2[r] = a[2] / d;
  }
  return SolveStatus::kSuccess;
}

Eigen::SparseMatrix<double> separable_banded_matrix(const SeparableBandedOperator& op) {
  using SpMat = Eigen::SparseMatrix<double>;
  using StorageIndex = SpMat::StorageIndex;
  const auto span = [](int k, int len) { return std::min(len - 1, k + 2) - std::max(0, k - 2) + 1; };
  Eigen::Index nnz = 0;
  for (int i = 0; i < op.rows; ++i)
    for (int j = 0; j < op.cols; ++j) nnz += Eigen::Index(span(i, op.rows)) * span(j, op.cols);
  SpMat A(op.size(), op.size());
  A.resizeNonZeros(nnz);
  StorageIndex* outer = A.outerIndexPtr();
  StorageIndex* inner = A.innerIndexPtr();
  double* value = A.valuePtr();
  Eigen::Index pos = 0;
  outer[0] = 0;
  for (int i = 0; i < op.rows; ++i)
    for (int j = 0; j < op.cols; ++j) {
      for (int a = -2; a <= 2; ++a) {
        if (i + a < 0 || i + a >= op.rows) continue;
        for (int b = -2; b <= 2; ++b) {
          if (j + b < 0 || j + b >= op.cols) continue;
          inner[pos] = StorageIndex(Eigen::Index(i + a) * op.cols + j + b);
          value[pos] = op.along_i[std::size_t(std::abs(a))] * op.along_j[std::size_t(std::abs(b))];
          ++pos;
        }
      }
      outer[Eigen::Index(i) * op.cols + j + 1] = StorageIndex(pos);
    }
  return A;
}

SolveStatus separable_banded_solve(const SeparableBandedOperator& op, const Eigen::MatrixX3d& B,
                                   Eigen::MatrixX3d& X) {
  BandedLdlt fi, fj;
  if (B.rows() != op.size()) return SolveStatus::kNotApplicable;
  if (banded_ldlt(op.along_i, op.rows, fi) != SolveStatus::kSuccess ||
      banded_ldlt(op.along_j, op.cols, fj) != SolveStatus::kSuccess)
    return SolveStatus::kSingular;
  solve_separable(fi, fj, op.rows, op.cols, B, X);
  return SolveStatus::kSuccess;
}

std::unique_ptr<LinearSolver> make_separable_banded_solver(const SeparableBandedOperator& op,
                                                           const SolverOptions& options) {
  return std::make_unique<SeparableBandedSolver>(op, options);
}

}  // namespace coons::solvers
