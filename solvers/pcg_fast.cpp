#include "pcg_fast.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "fast5_solver.h"
#include "separable_banded_solver.h"
#include "stencil_operator.h"
#include "structured_solvers.h"

namespace coons::solvers {

namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The reflection-symmetric 3×3 operator as a GridStencil (for `fast`), else nullopt.
std::optional<GridStencil> grid_stencil_of(const StencilOperator& g) {
  if (g.radius != 1) return std::nullopt;
  const double c = g.weight(0, 0), ei = g.weight(1, 0), ej = g.weight(0, 1), d = g.weight(1, 1);
  if (g.weight(-1, 0) != ei || g.weight(0, -1) != ej || g.weight(-1, -1) != d || g.weight(1, -1) != d ||
      g.weight(-1, 1) != d)
    return std::nullopt;
  return GridStencil{g.rows, g.cols, c, ei, ej, d};
}

enum class BoxSolver { kNone, kFast, kFast5, kSeparable };

const char* to_string(BoxSolver kind) {
  switch (kind) {
    case BoxSolver::kFast:
      return "fast";
    case BoxSolver::kFast5:
      return "fast5";
    case BoxSolver::kSeparable:
      return "separable-banded";
    case BoxSolver::kNone:
      break;
  }
  return "none";
}

class PcgFastSolver final : public LinearSolver {
 public:
  explicit PcgFastSolver(const SolverOptions& options) : LinearSolver(options) {}
  [[nodiscard]] std::string name() const override { return "pcg-fast"; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (!setup(op, summary)) return SolveStatus::kNotApplicable;
    return pass_on(inner_->analyze(box_op_), summary);
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!setup(op, summary)) return SolveStatus::kNotApplicable;
    if (box_stencil_) {  // the exact spectrum of the box is known
      const double lo = stencil_eigenvalue_range(*box_stencil_).first;
      if (!(lo > 0)) {
        summary.message = "smallest eigenvalue of the bounding rectangle's operator is " + format_g(lo) +
                          ": conjugate gradients need a positive definite system";
        return SolveStatus::kNotPositiveDefinite;
      }
    }
    return pass_on(inner_->factorize(box_op_), summary);
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const Eigen::Index n = B.rows();
    X.setZero(n, 3);
    IterationEnd end;
    end.limit = iteration_limit(options_, n, 20, 2e10);
    end.krylov = true;
    const Eigen::Array3d norm_b = B.colwise().norm().transpose().array();
    std::array<bool, 3> active{};
    for (int c = 0; c < 3; ++c) active[std::size_t(c)] = norm_b[c] > 0;
    Eigen::MatrixX3d R = B, Z, P, AP;
    if (!precondition(R, Z, summary)) return SolveStatus::kFailure;
    Eigen::Array3d rz = (R.array() * Z.array()).colwise().sum().transpose();
    P = Z;
    end.residual = 0;
    end.converged = !(active[0] || active[1] || active[2]);
    while (!end.converged && end.iterations < end.limit) {
      apply(P, AP);
      ++end.iterations;
      const Eigen::Array3d pap = (P.array() * AP.array()).colwise().sum().transpose();
      end.residual = 0;
      for (int c = 0; c < 3; ++c) {
        if (!active[std::size_t(c)]) continue;
        if (!(pap[c] > 0)) {
          summary.iterations = end.iterations;
          summary.message = "p^T A p = " + format_g(pap[c]) + ": the operator is not positive definite";
          X.setZero();
          return SolveStatus::kNotPositiveDefinite;
        }
        const double step = rz[c] / pap[c];
        X.col(c) += step * P.col(c);
        R.col(c) -= step * AP.col(c);
        const double res = R.col(c).norm() / norm_b[c];
        if (res <= options_.tolerance) active[std::size_t(c)] = false;
        end.residual = std::max(end.residual, res);
      }
      end.converged = !(active[0] || active[1] || active[2]);
      if (end.converged) break;
      if (!std::isfinite(end.residual) || end.residual > 1e8) {
        end.diverged = true;
        break;
      }
      if (out_of_time()) {
        end.timed_out = true;
        break;
      }
      if (!precondition(R, Z, summary)) return SolveStatus::kFailure;
      for (int c = 0; c < 3; ++c) {
        if (!active[std::size_t(c)]) continue;
        const double rz_next = R.col(c).dot(Z.col(c));
        P.col(c) = Z.col(c) + (rz_next / rz[c]) * P.col(c);
        rz[c] = rz_next;
      }
    }
    return finish_iteration(end, X, summary);
  }

 private:
  // Reads the grid operator of op, the box operator and the kind of box solver (a new inner
  // solver when the kind changes). False, with the reason in the summary, when not applicable.
  bool setup(const LinearOperator& op, SolveSummary& summary) {
    if (op.grid) {
      grid_ = *op.grid;
    } else if (op.stencil) {
      grid_ = stencil_operator(*op.stencil);
    } else {
      summary.message = "needs a grid operator (3x3 or 5x5 with its free mask) or a grid stencil";
      return false;
    }
    if (std::string why = grid_operator_problem(grid_, op.matrix); !why.empty()) {
      summary.message = why;
      return false;
    }
    if (!grid_.symmetric()) {
      summary.message = "conjugate gradients need a symmetric stencil (w(d) = w(-d)); use gmres";
      return false;
    }
    box_ = grid_;
    box_.free.clear();
    box_stencil_ = grid_stencil_of(box_);
    BoxSolver kind = BoxSolver::kNone;
    if (box_stencil_)
      kind = BoxSolver::kFast;
    else if (c1_family_weights(box_))
      kind = BoxSolver::kFast5;
    else if (separable_operator(box_))
      kind = BoxSolver::kSeparable;
    if (kind == BoxSolver::kNone) {
      summary.message =
          "no exact structured solver covers the bounding rectangle's stencil (needs a reflection-symmetric 3x3, "
          "a*C + b*T or a separable stencil)";
      return false;
    }
    if (kind != kind_ || !inner_) {
      SolverOptions inner = options_;
      inner.compute_residual = false;
      if (kind == BoxSolver::kFast) inner_ = make_fast_solver(inner);
      if (kind == BoxSolver::kFast5) inner_ = make_fast5_solver(inner);
      if (kind == BoxSolver::kSeparable) inner_ = make_separable_banded(inner);
      kind_ = kind;
    }
    box_op_ = LinearOperator{};
    box_op_.grid = &box_;
    box_op_.stencil = box_stencil_;
    points_.clear();
    const std::vector<Eigen::Index> number = free_numbering(grid_);
    for (std::size_t p = 0; p < number.size(); ++p)
      if (number[p] >= 0) points_.push_back(Eigen::Index(p));
    return true;
  }

  SolveStatus pass_on(SolveStatus status, SolveSummary& summary) const {
    if (status != SolveStatus::kSuccess)
      summary.message = std::string("the rectangle's solver ") + to_string(kind_) + ": " + inner_->summary().message;
    return status;
  }

  // Z = restrict(A_box⁻¹ extend(R)).
  bool precondition(const Eigen::MatrixX3d& R, Eigen::MatrixX3d& Z, SolveSummary& summary) {
    box_rhs_.setZero(box_.size(), 3);
    for (std::size_t k = 0; k < points_.size(); ++k) box_rhs_.row(points_[k]) = R.row(Eigen::Index(k));
    const SolveSummary s = inner_->solve(box_rhs_, box_x_);
    if (!s.ok()) {
      summary.message = std::string("the rectangle's solver ") + to_string(kind_) + ": " + s.message;
      return false;
    }
    Z.resize(R.rows(), 3);
    for (std::size_t k = 0; k < points_.size(); ++k) Z.row(Eigen::Index(k)) = box_x_.row(points_[k]);
    return true;
  }

  // Y = A X on the free points: each column scattered onto the grid (zero at fixed points), the
  // stencil applied as shifted block updates, gathered at the free points.
  void apply(const Eigen::MatrixX3d& X, Eigen::MatrixX3d& Y) {
    const int rows = grid_.rows, cols = grid_.cols, r = grid_.radius;
    Y.resize(X.rows(), 3);
    for (int c = 0; c < 3; ++c) {
      in_.setZero(rows, cols);
      out_.setZero(rows, cols);
      for (std::size_t k = 0; k < points_.size(); ++k) in_.data()[points_[k]] = X(Eigen::Index(k), c);
      for (int di = -r; di <= r; ++di)
        for (int dj = -r; dj <= r; ++dj) {
          const double w = grid_.weight(di, dj);
          const int i0 = std::max(0, -di), i1 = std::min(rows, rows - di);
          const int j0 = std::max(0, -dj), j1 = std::min(cols, cols - dj);
          if (w == 0 || i1 <= i0 || j1 <= j0) continue;
          out_.block(i0, j0, i1 - i0, j1 - j0) += w * in_.block(i0 + di, j0 + dj, i1 - i0, j1 - j0);
        }
      for (std::size_t k = 0; k < points_.size(); ++k) Y(Eigen::Index(k), c) = out_.data()[points_[k]];
    }
  }

  StencilOperator grid_, box_;
  std::optional<GridStencil> box_stencil_;
  LinearOperator box_op_;
  BoxSolver kind_ = BoxSolver::kNone;
  std::unique_ptr<LinearSolver> inner_;
  std::vector<Eigen::Index> points_;  // grid index (row-major) of each unknown
  Eigen::MatrixX3d box_rhs_, box_x_;
  RowMajor in_, out_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_pcg_fast_solver(const SolverOptions& options) {
  return std::make_unique<PcgFastSolver>(options);
}

}  // namespace coons::solvers
