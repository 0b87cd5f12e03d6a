#include "mask_iterations.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "iteration_summary.h"

namespace coons::solvers {
namespace {

enum class Scheme { kJacobi, kGaussSeidel };

// Σ of the off-centre stencil terms at (i, j) of one column x (zero outside the grid).
inline double neighbour_sum(const GridStencil& s, const double* x, int i, int j) {
  const int R = s.rows, C = s.cols;
  const double* mid = x + Eigen::Index(i) * C;
  double ei = 0, ej = 0, dg = 0;
  if (j > 0) ej += mid[j - 1];
  if (j + 1 < C) ej += mid[j + 1];
  if (i > 0) {
    const double* up = mid - C;
    ei += up[j];
    if (j > 0) dg += up[j - 1];
    if (j + 1 < C) dg += up[j + 1];
  }
  if (i + 1 < R) {
    const double* down = mid + C;
    ei += down[j];
    if (j > 0) dg += down[j - 1];
    if (j + 1 < C) dg += down[j + 1];
  }
  return s.edge_i * ei + s.edge_j * ej + s.diag * dg;
}

class MaskIteration : public LinearSolver {
 public:
  MaskIteration(Scheme scheme, const SolverOptions& options) : LinearSolver(options), scheme_(scheme) {}
  [[nodiscard]] std::string name() const override { return scheme_ == Scheme::kJacobi ? "jacobi" : "gauss-seidel"; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (lacks_stencil(op, summary)) return SolveStatus::kNotApplicable;
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    if (!op.stencil) return do_analyze(op, summary);
    if (op.stencil->center == 0) {
      summary.message = "the stencil's centre weight is zero";
      return SolveStatus::kSingular;
    }
    stencil_ = *op.stencil;
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    constexpr int kCheckEvery = 10;
    LinearOperator op;
    op.stencil = stencil_;
    X.setZero(B.rows(), 3);
    Eigen::MatrixX3d next = X;
    IterationEnd end;
    end.limit = iteration_limit(options_, stencil_.size(), 1000, 1e8);
    end.initial = end.residual = relative_residual(op, B, X);
    end.convergent = scheme_ == Scheme::kGaussSeidel && options_.sor_omega > 0 && options_.sor_omega < 2 &&
                     stencil_eigenvalue_range(stencil_).first > 0;
    // A residual near the rounding floor (kStagnationFloor) that has set no new low for this many
    // sweeps has stalled there: a steady iteration, however slow (Jacobi at N = 1023 gains 5e-6 a
    // sweep), keeps setting lows. Above the floor nothing is concluded (SOR may stay flat for
    // thousands of sweeps and fall again).
    const int stall_window = std::max(1000, 10 * (stencil_.rows + stencil_.cols));
    double lowest = HUGE_VAL;
    int lowest_at = 0;
    while (end.iterations < end.limit && end.residual > options_.tolerance) {
      for (int k = 0; k < kCheckEvery && end.iterations < end.limit; ++k, ++end.iterations) sweep_once(B, X, next);
      end.residual = relative_residual(op, B, X);
      if (!std::isfinite(end.residual) || end.residual > 1e8 * std::max(end.initial, 1e-300)) {
        end.diverged = true;
        break;
      }
      if (end.residual < lowest) {
        lowest = end.residual;
        lowest_at = end.iterations;
      } else if (end.residual > options_.tolerance && lowest <= kStagnationFloor &&
                 end.iterations - lowest_at >= stall_window) {
        end.stagnation = no_new_low(end.iterations - lowest_at);
        break;
      }
      if (end.residual > options_.tolerance && out_of_time()) {
        end.timed_out = true;
        break;
      }
    }
    end.converged = !end.diverged && end.residual <= options_.tolerance;
    return finish_iteration(end, X, summary);
  }

 private:
  void sweep_once(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, Eigen::MatrixX3d& next) const {
    const GridStencil& s = stencil_;
    const double inv_c = 1.0 / s.center, omega = options_.sor_omega;
    for (int c = 0; c < 3; ++c) {
      const double* b = B.col(c).data();
      if (scheme_ == Scheme::kJacobi) {
        const double* x = X.col(c).data();
        double* y = next.col(c).data();
        for (int i = 0; i < s.rows; ++i)
          for (int j = 0; j < s.cols; ++j) {
            const Eigen::Index k = Eigen::Index(i) * s.cols + j;
            y[k] = (b[k] - neighbour_sum(s, x, i, j)) * inv_c;
          }
      } else {
        double* x = X.col(c).data();
        for (int i = 0; i < s.rows; ++i)
          for (int j = 0; j < s.cols; ++j) {
            const Eigen::Index k = Eigen::Index(i) * s.cols + j;
            const double gs = (b[k] - neighbour_sum(s, x, i, j)) * inv_c;
            x[k] += omega * (gs - x[k]);
          }
      }
    }
    if (scheme_ == Scheme::kJacobi) X.swap(next);
  }

  Scheme scheme_;
  GridStencil stencil_;
};

}  // namespace

std::unique_ptr<LinearSolver> make_jacobi(const SolverOptions& o) {
  return std::make_unique<MaskIteration>(Scheme::kJacobi, o);
}
std::unique_ptr<LinearSolver> make_gauss_seidel(const SolverOptions& o) {
  return std::make_unique<MaskIteration>(Scheme::kGaussSeidel, o);
}

}  // namespace coons::solvers
