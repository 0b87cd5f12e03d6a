#include "fast5_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fast5_boundary_values.h"
#include "fast5_capacitance.h"
#include "fast5_low_modes.h"
#include "fast5_modes.h"
#include "fast5_near_columns.h"
#include "fast5_rows.h"
#include "fast5_twisted.h"
#include "row_form.h"
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
// B is read from its row forms (fast5_rows.h) when cols ≥ kMinEdgeCols (the columns 0, 1, cols−2,
// cols−1 distinct) and no column has more than rows/kFullRowShare full rows.
constexpr int kMinEdgeCols = 6;
constexpr int kFullRowShare = 4;
// The modes q < cols/kLowModeShare (rounded up to even) are solved in closed form
// (fast5_low_modes.h): from there on κ(M_q) ∝ (cols/q)⁴ is at most about 16⁴, so the banded
// solves' forward error is below the rounding the transforms leave anyway. (A fixed 64 modes
// made N = 127 and 255 a third slower for no accuracy.)
constexpr int kLowModeShare = 16;
// g is formed in closed form (fast5_boundary_values.h), without the first sweep, when B is read
// from its row forms and its full rows pair into at most this many key rows (mask data: 2).
constexpr std::size_t kMaxKeyRows = 4;

constexpr std::array<double, 5> kDelta4 = {1, -4, 6, -4, 1};
constexpr std::array<double, 5> kDelta2 = {0, 1, -2, 1, 0};
constexpr std::array<double, 5> kImpulse = {0, 0, 1, 0, 0};
// The capacitance solve stops at this residual relative to its right-hand side, below the rounding of
// the rest of the solve, so that no correction is needed for it (one product with Cap, the
// preconditioned solve and one correction, from N = 31 to 2047 on mask data; at 1e−13 CG let some
// columns stop a step early and the solve's residual was a third higher). A correction (rare, see
// do_solve) solves to the accuracy it needs (to bring the boundary residual to a tenth of its
// limit), within [kCorrectionTolerance, 1e-2].
constexpr double kCapacitanceTolerance = 1e-14;
constexpr double kCorrectionTolerance = 1e-10;
constexpr int kCorrections = 3;  // at most this many boundary corrections per solve
// The boundary columns are corrected only while their residual is clearly above the rounding of
// the rest of the solve: above max(kBoundaryResidual, kRoundingFactor·max(rows, cols)·ε)·‖b‖
// (after the first solve it is 2.5–5.3·N·ε·‖b‖ on mask data from N = 255 to 1023, and a
// correction, which goes through two more row transforms, does not lower it), and above
// kReferenceFactor times the residual the other columns are estimated to have from the columns 2
// and cols−3 (A x − b there is rounding only; on random data, whose solutions are large, that
// rounding is the larger one, and a correction only adds to it).
constexpr double kBoundaryResidual = 1e-13;
constexpr double kRoundingFactor = 16;
constexpr double kReferenceFactor = 4;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

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
    twisted_ = fast5_detail::twisted_buffers(R_, C_, threads_, planning);
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    C1FamilyWeights w;
    if (!describe(op, summary, &w)) return SolveStatus::kNotApplicable;
    weights_ = w;
    for (int di = -2; di <= 2; ++di)
      for (int dj = -2; dj <= 2; ++dj)
        stencil_[std::size_t(di + 2) * 5 + std::size_t(dj + 2)] = w.a * c_weight(di, dj) + w.b * t_weight(di, dj);
    separable_ = !(w.b > 1e-12 * w.a);
    if (separable_) return SolveStatus::kSuccess;
    set_up();
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
    X.resize(B.rows(), 3);
    fast5_detail::prepare_near_columns(R_, C_, count, near_);
    for (int c = 0; c < count; ++c) hats_[std::size_t(c)] = X.col(c).data();
    // B's transform is read by the sweeps from its row form when it has few full rows (mask data:
    // four), otherwise X holds it (the hats) until the second sweep overwrites it with x̂
    edge_input_ = take_row_forms(B);
    if (edge_input_) {
      for (int c = 0; c < count; ++c) b_norms_[std::size_t(c)] = edge_rows_[std::size_t(c)].norm;
      transform_full_rows();
    } else {
      for (int c = 0; c < count; ++c) b_norms_[std::size_t(c)] = B.col(c).norm();
      transform_rows(count, true, B);
    }
    // g = the boundary columns of A₁⁻¹ b̂ (both parities), in closed form or by a sweep;
    // h = Cap⁻¹ g; x̂ = A₁⁻¹ (b̂ − U h).
    std::array<Eigen::MatrixXd, 2> h;
    int iterations = 0;
    if (edge_input_ && boundary_sources(count)) {
      std::array<Eigen::MatrixXd, 4> g;
      [[maybe_unused]] const int nt = threads_;
      COONS_PARALLEL_FOR
      for (int b = 0; b < 4; ++b)
        g[std::size_t(b)] =
            fast5_detail::boundary_values(blocks_[std::size_t(b)], b / 2, t_, near_sines_.col(0).data(),
                                          near_sines_.col(1).data(), keys_, R_, sources_[std::size_t(b % 2)]);
      iterations = solve_blocks(g, count, kCapacitanceTolerance, false, h);
    } else {
      banded_solve_all(count, dots_);
      iterations = capacitance_solve(dots_, count, kCapacitanceTolerance, h);
    }
    if (edge_input_ && twist_.rows > 0) {  // x̂ and its row transforms, into X
      fast5_detail::twisted_solve(factors_, twist_, low_, sweep_input(true, &h, -1.0), hats_, twisted_, along_i_,
                                  along_j_, threads_, [this](int c, int r, const double* row) {
                                    near_.keep(c, r, row);  // for the boundary check, while the row is in the cache
                                  });
    } else {
      add_boundary_response(count, h, -1.0, true);
      transform_rows(count, false, B);
    }
    // The columns 0 and cols−1 carry what rounding left in h (see the header): corrected from
    // their residual (in the sine basis again: S is its own inverse) while it is above its limit.
    std::array<Eigen::MatrixXd, 2> rho;
    for (int step = 0; step < kCorrections && boundary_residual(B, count, rho); ++step) {
      const double tolerance = std::clamp(0.1 / boundary_excess_, kCorrectionTolerance, 1e-2);
      iterations = std::max(iterations, capacitance_solve(rho, count, tolerance, h));
      transform_rows(count, false, B);
      add_boundary_response(count, h, 1.0, false);
      transform_rows(count, false, B);
    }
    summary.iterations = iterations;
    return SolveStatus::kSuccess;
  }

 private:
  // The one scan of B (rhs_scaling) gives each column's row form, its largest magnitude and its
  // norm; do_solve takes it over when it gets that B.
  ColumnExponents rhs_scaling(const Eigen::MatrixX3d& B) override {
    scanned_source_ = nullptr;
    if (separable_ || C_ < kMinEdgeCols) return LinearSolver::rhs_scaling(B);
    split_row_forms(B);
    ColumnExponents e{};
    for (std::size_t c = 0; c < 3; ++c) {
      e[c] = scaling_exponent(edge_rows_[c].largest);
      // a column near overflow is also checked for entries that scaling it down would lose
      if (e[c] > 0) return LinearSolver::rhs_scaling(B);
    }
    scanned_source_ = B.data();
    return e;
  }

  void split_row_forms(const Eigen::MatrixX3d& B) {
    for (int c = 0; c < 3; ++c)
      edge_rows_[std::size_t(c)] = fast5_detail::split_edge_rows(B.col(c).data(), R_, C_, threads_, R_ / kFullRowShare);
  }

  // true when the sweeps are to read B from its row forms (edge_rows_, from rhs_scaling's scan of
  // this B or a new one): every column with at most rows/kFullRowShare full rows.
  bool take_row_forms(const Eigen::MatrixX3d& B) {
    if (C_ < kMinEdgeCols) return false;
    if (scanned_source_ != B.data()) split_row_forms(B);
    scanned_source_ = nullptr;
    return std::none_of(edge_rows_.begin(), edge_rows_.end(),
                        [](const fast5_detail::EdgeRows& f) { return f.too_many; });
  }

  // The sine transform of the full rows of edge_rows_, in place (shared among the threads).
  void transform_full_rows() {
    std::vector<std::pair<int, int>> units;  // (column of B, full row)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < edge_rows_[std::size_t(c)].full_rows(); ++k) units.emplace_back(c, k);
    const double scale_j = std::sqrt(2.0 / (C_ + 1));
    [[maybe_unused]] const int nt = threads_;
#if defined(_OPENMP)
#pragma omp parallel num_threads(nt) if (nt > 1 && units.size() > 1)
#endif
    {
      detail::SineTransform& along_j = along_j_[std::size_t(thread_index())];
#if defined(_OPENMP)
#pragma omp for schedule(static)
#endif
      for (std::size_t u = 0; u < units.size(); ++u) {
        double* row = edge_rows_[std::size_t(units[u].first)].values.data() + std::ptrdiff_t(units[u].second) * C_;
        along_j.apply(row, row, scale_j);
      }
    }
  }

  // forward: hats_[c] (X's column c) = the sine transform of each row of B's column c; a row that is
  // zero but on the columns 0, 1, cols−2, cols−1 (most rows of a mask system: the data rings are
  // next to them) is the combination of those four columns' sine vectors instead (exact, no
  // transform). Otherwise X's column c = the inverse transform of each of its rows, in place. Rows
  // shared among the threads, one transform each (a SineTransform is not thread-safe).
  void transform_rows(int count, bool forward, const Eigen::MatrixX3d& B) {
    const double scale_j = std::sqrt(2.0 / (C_ + 1));
    const bool edges = forward && C_ >= kMinEdgeCols;
    [[maybe_unused]] const int nt = threads_;
#if defined(_OPENMP)
#pragma omp parallel num_threads(nt) if (nt > 1)
#endif
    {
      detail::SineTransform& along_j = along_j_[std::size_t(thread_index())];
#if defined(_OPENMP)
// (dynamic: the threads of a shared machine do not run at the same speed, and a static split
// waits for the slower one; each row is transformed alone, so the bits do not depend on it)
#pragma omp for schedule(dynamic, 16)
#endif
      for (int unit = 0; unit < count * R_; ++unit) {
        const int c = unit / R_, r = unit % R_;
        double* hat = hats_[std::size_t(c)] + std::ptrdiff_t(r) * C_;
        if (!forward) {
          if (r + 1 < R_)  // the next row, which its transform reads and writes (mostly this thread's)
            for (int k = 0; k < C_; k += 8) __builtin_prefetch(hat + C_ + k, 1);
          along_j.apply(hat, hat, scale_j);
          near_.keep(c, r, hat);  // for the boundary check, while the row is in the cache
          continue;
        }
        const double* b = B.col(c).data() + std::ptrdiff_t(r) * C_;
        if (edges && !detail::has_interior(b + 1, C_ - 2)) {  // zero off the columns 0, 1, cols−2, cols−1
          fast5_detail::edge_row_transform({b[0], b[1], b[C_ - 2], b[C_ - 1]}, near_sines_.col(0).data(),
                                           near_sines_.col(1).data(), 0, C_, hat);
        } else {
          along_j.apply(b, hat, scale_j);
        }
      }
    }
  }

  // The data-independent set-up: the banded LDLᵀ of M_q = (aν_q² + b)·P_i + 2bν_q·D_i + bν_q²·I
  // for every mode q along j, the four capacitance blocks (parity of q) × (parity of p), see the
  // header, the closed form of the lowest modes, and the sine vectors of the grid columns next to
  // the boundary. The six parts are independent and share the threads as units (longest first:
  // each part on one thread; split into their own loops, the factors and the lowest modes scaled
  // worse on two threads than the units do together).
  void set_up() {
    const double a = weights_.a, b = weights_.b;
    nu_ = second_difference_eigenvalues(C_);
    const Eigen::VectorXd mu = second_difference_eigenvalues(R_);
    t_ = std::sqrt(2.0) * first_sine_column(C_);
    tmasks_.setZero(C_, 2);  // t_q on the modes of each parity
    for (int q = 0; q < C_; ++q) tmasks_(q, q % 2) = t_[q];
    near_sines_.resize(C_, 2);  // columns 0, 1 (those of cols−1, cols−2 times (−1)^q)
    no_sines_.resize(C_, 0);
    for (int j = 0; j < 2; ++j)
      for (int q = 0; q < C_; ++q)
        near_sines_(q, j) = std::sqrt(2.0 / (C_ + 1)) * std::sin(M_PI * (j + 1) * (q + 1) / (C_ + 1));
    const fast5_detail::BlockInputs inputs = fast5_detail::block_inputs(a, b, mu, nu_, t_);
    const int low = low_mode_count();
    [[maybe_unused]] const int nt = threads_;
    COONS_PARALLEL_FOR
    for (int unit = 0; unit < 6; ++unit) {  // each unit writes its own member
      if (unit < 4)
        blocks_[std::size_t(unit)] = fast5_detail::capacitance_block(inputs, unit);
      else if (unit == 4)
        set_up_factors(a, b, low);
      else
        low_ = fast5_detail::low_modes(a, b, mu, nu_, low, 1);
    }
  }

  // The per-mode factors, and the middle of the twisted sweep from them (fast5_twisted.h; on mask
  // data, from kMinTwistRows rows on).
  void set_up_factors(double a, double b, int low) {
    factors_ = fast5_detail::factor_modes(a, b, nu_, R_, 1, low);
    twist_ =
        R_ >= fast5_detail::kMinTwistRows ? fast5_detail::twist_factors(factors_, low) : fast5_detail::TwistFactors{};
  }

  // The number of modes solved in closed form (kLowModeShare), even: the chunks after them start
  // on an even mode.
  [[nodiscard]] int low_mode_count() const {
    const int low = (C_ + kLowModeShare - 1) / kLowModeShare;
    return std::min(low + low % 2, C_ - C_ % 2);
  }

  // M⁻¹ of the input (see SweepInput) for every mode, into `output`, and out(r, 2k·c + 2m + p) = the
  // sum over the modes q of parity p of row r of the new values times sines(q, m), k = #sines. The
  // modes go in chunks of kModeChunk, each swept down and up in a per-thread buffer that stays in
  // the cache; the chunks' partial sums are added in their order (so the same on any number of
  // threads).
  void solve_modes(int count, const fast5_detail::SweepInput& in, const fast5_detail::ChunkOutput& output,
                   const Eigen::MatrixXd& sines, Eigen::MatrixXd& out) {
    const int low = low_.modes;
    const int chunks = (C_ - low + kModeChunk - 1) / kModeChunk;
    partial_.resize(std::size_t(chunks) + 1);
    buffers_.resize(std::size_t(threads_));
    [[maybe_unused]] const int nt = threads_;
    // Unit 0 is the closed form of the lowest modes. On threads, the chunks are taken in the order
    // 0, h, 1, h + 1, ... (h = half the chunks): the chunks that run at the same time are not
    // neighbours, whose rows in X share a cache line at their border.
    const int half = (chunks + 1) / 2;
    COONS_PARALLEL_FOR
    for (int i = 0; i <= chunks; ++i) {
      if (i == 0) {
        fast5_detail::solve_low_modes(low_, along_i_, count, in, output, sines, partial_[0]);
        continue;
      }
      const int j = i - 1, k = nt == 1 ? j : j % 2 == 0 ? j / 2 : half + j / 2;
      detail::AlignedBuffer& buf = buffers_[std::size_t(thread_index())];
      const int b0 = low + k * kModeChunk, b1 = std::min(C_, b0 + kModeChunk);
      const std::size_t size = 3 * std::size_t(R_) * std::size_t(b1 - b0);
      if (buf.size() < size) buf = detail::AlignedBuffer(size);  // not initialised: every entry is written first
      fast5_detail::solve_chunk(factors_, b0, b1, count, in, output, buf.data(), sines, partial_[std::size_t(k) + 1]);
    }
    out = partial_[0];
    for (std::size_t k = 1; k < partial_.size(); ++k) out += partial_[k];
  }

  // The input sign·U z_c (or none) plus the hats (with from_hats).
  [[nodiscard]] fast5_detail::SweepInput sweep_input(bool from_hats, const std::array<Eigen::MatrixXd, 2>* z,
                                                     double sign) const {
    fast5_detail::SweepInput in;
    if (from_hats && edge_input_) {
      in.edges = {&edge_rows_[0], &edge_rows_[1], &edge_rows_[2]};
      in.s0 = near_sines_.col(0).data();
      in.s1 = near_sines_.col(1).data();
    } else if (from_hats) {
      in.hats = {hats_[0], hats_[1], hats_[2]};
    }
    in.z = z;
    in.sign = sign;
    in.t_even = tmasks_.col(0).data();
    in.t_odd = tmasks_.col(1).data();
    in.t = t_.data();
    return in;
  }

  // g(r, 2c + parity) = Σ_q (M⁻¹ hat_c)(r, q)·t_q over the modes q of that parity (hats_ kept).
  void banded_solve_all(int count, Eigen::MatrixXd& g) { solve_modes(count, sweep_input(true, nullptr, 0), {}, t_, g); }

  // With replace: hats_[c] ← M⁻¹(hats_[c] + sign·U z_c); otherwise hats_[c] += sign·M⁻¹ U z_c.
  void add_boundary_response(int count, const std::array<Eigen::MatrixXd, 2>& z, double sign, bool replace) {
    fast5_detail::ChunkOutput output;
    output.grid = {hats_[0], hats_[1], hats_[2]};
    output.add = !replace;
    solve_modes(count, sweep_input(replace, &z, sign), output, no_sines_, unused_dots_);
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
    std::array<Eigen::MatrixXd, 2> hat;
    Eigen::VectorXd column(R_);
    for (std::size_t qpar = 0; qpar < 2; ++qpar) {
      hat[qpar].resize(R_, count);
      for (int c = 0; c < count; ++c) {
        column = rhs[qpar].col(c);
        along_i_.apply(column.data(), hat[qpar].col(c).data(), scale_i);
      }
    }
    std::array<Eigen::MatrixXd, 4> block_rhs;
    for (std::size_t b = 0; b < 4; ++b) {
      const CapacitanceBlock& blk = blocks_[b];
      block_rhs[b].resize(Eigen::Index(blk.modes.size()), count);
      for (std::size_t k = 0; k < blk.modes.size(); ++k)
        block_rhs[b].row(Eigen::Index(k)) = hat[b / 2].row(blk.modes[k]);
    }
    return solve_blocks(block_rhs, count, tolerance, apply_h, out);
  }

  // The capacitance solve in the sine basis along i: block_rhs[2·qpar + ppar] holds the right-hand
  // sides on the block's modes (with apply_h, H⁻¹ of them); out[qpar] = Cap⁻¹ of them back in the
  // grid (rows × count). Returns the most products with Cap of a block (CapacitanceBlock::solve).
  int solve_blocks(std::array<Eigen::MatrixXd, 4>& block_rhs, int count, double tolerance, bool apply_h,
                   std::array<Eigen::MatrixXd, 2>& out) {
    const double scale_i = std::sqrt(2.0 / (R_ + 1));
    std::array<Eigen::MatrixXd, 2> solved;
    for (std::size_t qpar = 0; qpar < 2; ++qpar) solved[qpar].resize(R_, count);
    // the four blocks (parity of q) × (parity of p) are independent; each writes its own rows
    std::array<int, 4> iterations{};
    [[maybe_unused]] const int nt = threads_;
    COONS_PARALLEL_FOR
    for (int b = 0; b < 4; ++b) {
      const CapacitanceBlock& blk = blocks_[std::size_t(b)];
      const std::size_t qpar = std::size_t(b) / 2;
      Eigen::MatrixXd part;
      if (apply_h) blk.apply_h_inverse(block_rhs[std::size_t(b)]);
      iterations[std::size_t(b)] = blk.solve(block_rhs[std::size_t(b)], part, tolerance);
      for (std::size_t k = 0; k < blk.modes.size(); ++k) solved[qpar].row(blk.modes[k]) = part.row(Eigen::Index(k));
    }
    Eigen::VectorXd column(R_);
    for (std::size_t qpar = 0; qpar < 2; ++qpar) {
      out[qpar].resize(R_, count);
      for (int c = 0; c < count; ++c) {
        column = solved[qpar].col(c);
        along_i_.apply(column.data(), out[qpar].col(c).data(), scale_i);
      }
    }
    return *std::max_element(iterations.begin(), iterations.end());
  }

  // The right-hand sides in the form of fast5_boundary_values.h into sources_ (keys_), from
  // edge_rows_ (their full rows transformed); false when they have more than kMaxKeyRows key rows.
  bool boundary_sources(int count) {
    return fast5_detail::boundary_sources(edge_rows_.data(), count, along_i_, kMaxKeyRows, keys_, sources_);
  }

  // ρ = (b − A x) on the columns 0 and cols−1 in parity coordinates (rows × count each); false
  // when, for every right-hand side, its norm is within its limit: the larger of
  // max(kBoundaryResidual, kRoundingFactor·max(rows, cols)·ε)·‖b‖ and kReferenceFactor times the
  // residual of the other columns, estimated from the columns 2 and cols−3 (rounding only: A x − b
  // vanishes off the columns 0 and cols−1 for any h). boundary_excess_: the largest ratio of a
  // boundary residual to its limit.
  bool boundary_residual(const Eigen::MatrixX3d& B, int count, std::array<Eigen::MatrixXd, 2>& rho) {
    std::array<Eigen::MatrixXd, 2> side;  // the residual on column 0 and on column cols−1
    for (int s = 0; s < 2; ++s) side[std::size_t(s)].resize(R_, count);
    const bool reference = C_ >= 6;  // columns 2 and cols−3 distinct from and not next to 0 and cols−1
    boundary_excess_ = 0;
    // the columns 0, cols−1 and (reference) 2, cols−3 of every right-hand side, on the threads
    const std::vector<int> which = reference ? std::vector<int>{0, C_ - 1, 2, C_ - 3} : std::vector<int>{0, C_ - 1};
    fast5_detail::gather_b_columns(B, edge_input_ ? &edge_rows_ : nullptr, count, which, near_);
    std::array<Eigen::VectorXd, 12> columns;
    const int units = count * int(which.size());
    [[maybe_unused]] const int nt = threads_;
    COONS_PARALLEL_FOR
    for (int u = 0; u < units; ++u) {
      const int c = u % count, k = u / count;
      columns[std::size_t(u)] = fast5_detail::column_residual(near_, stencil_, which[std::size_t(k)], k, c);
    }
    const auto residual = [&](std::size_t k, int c) -> const Eigen::VectorXd& {
      return columns[k * std::size_t(count) + std::size_t(c)];
    };
    for (int c = 0; c < count; ++c) {
      side[0].col(c) = residual(0, c);
      side[1].col(c) = residual(1, c);
      const double boundary = side[0].col(c).squaredNorm() + (C_ > 1 ? side[1].col(c).squaredNorm() : 0.0);
      const double rounding = reference ? residual(2, c).squaredNorm() + residual(3, c).squaredNorm() : 0.0;
      // A zero column has a zero solution and no boundary residual; 0/0 would make the excess, and
      // with it every column's correction tolerance, NaN (and every correction a no-op).
      const double b_norm = b_norms_[std::size_t(c)];
      if (!(b_norm > 0)) continue;
      // the reference columns' residual as an estimate of that of all cols − 2 other columns
      const double others = std::sqrt(rounding * (C_ - 2) / 2.0);
      const double floor = std::max(kBoundaryResidual, kRoundingFactor * std::max(R_, C_) * kEpsilon);
      const double limit = std::max(floor * b_norm, kReferenceFactor * others);
      boundary_excess_ = std::max(boundary_excess_, std::sqrt(boundary) / limit);
    }
    if (!(boundary_excess_ > 1)) return false;
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
  double boundary_excess_ = 0;        // see boundary_residual
  std::array<double, 25> stencil_{};  // the weights of a·C + b·T, row-major (di, dj = −2..2)
  ModeFactors factors_;
  std::array<CapacitanceBlock, 4> blocks_;
  fast5_detail::LowModes low_;
  fast5_detail::TwistFactors twist_;  // rows 0: no twisted sweep (fast5_twisted.h)
  fast5_detail::TwistedBuffers twisted_;
  std::array<double*, 3> hats_{};                                     // the transformed rows, in X during a solve
  std::array<fast5_detail::EdgeRows, 3> edge_rows_;                   // B's columns row by row (fast5_rows.h)
  std::vector<int> keys_;                                             // boundary_sources: the key rows
  std::array<std::vector<fast5_detail::BoundarySource>, 2> sources_;  // per parity of p, per column of B
  const double* scanned_source_ = nullptr;      // the B whose row forms rhs_scaling left in edge_rows_
  bool edge_input_ = false;                     // this solve reads B's transform from edge_rows_
  std::vector<detail::AlignedBuffer> buffers_;  // solve_modes: one chunk buffer per thread
  std::vector<Eigen::MatrixXd> partial_;        // solve_modes: one product with the dots per chunk
  Eigen::MatrixXd no_sines_, unused_dots_;      // add_boundary_response: no dots wanted
  fast5_detail::NearColumns near_;  // boundary_residual: B and X near the boundary columns (fast5_near_columns.h)
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
