#include "separable_banded_solver.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "stencil_operator.h"

namespace coons::solvers {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// X = P⁻¹ R Q⁻¹ for each column of B viewed as a rows × cols grid R (row-major), in two passes
// over the grid (P⁻¹ and Q⁻¹ act on different sides, so their parts may be interleaved):
//   pass 1, kBlock rows at a time: copy the rows of B, solve along j in every row of the block
//           (the inner loop runs across the block's rows, which stay in cache), then the forward
//           elimination along i of those rows (the two rows above are still in cache);
//   pass 2, bottom to top: the scaling by 1/d and the back substitution along i, whole rows.
void solve_separable(const BandedLdlt& fi, const BandedLdlt& fj, int rows, int cols, const Eigen::MatrixX3d& B,
                     Eigen::MatrixX3d& X) {
  constexpr Eigen::Index kBlock = 16;
  X.resize(B.rows(), 3);
  if (rows == 0 || cols == 0) return;
  const Eigen::VectorXd inv_di = fi.d.cwiseInverse(), inv_dj = fj.d.cwiseInverse();
  const double* l1 = fj.l1.data();
  const double* l2 = fj.l2.data();
  const double* idj = inv_dj.data();
  const Eigen::Index k = cols;
  for (int c = 0; c < 3; ++c) {
    Eigen::Map<const RowMajor> R(B.col(c).data(), rows, cols);
    Eigen::Map<RowMajor> Y(X.col(c).data(), rows, cols);
    for (Eigen::Index r0 = 0; r0 < rows; r0 += kBlock) {
      const Eigen::Index r1 = std::min<Eigen::Index>(rows, r0 + kBlock);
      Y.middleRows(r0, r1 - r0) = R.middleRows(r0, r1 - r0);
      for (Eigen::Index j = 1; j < k; ++j)  // along j: forward
        for (Eigen::Index r = r0; r < r1; ++r) {
          double v = Y(r, j) - l1[j - 1] * Y(r, j - 1);
          if (j >= 2) v -= l2[j - 2] * Y(r, j - 2);
          Y(r, j) = v;
        }
      for (Eigen::Index r = r0; r < r1; ++r) Y(r, k - 1) *= idj[k - 1];
      for (Eigen::Index j = k - 2; j >= 0; --j)  // along j: scale and back substitution
        for (Eigen::Index r = r0; r < r1; ++r) {
          double v = Y(r, j) * idj[j] - l1[j] * Y(r, j + 1);
          if (j + 2 < k) v -= l2[j] * Y(r, j + 2);
          Y(r, j) = v;
        }
      for (Eigen::Index r = std::max<Eigen::Index>(r0, 1); r < r1; ++r) {  // along i: forward
        Y.row(r) -= fi.l1[r - 1] * Y.row(r - 1);
        if (r >= 2) Y.row(r) -= fi.l2[r - 2] * Y.row(r - 2);
      }
    }
    Y.row(rows - 1) *= inv_di[rows - 1];
    for (Eigen::Index r = rows - 2; r >= 0; --r) {  // along i: scale and back substitution
      Y.row(r) = Y.row(r) * inv_di[r] - fi.l1[r] * Y.row(r + 1);
      if (r + 2 < rows) Y.row(r) -= fi.l2[r] * Y.row(r + 2);
    }
  }
}

class SeparableBandedSolver final : public LinearSolver {
 public:
  SeparableBandedSolver(std::optional<SeparableBandedOperator> op, const SolverOptions& options)
      : LinearSolver(options), fixed_(op) {}

  [[nodiscard]] std::string name() const override { return "separable-banded"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    return describe(op, summary) ? SolveStatus::kSuccess : SolveStatus::kNotApplicable;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!describe(op, summary)) return SolveStatus::kNotApplicable;
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
  // op_ = the operator given at construction, else the one read from op; false (with the reason
  // in the summary) when there is none or its size differs from op's.
  bool describe(const LinearOperator& op, SolveSummary& summary) {
    if (fixed_) {
      op_ = *fixed_;
    } else if (auto found = separable_operator(op)) {
      op_ = *found;
    } else {
      summary.message =
          "needs a separable stencil (w(a,b) = u(a) v(b), symmetric) on a full rectangle (a grid stencil or "
          "grid operator)";
      return false;
    }
    if (op.size() != op_.size()) {
      summary.message = "the operator has " + std::to_string(op.size()) + " unknowns, the separable grid " +
                        std::to_string(op_.rows) + " x " + std::to_string(op_.cols);
      return false;
    }
    return true;
  }

  std::optional<SeparableBandedOperator> fixed_;
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

SolveStatus separable_banded_solve(const SeparableBandedOperator& op, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X) {
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

std::unique_ptr<LinearSolver> make_separable_banded(const SolverOptions& options) {
  return std::make_unique<SeparableBandedSolver>(std::nullopt, options);
}

std::optional<SeparableBandedOperator> separable_operator(const StencilOperator& g) {
  if (!g.is_valid(nullptr) || g.size() != Eigen::Index(g.rows) * g.cols) return std::nullopt;
  const int r = g.radius;
  int pi = 0, pj = 0;  // the largest weight: the pivot of the rank-one split
  double scale = 0;
  for (int di = -r; di <= r; ++di)
    for (int dj = -r; dj <= r; ++dj)
      if (std::abs(g.weight(di, dj)) > scale) {
        scale = std::abs(g.weight(di, dj));
        pi = di;
        pj = dj;
      }
  if (!(scale > 0)) return std::nullopt;
  const double tol = 1e-12 * scale;
  const double pivot = g.weight(pi, pj);
  for (int di = -r; di <= r; ++di)
    for (int dj = -r; dj <= r; ++dj) {
      const double w = g.weight(di, dj);
      if (std::abs(w - g.weight(di, pj) * g.weight(pi, dj) / pivot) > tol) return std::nullopt;
      if (std::abs(w - g.weight(-di, dj)) > tol || std::abs(w - g.weight(di, -dj)) > tol) return std::nullopt;
    }
  SeparableBandedOperator op;
  op.rows = g.rows;
  op.cols = g.cols;
  for (int k = 0; k <= r; ++k) {
    op.along_i[std::size_t(k)] = g.weight(k, pj);
    op.along_j[std::size_t(k)] = g.weight(pi, k) / pivot;
  }
  return op;
}

std::optional<SeparableBandedOperator> separable_operator(const LinearOperator& op) {
  if (op.grid) return separable_operator(*op.grid);
  if (op.stencil) return separable_operator(stencil_operator(*op.stencil));
  return std::nullopt;
}

}  // namespace coons::solvers
