// dst: X = S (S B ./ λ) / (2(rows+1)·2(cols+1)), S the 2-D DST-I (FFTW RODFT00 × RODFT00).
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965); eigenvalues from G. Farin & D. Hansford, Discrete Coons patches, CAGD 16 (1999).
#include <fftw3.h>

#include <cmath>
#include <string>
#include <vector>

#include "sine_transform.h"
#include "structured_solvers.h"

namespace coons::solvers {
namespace {

using detail::AlignedBuffer;

// o = σ·tb + l·τ + r·τ' (then ∘ inv when given): one row of the ring right-hand side's transform.
COONS_VECTOR_CLONES void ring_row(double sigma, const double* __restrict tb, double l, const double* __restrict tau,
                                  double r, const double* __restrict tau_signed, const double* __restrict inv,
                                  double* __restrict o, int n) {
  if (inv)
    for (int q = 0; q < n; ++q) o[q] = (sigma * tb[q] + l * tau[q] + r * tau_signed[q]) * inv[q];
  else
    for (int q = 0; q < n; ++q) o[q] = sigma * tb[q] + l * tau[q] + r * tau_signed[q];
}

class FftwPlan {
 public:
  FftwPlan() = default;
  explicit FftwPlan(fftw_plan plan) : plan_(plan) {}
  ~FftwPlan() { reset(); }
  FftwPlan(const FftwPlan&) = delete;
  FftwPlan& operator=(const FftwPlan&) = delete;
  FftwPlan& operator=(FftwPlan&& other) noexcept {
    if (this != &other) {
      reset();
      plan_ = other.plan_;
      other.plan_ = nullptr;
    }
    return *this;
  }
  void execute() const { fftw_execute(plan_); }
  explicit operator bool() const { return plan_ != nullptr; }

 private:
  void reset() {
    if (plan_) fftw_destroy_plan(plan_);
    plan_ = nullptr;
  }
  fftw_plan plan_ = nullptr;
};

class DstSolver : public detail::StructuredSolver {
 public:
  explicit DstSolver(const SolverOptions& options) : StructuredSolver(options) {}
  [[nodiscard]] std::string name() const override { return "dst"; }

 protected:
  // A sweep transforms each basis right-hand side once (hat_[r][c], R×C) and combines the
  // transforms per member.
  void do_begin_sweep() override { hat_.clear(); }
  SolveStatus do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::MatrixX3d& X, SolveSummary& summary) override;

  SolveStatus analyze_grid(SolveSummary& summary) override {
    const std::size_t n = std::size_t(R_) * std::size_t(C_);
    grid_ = AlignedBuffer(n);
    row_ = AlignedBuffer(std::size_t(C_));
    col_ = AlignedBuffer(std::size_t(R_));
    inverse_eigenvalues_.assign(n, 0.0);
    const unsigned planning = detail::fft_planning(options_);
    detail::fft_plan_threads(options_.threads);  // the 2-D transforms are the cost: only they get threads
    plan_2d_ = FftwPlan(fftw_plan_r2r_2d(R_, C_, grid_.data(), grid_.data(), FFTW_RODFT00, FFTW_RODFT00, planning));
    detail::fft_plan_threads(1);
    plan_row_ = FftwPlan(fftw_plan_r2r_1d(C_, row_.data(), row_.data(), FFTW_RODFT00, planning));
    plan_col_ = FftwPlan(fftw_plan_r2r_1d(R_, col_.data(), col_.data(), FFTW_RODFT00, planning));
    if (!plan_2d_ || !plan_row_ || !plan_col_) {
      summary.message = "FFTW could not make a plan";
      return SolveStatus::kFailure;
    }
    // 2 sin(π(p+1)/(rows+1)): the RODFT00 of e_0 (and, with signs (−1)^p, of e_{rows−1}).
    edge_i_.resize(std::size_t(R_));
    edge_j_.resize(std::size_t(C_));
    for (int p = 0; p < R_; ++p) edge_i_[std::size_t(p)] = 2 * std::sin(M_PI * (p + 1) / (R_ + 1));
    for (int q = 0; q < C_; ++q) edge_j_[std::size_t(q)] = 2 * std::sin(M_PI * (q + 1) / (C_ + 1));
    return SolveStatus::kSuccess;
  }

  SolveStatus factorize_grid(const LinearOperator& /*op*/, const GridStencil& s, SolveSummary& summary) override {
    std::vector<double> x(static_cast<std::size_t>(R_)), y(static_cast<std::size_t>(C_));
    for (int p = 0; p < R_; ++p) x[std::size_t(p)] = std::cos(M_PI * (p + 1) / (R_ + 1));
    for (int q = 0; q < C_; ++q) y[std::size_t(q)] = std::cos(M_PI * (q + 1) / (C_ + 1));
    // FFTW's RODFT00 applied twice multiplies by 2(n+1): fold that into 1/λ.
    const double norm = 4.0 * (R_ + 1) * (C_ + 1);
    double smallest = HUGE_VAL, largest = 0;
    for (int p = 0; p < R_; ++p) {
      const double xp = x[std::size_t(p)];
      const double a = s.center + 2 * s.edge_i * xp, b = 2 * s.edge_j + 4 * s.diag * xp;
      double* inv = inverse_eigenvalues_.data() + std::size_t(p) * std::size_t(C_);
      for (int q = 0; q < C_; ++q) {
        const double lambda = a + b * y[std::size_t(q)];
        smallest = std::min(smallest, std::abs(lambda));
        largest = std::max(largest, std::abs(lambda));
        inv[q] = 1 / (lambda * norm);
      }
    }
    if (!(smallest > kSingularEigenvalue * largest)) {
      summary.message = "smallest |eigenvalue| " + std::to_string(smallest) + " of largest " + std::to_string(largest) +
                        ": the stencil is singular";
      return SolveStatus::kSingular;
    }
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    X.resize(B.rows(), 3);
    for (int c = 0; c < 3; ++c) {
      divide_and_invert(X.col(c).data(), forward(B.col(c).data(), true));
    }
    summary.iterations = 1;
    return SolveStatus::kSuccess;
  }

 private:
  static constexpr double kSingularEigenvalue = 1e-13;

  // True when only the ring next to the frame can be non-zero: rows 1..R−2 are zero at 1..C−2.
  bool on_ring(const double* b) const {
    if (R_ < 3 || C_ < 3) return false;
    for (int i = 1; i + 1 < R_; ++i) {
      const double* row = b + std::size_t(i) * std::size_t(C_);
      for (int j = 1; j + 1 < C_; ++j)
        if (row[j] != 0) return false;
    }
    return true;
  }

  // grid_ = 2-D RODFT00 of the grid b (R×C, row-major). A right-hand side on the ring transforms in
  // closed form from the 1-D transforms of its four sides:
  //   B̂(p,q) = σ_p (t̂_q + (−1)^p b̂_q) + τ_q (l̂_p + (−1)^q r̂_p),   σ, τ = edge_i_, edge_j_,
  // and then, when `divide`, is divided by the eigenvalues in the same pass. Returns whether it
  // divided.
  bool forward(const double* b, bool divide) {
    const std::size_t n = std::size_t(R_) * std::size_t(C_);
    double* out = grid_.data();
    if (!on_ring(b)) {
      std::copy(b, b + n, out);
      plan_2d_.execute();
      return false;
    }
    const bool divided = divide;
    auto row_transform = [&](int i, std::vector<double>& t) {
      std::copy(b + std::size_t(i) * C_, b + std::size_t(i + 1) * C_, row_.data());
      plan_row_.execute();
      t.assign(row_.data(), row_.data() + C_);
    };
    auto col_transform = [&](int j, std::vector<double>& t) {
      col_[0] = 0;
      col_[std::size_t(R_ - 1)] = 0;
      for (int i = 1; i + 1 < R_; ++i) col_[std::size_t(i)] = b[std::size_t(i) * C_ + j];
      plan_col_.execute();
      t.assign(col_.data(), col_.data() + R_);
    };
    row_transform(0, top_);
    row_transform(R_ - 1, bottom_);
    col_transform(0, left_);
    col_transform(C_ - 1, right_);
    const auto width = static_cast<std::size_t>(C_);
    std::vector<double> plus(width), minus(width), signed_edge(width);
    for (int q = 0; q < C_; ++q) {
      plus[std::size_t(q)] = top_[std::size_t(q)] + bottom_[std::size_t(q)];
      minus[std::size_t(q)] = top_[std::size_t(q)] - bottom_[std::size_t(q)];
      signed_edge[std::size_t(q)] = q % 2 ? -edge_j_[std::size_t(q)] : edge_j_[std::size_t(q)];
    }
    for (int p = 0; p < R_; ++p) {
      const double* tb = p % 2 ? minus.data() : plus.data();
      const double* inv = divided ? inverse_eigenvalues_.data() + std::size_t(p) * C_ : nullptr;
      ring_row(edge_i_[std::size_t(p)], tb, left_[std::size_t(p)], edge_j_.data(), right_[std::size_t(p)],
               signed_edge.data(), inv, out + std::size_t(p) * C_, C_);
    }
    return divided;
  }

  // grid_ holds B̂ (divided: B̂ ./ λ): X = S (B̂ ./ λ) / norm, written to x.
  void divide_and_invert(double* x, bool divided) {
    const std::size_t n = std::size_t(R_) * std::size_t(C_);
    double* g = grid_.data();
    const double* inv = inverse_eigenvalues_.data();
    if (!divided)
      for (std::size_t k = 0; k < n; ++k) g[k] *= inv[k];
    plan_2d_.execute();
    detail::stream_copy(g, x, n);
    detail::stream_fence();
  }

  AlignedBuffer grid_, row_, col_;
  FftwPlan plan_2d_, plan_row_, plan_col_;
  std::vector<double> inverse_eigenvalues_, edge_i_, edge_j_;
  std::vector<double> top_, bottom_, left_, right_;
  std::vector<std::vector<std::vector<double>>> hat_;  // a sweep's transformed basis
};

SolveStatus DstSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                                      Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::Index n = Eigen::Index(R_) * C_;
  const std::size_t used = weights.size();
  if (hat_.size() < used || (!hat_.empty() && hat_[0][0].size() != std::size_t(n))) {
    hat_.assign(used, {});
    for (std::size_t r = 0; r < used; ++r) {
      hat_[r].resize(3);
      for (int c = 0; c < 3; ++c) {
        forward(basis[r].col(c).data(), false);
        hat_[r][std::size_t(c)].assign(grid_.data(), grid_.data() + n);
      }
    }
  }
  X.resize(n, 3);
  for (int c = 0; c < 3; ++c) {
    double* g = grid_.data();
    std::fill(g, g + n, 0.0);
    for (std::size_t r = 0; r < used; ++r) {
      const double w = weights[r];
      const double* h = hat_[r][std::size_t(c)].data();
      if (w != 0)
        for (Eigen::Index m = 0; m < n; ++m) g[m] += w * h[m];
    }
    divide_and_invert(X.col(c).data(), false);
  }
  summary.iterations = 1;
  return SolveStatus::kSuccess;
}

}  // namespace

std::unique_ptr<LinearSolver> make_dst_solver(const SolverOptions& options) {
  return std::make_unique<DstSolver>(options);
}

}  // namespace coons::solvers
