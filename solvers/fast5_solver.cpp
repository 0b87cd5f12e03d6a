#include "fast5_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "fast5_capacitance.h"
#include "fast5_modes.h"
#include "separable_banded_solver.h"
#include "sine_transform.h"

#if defined(_OPENMP)
// A loop over independent units on `nt` threads (a local); each unit writes its own data.
#define COONS_PARALLEL_FOR _Pragma("omp parallel for num_threads(nt) if (nt > 1) schedule(dynamic)")
#else
#define COONS_PARALLEL_FOR
#endif

namespace coons::solvers {

namespace {

using fast5_detail::CapacitanceBlock;
using fast5_detail::first_sine_column;
using fast5_detail::ModeFactors;
using fast5_detail::second_difference_eigenvalues;

// Modes per unit of the threaded sweeps (fixed: the partial sums do not depend on the thread count).
constexpr int kModeChunk = 128;

constexpr std::array<double, 5> kDelta4 = {1, -4, 6, -4, 1};
constexpr std::array<double, 5> kDelta2 = {0, 1, -2, 1, 0};
constexpr std::array<double, 5> kImpulse = {0, 0, 1, 0, 0};
// The capacitance CG stops at this residual relative to its right-hand side: the boundary
// corrections remove what is left (the first solve is only accurate to 1e-5 there at N = 1023
// anyway, see the header). A correction solves to the accuracy it needs (to bring the boundary
// residual to a tenth of kBoundaryResidual), within [kCorrectionTolerance, 1e-2].
constexpr double kCapacitanceTolerance = 1e-7;
constexpr double kCorrectionTolerance = 1e-10;
constexpr int kCorrections = 3;              // at most this many boundary corrections per solve
constexpr double kBoundaryResidual = 1e-13;  // relative residual on the boundary columns at which they stop

double c_weight(int di, int dj) { return kDelta4[std::size_t(di) + 2] * kDelta4[std::size_t(dj) + 2]; }
double t_weight(int di, int dj) {
  const auto i = std::size_t(di) + 2, j = std::size_t(dj) + 2;
  return kDelta4[i] * kImpulse[j] + 2 * kDelta2[i] * kDelta2[j] + kImpulse[i] * kDelta4[j];
}

// The unknown-independent checks of fast5: a grid operator, every point free, a·C + b·T.
bool describe(const LinearOperator& op, SolveSummary& summary, C1FamilyWeights* weights) {
  if (!op.grid) {
    summary.message = "needs the 5x5 grid operator (a full rectangle with an a*C + b*T stencil)";
    return false;
  }
  const StencilOperator& g = *op.grid;
  if (std::string why = grid_operator_problem(g, op.matrix); !why.empty()) {
    summary.message = why;
    return false;
  }
  if (g.size() != Eigen::Index(g.rows) * g.cols) {
    summary.message = "needs a full rectangle (every grid point free); use pcg-fast for other free sets";
    return false;
  }
  const auto w = c1_family_weights(g);
  if (!w) {
    summary.message = "the stencil is not a*C + b*T with a, b >= 0 (c1-coons, c1-family, biharmonic)";
    return false;
  }
  if (weights) *weights = *w;
  return true;
}

class Fast5Solver final : public LinearSolver {
 public:
  explicit Fast5Solver(const SolverOptions& options) : LinearSolver(options) {}
  [[nodiscard]] std::string name() const override { return "fast5"; }

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    if (!describe(op, summary, nullptr)) return SolveStatus::kNotApplicable;
    R_ = op.grid->rows;
    C_ = op.grid->cols;
    const unsigned planning = detail::fft_planning(options_);
    threads_ = resolved_threads(options_.threads);
    along_i_ = detail::SineTransform(R_, planning);
    along_j_.clear();
    for (int t = 0; t < threads_; ++t) along_j_.emplace_back(C_, planning);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    C1FamilyWeights w;
    if (!describe(op, summary, &w)) return SolveStatus::kNotApplicable;
    weights_ = w;
    separable_ = !(w.b > 1e-12 * w.a);
    if (separable_) return SolveStatus::kSuccess;
    factor_modes();
    build_capacitance();
    summary.factor_nnz = 3LL * R_ * C_;
    return SolveStatus::kSuccess;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    if (separable_) {  // a·P⊗P
      SeparableBandedOperator sep;
      sep.rows = R_;
      sep.cols = C_;
      sep.along_i = {6 * weights_.a, -4 * weights_.a, weights_.a};
      sep.along_j = {6, -4, 1};
      summary.iterations = 1;
      const SolveStatus status = separable_banded_solve(sep, B, X, resolved_threads(options_.threads));
      if (status != SolveStatus::kSuccess) summary.message = "a zero pivot in the banded LDL^T of a factor";
      return status;
    }
    const int count = 3;
    for (int c = 0; c < count; ++c) b_norms_[std::size_t(c)] = B.col(c).norm();
    // X holds the transformed rows (the hats) until the inverse transform at the end
    X.resize(B.rows(), 3);
    for (int c = 0; c < count; ++c) hats_[std::size_t(c)] = X.col(c).data();
    transform_rows(count, true, B);
    // ŷ = A₁⁻¹ b̂ and its boundary columns g (both parities); h = Cap⁻¹ g; x̂ = ŷ − A₁⁻¹ U h.
    banded_solve_all(count, dots_);
    std::array<Eigen::MatrixXd, 2> h;
    int iterations = capacitance_solve(dots_, count, kCapacitanceTolerance, h);
    add_boundary_response(count, h, -1.0, true);
    // The columns 0 and cols−1 carry the rounding of h (see the header): correct them from the
    // residual there, which is exact, until it is below kBoundaryResidual relative to b.
    std::array<Eigen::MatrixXd, 2> rho;
    for (int step = 0; step < kCorrections; ++step) {
      if (!boundary_residual(B, count, rho)) break;
      const double tolerance = std::clamp(0.1 * kBoundaryResidual / boundary_ratio_, kCorrectionTolerance, 1e-2);
      iterations = std::max(iterations, capacitance_solve(rho, count, tolerance, h));
      add_boundary_response(count, h, 1.0, false);
    }
    transform_rows(count, false, B);
    summary.iterations = iterations;
    return SolveStatus::kSuccess;
  }

 private:
  // forward: hats_[c] (X's column c) = the sine transform of each row of B's column c; a row that is
  // zero but on the columns 0, 1, cols−2, cols−1 (most rows of a mask system: the data rings are
  // next to them) is the combination of those four columns' sine vectors instead (exact, no
  // transform). Otherwise X's column c = the inverse transform of each of its rows, in place. Rows
  // shared among the threads, one transform each (a SineTransform is not thread-safe).
  void transform_rows(int count, bool forward, const Eigen::MatrixX3d& B) {
    const double scale_j = std::sqrt(2.0 / (C_ + 1));
    const bool edges = forward && C_ >= 6;
    [[maybe_unused]] const int nt = threads_;
#if defined(_OPENMP)
#pragma omp parallel num_threads(nt) if (nt > 1)
#endif
    {
      detail::SineTransform& along_j = along_j_[std::size_t(thread_index())];
#if defined(_OPENMP)
#pragma omp for schedule(static)
#endif
      for (int unit = 0; unit < count * R_; ++unit) {
        const int c = unit / R_, r = unit % R_;
        double* hat = hats_[std::size_t(c)] + std::ptrdiff_t(r) * C_;
        if (!forward) {
          along_j.apply(hat, hat, scale_j);
          continue;
        }
        const double* b = B.col(c).data() + std::ptrdiff_t(r) * C_;
        if (edges && std::all_of(b + 2, b + C_ - 2, [](double v) { return v == 0; })) {
          // the sine vector of column cols−1−j is that of column j times (−1)^q
          const double e0 = b[0], e1 = b[1], e2 = b[C_ - 2], e3 = b[C_ - 1];
          const double* s0 = near_sines_.col(0).data();
          const double* s1 = near_sines_.col(1).data();
          for (int q = 0; q + 1 < C_; q += 2) {
            hat[q] = (e0 + e3) * s0[q] + (e1 + e2) * s1[q];
            hat[q + 1] = (e0 - e3) * s0[q + 1] + (e1 - e2) * s1[q + 1];
          }
          if (C_ % 2 == 1) hat[C_ - 1] = (e0 + e3) * s0[C_ - 1] + (e1 + e2) * s1[C_ - 1];
        } else {
          along_j.apply(b, hat, scale_j);
        }
      }
    }
  }

  // The banded LDLᵀ of M_q = (aν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I for every mode q along j.
  void factor_modes() {
    nu_ = second_difference_eigenvalues(C_);
    factors_ = fast5_detail::factor_modes(weights_.a, weights_.b, nu_, R_, threads_);
  }

  // The four capacitance blocks (parity of q) × (parity of p), see the header, and the sine
  // vectors of the grid columns next to the boundary (for the boundary residual).
  void build_capacitance() {
    const double a = weights_.a, b = weights_.b;
    const Eigen::VectorXd mu = second_difference_eigenvalues(R_);
    t_ = std::sqrt(2.0) * first_sine_column(C_);
    tmasks_.setZero(C_, 2);  // t_q on the modes of each parity
    for (int q = 0; q < C_; ++q) tmasks_(q, q % 2) = t_[q];
    near_sines_.resize(C_, 3);  // columns 0, 1, 2 (those of cols−1, cols−2, cols−3 times (−1)^q)
    for (int j = 0; j < 3; ++j)
      for (int q = 0; q < C_; ++q)
        near_sines_(q, j) = std::sqrt(2.0 / (C_ + 1)) * std::sin(M_PI * (j + 1) * (q + 1) / (C_ + 1));
    blocks_ = fast5_detail::capacitance_blocks(a, b, mu, nu_, t_, threads_);
  }

  // M⁻¹ of the input (see SweepInput) for every mode, into `output`, and out(r, 2k·c + 2m + p) = the
  // sum over the modes q of parity p of row r of the new values times sines(q, m), k = #sines. The
  // modes go in chunks of kModeChunk, each swept down and up in a per-thread buffer that stays in
  // the cache; the chunks' partial sums are added in their order (so the same on any number of
  // threads).
  void solve_modes(int count, const fast5_detail::SweepInput& in, const fast5_detail::ChunkOutput& output,
                   const Eigen::MatrixXd& sines, Eigen::MatrixXd& out) {
    const int chunks = (C_ + kModeChunk - 1) / kModeChunk;
    partial_.resize(std::size_t(chunks));
    buffers_.resize(std::size_t(threads_));
    [[maybe_unused]] const int nt = threads_;
    // On threads, taken in the order 0, h, 1, h + 1, ... (h = half the chunks): the chunks that run
    // at the same time are not neighbours, whose rows in X share a cache line at their border.
    const int half = (chunks + 1) / 2;
    COONS_PARALLEL_FOR
    for (int i = 0; i < chunks; ++i) {
      const int k = nt == 1 ? i : i % 2 == 0 ? i / 2 : half + i / 2;
      std::vector<double>& buf = buffers_[std::size_t(thread_index())];
      const int b0 = k * kModeChunk, b1 = std::min(C_, b0 + kModeChunk);
      buf.resize(3 * std::size_t(R_) * std::size_t(b1 - b0));
      fast5_detail::solve_chunk(factors_, b0, b1, count, in, output, buf.data(), sines, partial_[std::size_t(k)]);
    }
    out = partial_[0];
    for (std::size_t k = 1; k < partial_.size(); ++k) out += partial_[k];
  }

  // The input sign·U z_c (or none) plus the hats (with from_hats).
  [[nodiscard]] fast5_detail::SweepInput sweep_input(bool from_hats, const std::array<Eigen::MatrixXd, 2>* z,
                                                     double sign) const {
    fast5_detail::SweepInput in;
    if (from_hats) in.hats = {hats_[0], hats_[1], hats_[2]};
    in.z = z;
    in.sign = sign;
    in.t_even = tmasks_.col(0).data();
    in.t_odd = tmasks_.col(1).data();
    return in;
  }

  // g(r, 2c + parity) = Σ_q (M⁻¹ hat_c)(r, q)·t_q over the modes q of that parity (hats_ kept).
  void banded_solve_all(int count, Eigen::MatrixXd& g) { solve_modes(count, sweep_input(true, nullptr, 0), {}, t_, g); }

  // With replace: hats_[c] ← M⁻¹(hats_[c] + sign·U z_c); otherwise hats_[c] += sign·M⁻¹ U z_c.
  // near_values_(r, 6c + k) = the new hats on the columns 0, 1, 2, cols−3, cols−2, cols−1 (k = 0..5).
  void add_boundary_response(int count, const std::array<Eigen::MatrixXd, 2>& z, double sign, bool replace) {
    fast5_detail::ChunkOutput output;
    output.grid = {hats_[0], hats_[1], hats_[2]};
    output.add = !replace;
    solve_modes(count, sweep_input(replace, &z, sign), output, near_sines_, near_values_);
    // parity parts (even, odd) of the columns 0, 1, 2 → the six columns
    Eigen::MatrixXd parts;
    std::swap(parts, near_values_);
    near_values_.resize(R_, 6 * count);
    for (int c = 0; c < count; ++c)
      for (int j = 0; j < 3; ++j) {
        const auto even = parts.col(6 * c + 2 * j), odd = parts.col(6 * c + 2 * j + 1);
        near_values_.col(6 * c + j) = even + odd;
        near_values_.col(6 * c + 5 - j) = even - odd;
      }
  }

  // The capacitance system for each parity of q: rhs[qpar] is rows × count in the grid (along i);
  // with apply_h the right-hand side is H⁻¹·rhs. out[qpar] = Cap⁻¹ (H⁻¹) rhs, the same shape.
  int capacitance_solve(const Eigen::MatrixXd& g, int count, double tolerance, std::array<Eigen::MatrixXd, 2>& out) {
    std::array<Eigen::MatrixXd, 2> rhs;
    for (int qpar = 0; qpar < 2; ++qpar) {
      rhs[std::size_t(qpar)].resize(R_, count);
      for (int c = 0; c < count; ++c) rhs[std::size_t(qpar)].col(c) = g.col(2 * c + qpar);
    }
    return capacitance_solve(rhs, count, tolerance, out, false);
  }

  int capacitance_solve(const std::array<Eigen::MatrixXd, 2>& rhs, int count, double tolerance,
                        std::array<Eigen::MatrixXd, 2>& out, bool apply_h = true) {
    const double scale_i = std::sqrt(2.0 / (R_ + 1));
    std::array<Eigen::MatrixXd, 2> hat, solved;
    Eigen::VectorXd column(R_);
    for (std::size_t qpar = 0; qpar < 2; ++qpar) {
      hat[qpar].resize(R_, count);
      solved[qpar].resize(R_, count);
      for (int c = 0; c < count; ++c) {
        column = rhs[qpar].col(c);
        along_i_.apply(column.data(), hat[qpar].col(c).data(), scale_i);
      }
    }
    // the four blocks (parity of q) × (parity of p) are independent; each writes its own rows
    std::array<int, 4> iterations{};
    [[maybe_unused]] const int nt = threads_;
    COONS_PARALLEL_FOR
    for (int b = 0; b < 4; ++b) {
      const CapacitanceBlock& blk = blocks_[std::size_t(b)];
      const std::size_t qpar = std::size_t(b) / 2;
      Eigen::MatrixXd block_rhs(Eigen::Index(blk.modes.size()), count), part;
      for (std::size_t k = 0; k < blk.modes.size(); ++k) block_rhs.row(Eigen::Index(k)) = hat[qpar].row(blk.modes[k]);
      if (apply_h) blk.apply_h_inverse(block_rhs);
      iterations[std::size_t(b)] = blk.solve(block_rhs, part, tolerance);
      for (std::size_t k = 0; k < blk.modes.size(); ++k) solved[qpar].row(blk.modes[k]) = part.row(Eigen::Index(k));
    }
    for (std::size_t qpar = 0; qpar < 2; ++qpar) {
      out[qpar].resize(R_, count);
      for (int c = 0; c < count; ++c) {
        column = solved[qpar].col(c);
        along_i_.apply(column.data(), out[qpar].col(c).data(), scale_i);
      }
    }
    return *std::max_element(iterations.begin(), iterations.end());
  }

  // ρ = (b − A x) on the columns 0 and cols−1 in parity coordinates (rows × count each), x from
  // near_values_; false when it is below kBoundaryResidual·‖b‖ for every right-hand side.
  bool boundary_residual(const Eigen::MatrixX3d& B, int count, std::array<Eigen::MatrixXd, 2>& rho) {
    const double a = weights_.a, b = weights_.b;
    std::array<double, 25> w5{};
    for (int di = -2; di <= 2; ++di)
      for (int dj = -2; dj <= 2; ++dj)
        w5[std::size_t(di + 2) * 5 + std::size_t(dj + 2)] = a * c_weight(di, dj) + b * t_weight(di, dj);
    std::array<Eigen::MatrixXd, 2> side;  // the residual on column 0 and on column cols−1
    bool large = false;
    for (int s = 0; s < 2; ++s) side[std::size_t(s)].resize(R_, count);
    for (int c = 0; c < count; ++c) {
      const auto value = [&](int i, int j) {
        if (i < 0 || i >= R_ || j < 0 || j >= C_) return 0.0;
        return near_values_(i, 6 * c + (j < 3 ? j : j - C_ + 6));
      };
      double norm2 = 0;
      for (int s = 0; s < 2; ++s) {
        const int j = s == 0 ? 0 : C_ - 1;
        for (int i = 0; i < R_; ++i) {
          double r = B(Eigen::Index(i) * C_ + j, c);
          for (int di = -2; di <= 2; ++di)
            for (int dj = -2; dj <= 2; ++dj)
              r -= w5[std::size_t(di + 2) * 5 + std::size_t(dj + 2)] * value(i + di, j + dj);
          side[std::size_t(s)](i, c) = r;
        }
        norm2 += side[std::size_t(s)].col(c).squaredNorm();
      }
      // A zero column has a zero solution and no boundary residual; 0/0 would make the ratio, and
      // with it every column's correction tolerance, NaN (and every correction a no-op).
      const double ratio = b_norms_[std::size_t(c)] > 0 ? std::sqrt(norm2) / b_norms_[std::size_t(c)] : 0.0;
      boundary_ratio_ = c == 0 ? ratio : std::max(boundary_ratio_, ratio);
      if (ratio > kBoundaryResidual) large = true;
    }
    if (!large) return false;
    for (int s = 0; s < 2; ++s) rho[std::size_t(s)].resize(R_, count);
    if (C_ == 1) {  // U = √2·e₁ in the even parity
      rho[0] = side[0] / std::sqrt(2.0);
      rho[1].setZero();
    } else {
      rho[0] = (side[0] + side[1]) / std::sqrt(2.0);
      rho[1] = (side[0] - side[1]) / std::sqrt(2.0);
    }
    return true;
  }

  int R_ = 0, C_ = 0;
  C1FamilyWeights weights_;
  bool separable_ = false;
  int threads_ = 1;
  detail::SineTransform along_i_;
  std::vector<detail::SineTransform> along_j_;  // one per thread
  Eigen::VectorXd nu_, t_;
  Eigen::MatrixXd tmasks_, near_sines_, dots_;
  std::array<double, 3> b_norms_{};
  double boundary_ratio_ = 0;  // the largest ‖ρ‖/‖b‖ of the last boundary_residual
  ModeFactors factors_;
  std::array<CapacitanceBlock, 4> blocks_;
  std::array<double*, 3> hats_{};             // the transformed rows, in X during a solve
  std::vector<std::vector<double>> buffers_;  // solve_modes: one chunk buffer per thread
  std::vector<Eigen::MatrixXd> partial_;      // solve_modes: one product with the dots per chunk
  Eigen::MatrixXd near_values_;               // rows × (6 · count), see add_boundary_response
};

}  // namespace

std::optional<C1FamilyWeights> c1_family_weights(const StencilOperator& op) {
  if (op.radius != 2 || op.weights.size() != 25) return std::nullopt;
  double scale = 0;
  for (double w : op.weights) scale = std::max(scale, std::abs(w));
  if (!(scale > 0)) return std::nullopt;
  C1FamilyWeights w;
  w.a = op.weight(2, 2);
  w.b = op.weight(2, 0) - 6 * w.a;
  const double tol = 1e-12 * scale;
  for (int di = -2; di <= 2; ++di)
    for (int dj = -2; dj <= 2; ++dj)
      if (std::abs(op.weight(di, dj) - (w.a * c_weight(di, dj) + w.b * t_weight(di, dj))) > tol) return std::nullopt;
  if (w.a < -tol || w.b < -tol) return std::nullopt;
  w.a = std::max(w.a, 0.0);
  w.b = std::max(w.b, 0.0);
  if (!(w.a + w.b > 0)) return std::nullopt;
  return w;
}

std::unique_ptr<LinearSolver> make_fast5_solver(const SolverOptions& options) {
  return std::make_unique<Fast5Solver>(options);
}

}  // namespace coons::solvers
