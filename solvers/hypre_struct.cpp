// hypre-pfmg and hypre-smg: the grid stencil through hypre's Struct interface (hypre_solvers.h).
#include <HYPRE_struct_ls.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "hypre_common.h"
#include "hypre_solvers.h"
#include "stencil_operator.h"

namespace coons::solvers {

namespace {

enum class StructMethod { kPfmg, kSmg };

// The h-ellipticity measure of a 3×3 stencil (Trottenberg, Oosterlee, Schüller, Multigrid, §4.7):
// min |σ(θ)| over the high frequencies (max(|θ₁|, |θ₂|) ≥ π/2) over max |σ(θ)|, σ the symbol
// Σ w(d) e^{i d·θ}, sampled on a 64×64 grid of angles that contains 0, ±π/2 and π. A point
// smoother (PFMG's Jacobi) reduces a high-frequency mode by about 1 − ω σ(θ)/w(0): where σ
// vanishes it reduces nothing. At α = −1/4 (T⊗T, σ = (1 − cos θ₁)(1 − cos θ₂)) σ(π, 0) = 0.
double h_ellipticity(const StencilOperator& grid) {
  constexpr int kSamples = 64;
  double high_min = INFINITY, all_max = 0;
  for (int s = 0; s < kSamples; ++s)
    for (int t = 0; t < kSamples; ++t) {
      const double a = M_PI * (2.0 * s / kSamples - 1), b = M_PI * (2.0 * t / kSamples - 1);
      double re = 0, im = 0;
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj) {
          const int k = (di + 1) * 3 + dj + 1;
          const double w = grid.weights[static_cast<std::size_t>(k)];
          re += w * std::cos(di * a + dj * b);
          im += w * std::sin(di * a + dj * b);
        }
      const double size = std::hypot(re, im);
      all_max = std::max(all_max, size);
      if (std::max(std::abs(a), std::abs(b)) >= M_PI / 2) high_min = std::min(high_min, size);
    }
  return all_max > 0 ? high_min / all_max : 0;
}

// Below it hypre-pfmg refuses: at α = −1/4 PCG with PFMG still had a residual of 1e−3 to 1e−2
// after 500 iterations (63×63 to 255×255). The measure is 0.25 at α = 0, 0.11 at α = −0.1, 0.005
// at α = −0.24 and 0 at α = ±1/4 (at α = 1/4, σ = 1 − cos θ₁ cos θ₂ vanishes at (π, π): refused
// by the same rule, not measured).
constexpr double kMinHEllipticity = 1e-3;

std::optional<StencilOperator> grid_of(const LinearOperator& op) {
  if (op.grid) return *op.grid;
  if (op.stencil) return stencil_operator(*op.stencil);
  return std::nullopt;
}

class HypreStructBackend : public hypre_detail::HypreBackend {
 public:
  HypreStructBackend(std::string name, StructMethod method, const SolverOptions& options)
      : HypreBackend(options), name_(std::move(name)), method_(method) {}
  ~HypreStructBackend() override { release(); }
  HypreStructBackend(const HypreStructBackend&) = delete;
  HypreStructBackend& operator=(const HypreStructBackend&) = delete;

  [[nodiscard]] std::string name() const override { return name_; }
  [[nodiscard]] bool exact() const override { return false; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    const std::optional<StencilOperator> grid = grid_of(op);
    if (!grid) {
      summary.message = "needs a grid stencil (hypre's Struct interface), not only a matrix; use hypre-amg";
      return SolveStatus::kNotApplicable;
    }
    if (std::string why = grid_operator_problem(*grid, op.matrix); !why.empty()) {
      summary.message = why;
      return SolveStatus::kNotApplicable;
    }
    if (grid->radius != 1) {  // PFMG aborts the process on 25 points; SMG's set-up fails
      summary.message = "hypre's PFMG and SMG (2.26) take 5- and 9-point stencils in 2-D, not 5x5 ones; use hypre-amg";
      return SolveStatus::kNotApplicable;
    }
    if (!grid->symmetric()) {
      summary.message = "conjugate gradients need a symmetric stencil (w(d) = w(-d)); use hypre-amg or gmres";
      return SolveStatus::kNotApplicable;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    const SolveStatus checked = do_analyze(op, summary);
    if (checked != SolveStatus::kSuccess) return checked;
    if (!op.grid && op.stencil) {  // the exact spectrum is known
      const double lo = stencil_eigenvalue_range(*op.stencil).first;
      if (!(lo > 0)) {
        summary.message = "smallest eigenvalue of the operator is " + format_g(lo) +
                          ": conjugate gradients need a positive definite system";
        return SolveStatus::kNotPositiveDefinite;
      }
    }
    // After the definiteness test: an indefinite stencil (α < −1/4) is reported as such.
    if (method_ == StructMethod::kPfmg && h_ellipticity(*grid_of(op)) < kMinHEllipticity) {
      summary.message =
          "the stencil is not h-elliptic (its symbol vanishes at a high frequency, as at alpha = -1/4 at (pi, 0) and "
          "at "
          "alpha = 1/4 at (pi, pi)): "
          "PFMG's point smoother cannot reduce those modes and PCG with PFMG does not converge; use hypre-smg "
          "(line smoothing) or mg-cg";
      return SolveStatus::kNotApplicable;
    }
    release();
    grid_ = *grid_of(op);
    number_ = free_numbering(grid_);
    const HYPRE_Int error = build();
    if (error != 0) {
      summary.message = "hypre's set-up failed (error flag " + std::to_string(error) + ")";
      return SolveStatus::kFailure;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    const std::size_t local = std::size_t(last_row_ - first_row_) * std::size_t(grid_.cols);
    const std::size_t offset = std::size_t(first_row_) * std::size_t(grid_.cols);
    std::vector<double> values(local), gathered;
    auto solve = [&](int c) {
      for (std::size_t p = 0; p < local; ++p) {
        const Eigen::Index k = number_[offset + p];
        values[p] = k < 0 ? 0.0 : B(k, c);
      }
      set_box(b_, values);
      std::fill(values.begin(), values.end(), 0.0);
      set_box(x_, values);
      ColumnSolve out;
      out.error = HYPRE_StructPCGSolve(solver_, A_, b_, x_);
      HYPRE_StructPCGGetNumIterations(solver_, &out.iterations);
      HYPRE_StructPCGGetFinalRelativeResidualNorm(solver_, &out.residual);
      return out;
    };
    auto read = [&](int c) {
      if (local > 0) {
        std::array<HYPRE_Int, 2> lower{0, first_row_}, upper{grid_.cols - 1, last_row_ - 1};
        HYPRE_StructVectorGetBoxValues(x_, lower.data(), upper.data(), values.data());
      }
      hypre_detail::all_gather_blocks(values, grid_.rows, grid_.cols, gathered);
      for (std::size_t p = 0; p < gathered.size(); ++p)
        if (number_[p] >= 0) X(number_[p], c) = gathered[p];
    };
    return solve_columns(B, X, summary, solve, read);
  }

 private:
  void set_box(HYPRE_StructVector v, std::vector<double>& values) const {
    if (last_row_ > first_row_) {
      std::array<HYPRE_Int, 2> lower{0, first_row_}, upper{grid_.cols - 1, last_row_ - 1};
      HYPRE_StructVectorSetBoxValues(v, lower.data(), upper.data(), values.data());
    }
    HYPRE_StructVectorAssemble(v);
  }

  // The grid, stencil, matrix, vectors and solver on this rank's block of grid rows. hypre's
  // index is (x, y) = (j, i); couplings that leave the grid or reach a fixed point are zero.
  HYPRE_Int build() {
    MPI_Comm comm = hypre_detail::communicator();
    const auto [first, last] = block_of(grid_.rows, mpi_rank(), mpi_size());
    first_row_ = int(first);
    last_row_ = int(last);
    const int r = grid_.radius;
    // The stencil's offsets (di, dj), the centre first: the 5-point cross always (PFMG's set-up
    // looks its entries up), the diagonals when any is non-zero, every 5×5 offset at radius 2.
    bool diagonal = r == 2;
    for (int di : {-1, 1})
      for (int dj : {-1, 1}) diagonal = diagonal || grid_.weight(di, dj) != 0;
    std::vector<std::array<int, 2>> offsets{{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (int di = -r; di <= r; ++di)
      for (int dj = -r; dj <= r; ++dj)
        if (std::abs(di) + std::abs(dj) > 1 && diagonal) offsets.push_back({di, dj});

    std::array<HYPRE_Int, 2> lower{0, first_row_}, upper{grid_.cols - 1, last_row_ - 1};
    HYPRE_StructGridCreate(comm, 2, &grid_handle_);
    if (last_row_ > first_row_) HYPRE_StructGridSetExtents(grid_handle_, lower.data(), upper.data());
    HYPRE_StructGridAssemble(grid_handle_);
    HYPRE_StructStencilCreate(2, HYPRE_Int(offsets.size()), &stencil_);
    for (std::size_t e = 0; e < offsets.size(); ++e) {
      std::array<HYPRE_Int, 2> offset{offsets[e][1], offsets[e][0]};
      HYPRE_StructStencilSetElement(stencil_, HYPRE_Int(e), offset.data());
    }
    HYPRE_StructMatrixCreate(comm, grid_handle_, stencil_, &A_);
    HYPRE_StructMatrixInitialize(A_);
    if (last_row_ > first_row_) {
      std::vector<HYPRE_Int> entries(offsets.size());
      for (std::size_t e = 0; e < offsets.size(); ++e) entries[e] = HYPRE_Int(e);
      std::vector<double> values;
      values.reserve(std::size_t(last_row_ - first_row_) * std::size_t(grid_.cols) * offsets.size());
      for (int i = first_row_; i < last_row_; ++i)
        for (int j = 0; j < grid_.cols; ++j)
          for (const auto& [di, dj] : offsets) {
            if (!grid_.is_free(i, j)) {  // an identity row
              values.push_back(di == 0 && dj == 0 ? 1.0 : 0.0);
              continue;
            }
            const int ii = i + di, jj = j + dj;
            const bool inside = ii >= 0 && ii < grid_.rows && jj >= 0 && jj < grid_.cols;
            values.push_back(inside && grid_.is_free(ii, jj) ? grid_.weight(di, dj) : 0.0);
          }
      HYPRE_StructMatrixSetBoxValues(A_, lower.data(), upper.data(), HYPRE_Int(offsets.size()), entries.data(),
                                     values.data());
    }
    HYPRE_StructMatrixAssemble(A_);
    for (HYPRE_StructVector* v : {&b_, &x_}) {
      HYPRE_StructVectorCreate(comm, grid_handle_, v);
      HYPRE_StructVectorInitialize(*v);
      HYPRE_StructVectorAssemble(*v);
    }

    HYPRE_StructPCGCreate(comm, &solver_);
    HYPRE_StructPCGSetTol(solver_, options_.tolerance);
    HYPRE_StructPCGSetTwoNorm(solver_, 1);  // stop at ‖r‖₂ ≤ tolerance·‖b‖₂
    HYPRE_StructPCGSetRelChange(solver_, 0);
    HYPRE_StructPCGSetMaxIter(solver_, limit());
    // Logging 0: with it, hypre prints an "ERROR detected by Hypre" banner on stdout (inside a
    // JSON report) on overflowing input. Iterations and the final residual are kept without it.
    HYPRE_StructPCGSetLogging(solver_, 0);
    HYPRE_StructPCGSetPrintLevel(solver_, 0);
    if (method_ == StructMethod::kPfmg) {
      HYPRE_StructPFMGCreate(comm, &precond_);
      HYPRE_StructPFMGSetMaxIter(precond_, 1);
      HYPRE_StructPFMGSetTol(precond_, 0.0);
      HYPRE_StructPFMGSetZeroGuess(precond_);
      HYPRE_StructPFMGSetRelaxType(precond_, kPfmgRelaxType);
      HYPRE_StructPFMGSetJacobiWeight(precond_, jacobi_weight());
      HYPRE_StructPFMGSetNumPreRelax(precond_, kPfmgSweeps);
      HYPRE_StructPFMGSetNumPostRelax(precond_, kPfmgSweeps);
      HYPRE_StructPCGSetPrecond(solver_, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, precond_);
    } else {
      HYPRE_StructSMGCreate(comm, &precond_);
      HYPRE_StructSMGSetMemoryUse(precond_, 0);
      HYPRE_StructSMGSetMaxIter(precond_, 1);
      HYPRE_StructSMGSetTol(precond_, 0.0);
      HYPRE_StructSMGSetZeroGuess(precond_);
      HYPRE_StructSMGSetNumPreRelax(precond_, 1);
      HYPRE_StructSMGSetNumPostRelax(precond_, 1);
      HYPRE_StructPCGSetPrecond(solver_, HYPRE_StructSMGSolve, HYPRE_StructSMGSetup, precond_);
    }
    const HYPRE_Int error = HYPRE_StructPCGSetup(solver_, A_, b_, x_);
    HYPRE_ClearAllErrors();
    return error;
  }

  // ω = 4/(3·G) with G = Σ|w| / |w(0,0)| ≥ the largest eigenvalue of D⁻¹A (Gershgorin): the
  // weighted Jacobi smoother then converges (ω·λ < 2) on every stencil, α = −1/4 (G = 4) and
  // the 5×5 ones included, and ω = 2/3 for the 5-point Laplacian.
  [[nodiscard]] double jacobi_weight() const {
    double sum = 0;
    for (double w : grid_.weights) sum += std::abs(w);
    return 4.0 / (3.0 * sum / std::abs(grid_.weight(0, 0)));
  }

  void release() {
    if (solver_) HYPRE_StructPCGDestroy(solver_);
    if (precond_) (method_ == StructMethod::kPfmg ? HYPRE_StructPFMGDestroy : HYPRE_StructSMGDestroy)(precond_);
    if (x_) HYPRE_StructVectorDestroy(x_);
    if (b_) HYPRE_StructVectorDestroy(b_);
    if (A_) HYPRE_StructMatrixDestroy(A_);
    if (stencil_) HYPRE_StructStencilDestroy(stencil_);
    if (grid_handle_) HYPRE_StructGridDestroy(grid_handle_);
    solver_ = precond_ = nullptr;
    x_ = b_ = nullptr;
    A_ = nullptr;
    stencil_ = nullptr;
    grid_handle_ = nullptr;
  }

  static constexpr int kPfmgRelaxType = 1;  // weighted Jacobi: symmetric, for any stencil
  static constexpr int kPfmgSweeps = 2;

  std::string name_;
  StructMethod method_;
  StencilOperator grid_;
  std::vector<Eigen::Index> number_;  // grid point (row-major) -> unknown, −1 at fixed points
  int first_row_ = 0, last_row_ = 0;  // this rank's grid rows [first, last)
  HYPRE_StructGrid grid_handle_ = nullptr;
  HYPRE_StructStencil stencil_ = nullptr;
  HYPRE_StructMatrix A_ = nullptr;
  HYPRE_StructVector b_ = nullptr, x_ = nullptr;
  HYPRE_StructSolver solver_ = nullptr, precond_ = nullptr;
};

}  // namespace

std::unique_ptr<LinearSolver> make_hypre_pfmg(const SolverOptions& o) {
  return std::make_unique<HypreStructBackend>("hypre-pfmg", StructMethod::kPfmg, o);
}
std::unique_ptr<LinearSolver> make_hypre_smg(const SolverOptions& o) {
  return std::make_unique<HypreStructBackend>("hypre-smg", StructMethod::kSmg, o);
}

}  // namespace coons::solvers
