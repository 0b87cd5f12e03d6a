// fast: the structured solver of structured_solvers.h. Per factorisation it picks one of three
// paths: the Kronecker path (kronecker_solver.h) when c·d = e_i·e_j; otherwise a sine transform
// along j (sine_transform.h) and the batch of tridiagonal solves along i of every mode
// (mode_pivots.h), vectorised across the modes, on the first L columns, L + 1 a fast transform
// length, the other columns eliminated by their Schur complement when cols + 1 is not one
// (capacitance.h); and the dst solver where elimination without pivoting would be unsafe. Right-hand sides are read row
// by row (row_form.h): only full rows are transformed. This file holds the orchestration and the pipeline of the
// transform path, which SolverOptions::threads runs with OpenMP: the threads eliminate forward side by side, then one
// substitutes back and the others take the inverse transforms of the finished rows (pipeline()): bit for bit the
// one-thread result.
// Sizes: #interior by 3 in and out; O(L) work arrays, 3 blocks of K·L for the pipeline.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965).
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "capacitance.h"
#include "kronecker_solver.h"
#include "mode_pivots.h"
#include "row_form.h"
#include "row_kernels.h"
#include "sine_transform.h"
#include "structured_solvers.h"

namespace coons::solvers {
namespace {

using detail::AlignedBuffer;
using detail::Capacitance;
using detail::KroneckerSolve;
using detail::ModePivots;
using detail::RowForm;
using detail::SineTransform;

// ------------------------------------------------------------------------------------------------

class FastSolver : public detail::StructuredSolver {
 public:
  explicit FastSolver(const SolverOptions& options) : StructuredSolver(options) {}
  [[nodiscard]] std::string name() const override { return "fast"; }

 protected:
  // A sweep splits the basis right-hand sides by rows and sine-transforms them once (SweepForms),
  // and combines the forms per member. Its workers (one per thread) share those forms.
  void do_begin_sweep() override { sweep_forms_.reset(); }
  SolveStatus do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::MatrixX3d& X, SolveSummary& summary) override;
  std::unique_ptr<LinearSolver> make_sweep_worker(const std::vector<Eigen::MatrixX3d>& basis,
                                                  const LinearOperator& op) override {
    SolverOptions one = options_;
    one.threads = 1;
    auto worker = std::make_unique<FastSolver>(one);
    if (worker->analyze(op) != SolveStatus::kSuccess) return nullptr;
    if (!worker->fits(sweep_forms_.get(), basis)) sweep_forms_ = worker->make_sweep_forms(basis);
    worker->sweep_forms_ = sweep_forms_;
    return worker;
  }

  SolveStatus analyze_grid(SolveSummary& /*summary*/) override {
    interface_ = detail::interface_columns(C_);
    L_ = C_ - interface_;
    const std::size_t L = std::size_t(L_);
#if defined(_OPENMP)
    threads_ = std::max(1, std::min(resolved_threads(options_.threads), L_ / 64));
#else
    threads_ = 1;
#endif
    sines_.clear();
    rows_.clear();
    for (int t = 0; t < threads_; ++t) {
      sines_.emplace_back(L_, detail::fft_planning(options_));
      rows_.emplace_back(L);
    }
    if (interface_ > 0) capacitance_.prepare(R_, detail::fft_planning(options_));
    auto sine_column = [&](int j, std::vector<double>& v) {  // S·e_j, length L
      v.resize(L);
      for (int q = 0; q < L_; ++q) v[std::size_t(q)] = std::sin(M_PI * double(j + 1) * (q + 1) / (L_ + 1));
    };
    y_.resize(L);
    for (int q = 0; q < L_; ++q) y_[std::size_t(q)] = std::cos(M_PI * (q + 1) / (L_ + 1));
    sine_column(0, sine_e0_);
    if (L_ >= 2)
      sine_column(L_ - 1, sine_e1_);  // the last column of the transformed region
    else
      sine_e1_.assign(L, 0.0);  // a row of one value has no second end
    unit_e0_.assign(std::size_t(C_), 0.0);
    unit_e1_.assign(std::size_t(C_), 0.0);
    unit_e0_[0] = 1;
    if (C_ >= 2) unit_e1_[std::size_t(C_ - 1)] = 1;
    for (auto& w : running_) w = AlignedBuffer(L);
    // Blocks of the back substitution: 3·K rows of L doubles, to stay in the L2 cache.
    block_rows_ = std::max(2, std::min(R_, std::clamp(16384 / L_, 4, 32)));
    // (Each row of a block starts on a cache line: at L = 1023 the row kernels over unaligned rows
    // took 1.7 times as long, measured 2026-11-24.)
    block_stride_ = (L + 7) / 8 * 8;
    for (auto& b : block_) b = AlignedBuffer(std::size_t(block_rows_) * block_stride_);
    dst_.reset();
    return SolveStatus::kSuccess;
  }

  SolveStatus factorize_grid(const LinearOperator& op, const GridStencil& s, SolveSummary& summary) override {
    if (KroneckerSolve::applies(s) && kronecker_.factor(s)) {
      path_ = Path::kKronecker;
      return SolveStatus::kSuccess;
    }
    if (modes_.factor(s, y_) && (interface_ == 0 || capacitance_.factor(s, y_))) {
      path_ = Path::kTransform;
      return SolveStatus::kSuccess;
    }
    // Elimination without pivoting is unsafe for some mode: the 2-D transform has no pivots.
    path_ = Path::kDst;
    if (!dst_) {
      SolverOptions inner = options_;
      inner.compute_residual = false;
      dst_ = make_dst_solver(inner);
    }
    const SolveStatus status = dst_->factorize(op);
    if (status != SolveStatus::kSuccess) summary.message = dst_->summary().message;
    return status;
  }

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override {
    summary.iterations = 1;
    if (path_ == Path::kDst) {
      const SolveSummary inner = dst_->solve(B, X);
      summary.message = inner.message;
      return inner.status;
    }
    X.resize(B.rows(), 3);
    Scan scanned = scanned_.source == B.data() ? std::move(scanned_) : scan(B);
    scanned_ = Scan{};  // (not kept: a scan of a B that was scaled first would hold its full rows)
    if (path_ == Path::kKronecker) {
      for (int c = 0; c < 3; ++c) kronecker_.solve(scanned.forms[std::size_t(c)], B.col(c).data(), X.col(c).data());
    } else {
      for (auto& f : scanned.forms) transform_rows(f);
      solve_transform(std::move(scanned.forms), scanned.interface, X);
    }
    return SolveStatus::kSuccess;
  }

  // The transform and Kronecker paths read every value of B in their scan (scan()): the largest
  // magnitude of each column comes from that pass, which do_solve() then takes over, instead of a
  // pass of its own before it.
  ColumnExponents rhs_scaling(const Eigen::MatrixX3d& B) override {
    scanned_.source = nullptr;
    if (path_ == Path::kDst) return LinearSolver::rhs_scaling(B);
    scanned_ = scan(B);
    ColumnExponents e{};
    for (std::size_t c = 0; c < 3; ++c) {
      e[c] = scaling_exponent(detail::larger_magnitude(
          detail::largest_magnitude(scanned_.forms[c]),
          detail::largest_magnitude(scanned_.interface[c].data(), scanned_.interface[c].size())));
    }
    scanned_.source = B.data();
    return e;
  }

 private:
  enum class Path { kKronecker, kTransform, kDst };

  // A right-hand side split by rows (split_rows; on the transform path the first L columns, and
  // its interface columns apart), not yet transformed; source: the B it was read from.
  struct Scan {
    const double* source = nullptr;
    std::array<RowForm, 3> forms;
    std::array<std::vector<double>, 3> interface;
  };
  // With several threads each splits a band of rows (join_rows puts them together): two threads read
  // B, 24 MB at N = 1023, from memory or the L3 cache faster than one.
  [[nodiscard]] Scan scan(const Eigen::MatrixX3d& B) const {
    Scan s;
    const int width = path_ == Path::kKronecker ? C_ : L_;
    const int bands = threads_;
    std::array<std::vector<RowForm>, 3> pieces;
    for (auto& p : pieces) p.resize(std::size_t(bands));
    detail::for_each_row_band(R_, bands, [&](int p, int r0, int r1) {
      for (int c = 0; c < 3; ++c)
        pieces[std::size_t(c)][std::size_t(p)] =
            detail::split_rows(B.col(c).data() + std::size_t(r0) * std::size_t(C_), r1 - r0, width, C_);
    });
    for (std::size_t c = 0; c < 3; ++c) {
      s.forms[c] = bands == 1 ? std::move(pieces[c][0]) : detail::join_rows(pieces[c]);
      if (path_ == Path::kTransform) s.interface[c] = interface_part(B.col(Eigen::Index(c)).data());
    }
    return s;
  }
  Scan scanned_;  // the scan of rhs_scaling() for the do_solve() that follows
  // Dense rows of a form of width L → their sine transforms.
  void transform_rows(RowForm& f) {
    const std::size_t L = std::size_t(L_);
    for (std::size_t k = 0; k < f.dense_rows.size(); ++k) {
      double* row = f.values.data() + k * L;
      sines_[0].apply(row, row, 1.0);
    }
  }

  // The interface columns L..C−1 of one column of a right-hand side (rows × k, row-major).
  [[nodiscard]] std::vector<double> interface_part(const double* b) const {
    const std::size_t k = std::size_t(interface_), C = std::size_t(C_);
    std::vector<double> part(std::size_t(R_) * k);
    for (std::size_t i = 0; i < std::size_t(R_); ++i)
      std::copy(b + i * C + std::size_t(L_), b + (i + 1) * C, part.begin() + std::ptrdiff_t(i * k));
    return part;
  }

  // For every mode q: X̂(:,q) = T_q⁻¹ B̂(:,q), three columns at once, each X̂ row handed to finish(t, i, c, x̂) (t: the
  // calling thread). Every loop runs over whole rows, vectorised across the modes. The forward elimination keeps only
  // the last row of each block of K rows (in rows[c] + i·stride: X itself) and recomputes a block in cache before
  // substituting back through it: two passes over memory fewer for a little more arithmetic. One thread hands each row
  // to finish as soon as its block is done (so that the inverse transform runs while the row is in cache).
  // Several threads: they first run the forward elimination side by side, each on its own range of modes (one thread
  // did it alone before, 0.9 of the 7 ms of a solve at N = 1023, the others waiting; side by side 0.7 ms). Then one
  // (the producer) substitutes back through every mode and publishes each finished row of x̂ (copied to rows, in the
  // order the blocks finish); the others finish published rows as they come, and the producer joins them when it is
  // done. While a block's worth of published rows per other thread waits, the producer finishes its new rows itself,
  // from cache. The back substitution costs about half what the transforms do, so at N = 1023 on 2 threads the
  // producer finished about a third of the rows. Measured 2026-11-24 with scratch drivers, 2 threads, N = 1023: this
  // pipeline 6.3–6.5 ms per solve; the modes split for the back substitution too, the threads in lock step with a
  // barrier per block, 7.1 ms; rows published through a ring buffer instead of X, 6.7 ms and some solves 14 ms; the
  // threads splitting the modes and meeting at a barrier before all the transforms, 8.4–9.5 ms. Each mode is
  // eliminated as on one thread (elementwise across modes) and every row is finished alike whoever takes it: bit for
  // bit the one-thread result.
  template <class Finish>
  void pipeline(const std::array<RowForm, 3>& forms, const std::array<double*, 3>& rows, std::size_t stride,
                Finish&& finish) {
    const int T = threads_;
    if (T == 1) {
      eliminate_forward(forms, rows, stride, 0, L_);
      substitute_back(forms, rows, stride, [&](int i, int c, const double* xh) { finish(0, i, c, xh); });
      detail::stream_fence();  // the non-temporal stores of finish, as on the threaded path
      return;
    }
    const int units = 3 * R_;
    const int backlog = 3 * block_rows_ * (T - 1);            // published rows not yet claimed, at most
    std::vector<int> order(static_cast<std::size_t>(units));  // published unit u: row order[u] / 3, column % 3
    std::atomic<int> published{0}, claimed{0};
    std::atomic<bool> produced{false};  // every unit eliminated: published is final
#if defined(_OPENMP)
#pragma omp parallel num_threads(T)
#endif
    {
      const int t = thread_index();
      const int team = team_size();
      // Mode ranges cut at multiples of 8 (whole cache lines of every row).
      auto cut = [&](int k) { return k == team ? L_ : (L_ * k / team) / 8 * 8; };
      eliminate_forward(forms, rows, stride, cut(t), cut(t + 1));
#if defined(_OPENMP)
#pragma omp barrier
#endif
      if (t == 0) {
        int next = 0;
        substitute_back(forms, rows, stride, [&](int i, int c, const double* xh) {
          if (next - claimed.load(std::memory_order_relaxed) >= backlog) {
            finish(0, i, c, xh);  // the others have enough to do: this row, still in cache, here
            return;
          }
          std::copy(xh, xh + L_, rows[std::size_t(c)] + std::size_t(i) * stride);
          order[std::size_t(next)] = 3 * i + c;
          published.store(++next, std::memory_order_release);
        });
        produced.store(true, std::memory_order_release);
      }
      for (int u = claimed.fetch_add(1);; u = claimed.fetch_add(1)) {
        bool ready = published.load(std::memory_order_acquire) > u;
        while (!ready) {
          const bool last = produced.load(std::memory_order_acquire);
          ready = published.load(std::memory_order_acquire) > u;
          if (ready || last) break;
          std::this_thread::yield();
        }
        if (!ready) break;  // every published unit is claimed
        const int i = order[std::size_t(u)] / 3, c = order[std::size_t(u)] % 3;
        finish(t, i, c, static_cast<const double*>(rows[std::size_t(c)] + std::size_t(i) * stride));
      }
      detail::stream_fence();
    }
  }

  // Row i of the forward elimination of all three columns in the modes [q0, q0 + n):
  // y_i = B̂_i − l_i ∘ y_{i−1}, l_i = o ∘ r_{i−1} (previous(c), target(c): rows of all L modes;
  // previous nullptr at i = 0). One pass over s, t and l when every column's row is sparse (rows
  // of mask data but two), else column by column.
  template <class Previous, class Target>
  void eliminate_row(const std::array<RowForm, 3>& forms, int i, int q0, int n, Previous&& previous,
                     Target&& target) const {
    const std::size_t k = std::size_t(i), L = std::size_t(L_), q = std::size_t(q0);
    const double* l = modes_.multipliers() + q;
    const double* e0 = sine_e0_.data() + q;
    const double* e1 = sine_e1_.data() + q;
    auto at = [&](auto* row) { return row ? row + q : row; };
    if (forms[0].slot[k] < 0 && forms[1].slot[k] < 0 && forms[2].slot[k] < 0) {
      const std::array<double, 3> a{forms[0].first[k], forms[1].first[k], forms[2].first[k]};
      const std::array<double, 3> e{forms[0].last[k], forms[1].last[k], forms[2].last[k]};
      const std::array<double*, 3> x{at(target(0)), at(target(1)), at(target(2))};
      const std::array<const double*, 3> p{at(previous(0)), at(previous(1)), at(previous(2))};
      detail::eliminate_sparse3(a.data(), e.data(), e0, e1, l, i > 0 ? p.data() : nullptr, x.data(), n);
      return;
    }
    for (int c = 0; c < 3; ++c) {
      const RowForm& f = forms[std::size_t(c)];
      const int slot = f.slot[k];
      if (slot >= 0)
        detail::eliminate_dense(f.values.data() + std::size_t(slot) * L + q, l, at(previous(c)), at(target(c)), n);
      else
        detail::eliminate_sparse(f.first[k], f.last[k], e0, e1, l, at(previous(c)), at(target(c)), n);
    }
  }

  // The forward elimination of the modes [q0, q1) through every row. It keeps only the last row of
  // each block of K rows (in rows[c] + i·stride: X itself) and the rows of the last block (in
  // block_), for substitute_back. Threads with disjoint mode ranges run it side by side: each loads
  // its own modes of the pivot rows they share (ModePivots::load), and at the end every mode holds
  // row R − 2.
  void eliminate_forward(const std::array<RowForm, 3>& forms, const std::array<double*, 3>& rows, std::size_t stride,
                         int q0, int q1) {
    const int K = block_rows_;
    for (int i = 0; i < R_; ++i) {
      if (i > 0) modes_.load(i >= 2 ? i - 2 : -1, i - 1, q0, q1);
      const int s = i % K;
      eliminate_row(
          forms, i, q0, q1 - q0, [&](int c) { return i > 0 ? slot_row(c, (s + K - 1) % K) : nullptr; },
          [&](int c) { return slot_row(c, s); });
      if (s == K - 1 && i + 1 < R_)
        for (int c = 0; c < 3; ++c)
          std::copy(slot_row(c, s) + q0, slot_row(c, s) + q1, rows[std::size_t(c)] + std::size_t(i) * stride + q0);
    }
  }

  // After eliminate_forward of every mode: the back substitution x̂_i = (y_i − o ∘ x̂_{i+1}) ∘ r_i,
  // block by block from the last one (whose rows are still in the buffer; the others are
  // eliminated again from their saved predecessor, in cache), handing each row of x̂ to
  // done(i, c, x̂) when its block is done; running_ holds x̂ of the block below.
  template <class Done>
  void substitute_back(const std::array<RowForm, 3>& forms, const std::array<double*, 3>& rows, std::size_t stride,
                       Done&& done) {
    const int n = L_;
    const int K = block_rows_;
    const int last_block = (R_ - 1) / K;
    const double* o = modes_.off();
    const double* r = modes_.pivots();
    auto saved = [&](int c, int i) { return rows[std::size_t(c)] + std::size_t(i) * stride; };
    int at = R_ >= 2 ? R_ - 2 : -1;  // the row the pivot rows hold (eliminate_forward's last)
    auto pivots_for = [&](int i) {
      if (at != i) modes_.load(at, i);
      at = i;
    };
    for (auto& w : running_) std::fill(w.data(), w.data() + n, 0.0);
    for (int b = last_block; b >= 0; --b) {
      const int first = b * K, end = std::min(R_, first + K);
      if (b != last_block)
        for (int i = first; i < end; ++i) {
          if (i > 0) pivots_for(i - 1);
          eliminate_row(
              forms, i, 0, n,
              [&](int c) -> const double* {
                return i == 0 ? nullptr : i == first ? saved(c, i - 1) : slot_row(c, i - first - 1);
              },
              [&](int c) { return slot_row(c, i - first); });
        }
      for (int i = end - 1; i >= first; --i) {
        pivots_for(i);
        std::array<double*, 3> y{};
        std::array<const double*, 3> next{};
        for (int c = 0; c < 3; ++c) {
          y[std::size_t(c)] = slot_row(c, i - first);
          next[std::size_t(c)] = i + 1 < end ? slot_row(c, i + 1 - first) : running_[std::size_t(c)].data();
        }
        detail::back_substitute_in_place3(y.data(), o, r, next.data(), n);
      }
      for (int c = 0; c < 3; ++c) std::copy(slot_row(c, 0), slot_row(c, 0) + n, running_[std::size_t(c)].data());
      for (int i = end - 1; i >= first; --i)
        for (int c = 0; c < 3; ++c) done(i, c, static_cast<const double*>(slot_row(c, i - first)));
    }
  }
  // Row s of the back-substitution buffer of column c (L values).
  [[nodiscard]] double* slot_row(int c, int s) {
    return block_[std::size_t(c)].data() + std::size_t(s) * block_stride_;
  }

  // X = (2/(L+1)) S X̂ on the first L columns. With an interface (L < C, capacitance.h): a first
  // pass that only records the fast region's column L−1 (V) with the interface at zero, the
  // interface values from V and the interface's right-hand side, and the pass that writes X with
  // the interface moved to the right-hand side of column L−1 (the `last` values of the forms,
  // and δ times S·e_{L−1} for their dense rows).
  void solve_transform(std::array<RowForm, 3> forms, const std::array<std::vector<double>, 3>& interface_rhs,
                       Eigen::MatrixX3d& X) {
    const std::size_t C = std::size_t(C_), L = std::size_t(L_);
    const double scale = 2.0 / (L_ + 1);
    const std::array<double*, 3> rows{X.col(0).data(), X.col(1).data(), X.col(2).data()};
    std::array<std::vector<double>, 3> x_interface;
    if (interface_ > 0) {
      std::array<std::vector<double>, 3> V;
      for (auto& v : V) v.assign(std::size_t(R_), 0.0);
      pipeline(forms, rows, C, [&](int /*t*/, int i, int c, const double* xh) {
        V[std::size_t(c)][std::size_t(i)] = scale * detail::dot(sine_e1_.data(), xh, L_);
      });
      std::vector<double> delta;
      for (std::size_t c = 0; c < 3; ++c) {
        capacitance_.interface_values(V[c], interface_rhs[c], x_interface[c]);
        capacitance_.coupling(x_interface[c], delta);
        RowForm& f = forms[c];
        for (std::size_t i = 0; i < std::size_t(R_); ++i) {
          const int slot = f.slot[i];
          if (slot < 0)
            f.last[i] -= delta[i];
          else
            detail::add_scaled(-delta[i], sine_e1_.data(), f.values.data() + std::size_t(slot) * L, L_);
        }
      }
    }
    pipeline(forms, rows, C, [&](int t, int i, int c, const double* xh) {
      double* row = rows_[std::size_t(t)].data();
      sines_[std::size_t(t)].apply(xh, row, scale);
      detail::stream_copy(row, X.col(c).data() + std::size_t(i) * C, L);
    });
    if (interface_ > 0) {
      const std::size_t k = std::size_t(interface_);
      for (std::size_t c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < std::size_t(R_); ++i)
          std::copy(x_interface[c].begin() + std::ptrdiff_t(i * k),
                    x_interface[c].begin() + std::ptrdiff_t((i + 1) * k), X.col(Eigen::Index(c)).data() + i * C + L);
    }
  }

  int L_ = 0, interface_ = 0, block_rows_ = 16;  // L_ = C_ − interface_: the transform length
  Path path_ = Path::kTransform;
  // The threads of a solve (SolverOptions::threads, at most one per 64 modes; see pipeline()).
  int threads_ = 1;
  std::vector<SineTransform> sines_;  // one per thread (a transform has scratch)
  std::vector<AlignedBuffer> rows_;   // one row of L per thread
  std::vector<double> y_, sine_e0_, sine_e1_, unit_e0_, unit_e1_;
  ModePivots modes_;          // the transform path's tridiagonal systems, one per mode
  Capacitance capacitance_;   // the interface columns (when L < C)
  KroneckerSolve kronecker_;  // the Kronecker path
  std::array<AlignedBuffer, 3> running_, block_;
  std::size_t block_stride_ = 0;  // of the rows of block_: L rounded up to whole cache lines
  std::unique_ptr<LinearSolver> dst_;

  // Every right-hand side of a sweep's basis split by rows (physical: the Kronecker path) and, on
  // the first L columns, with its dense rows sine-transformed (transformed: the transform path),
  // for an R × C grid, and its interface columns (interface_part).
  struct SweepForms {
    int rows = 0, cols = 0;
    std::vector<std::array<RowForm, 3>> physical, transformed;
    std::vector<std::array<std::vector<double>, 3>> interface;
  };
  [[nodiscard]] bool fits(const SweepForms* forms, const std::vector<Eigen::MatrixX3d>& basis) const {
    return forms && forms->rows == R_ && forms->cols == C_ && forms->physical.size() == basis.size();
  }
  std::shared_ptr<const SweepForms> make_sweep_forms(const std::vector<Eigen::MatrixX3d>& basis) {
    auto forms = std::make_shared<SweepForms>();
    forms->rows = R_;
    forms->cols = C_;
    forms->physical.resize(basis.size());
    forms->transformed.resize(basis.size());
    forms->interface.resize(basis.size());
    for (std::size_t r = 0; r < basis.size(); ++r)
      for (std::size_t c = 0; c < 3; ++c) {
        const double* b = basis[r].col(Eigen::Index(c)).data();
        forms->physical[r][c] = detail::split_rows(b, R_, C_);
        forms->transformed[r][c] = detail::split_rows(b, R_, L_, C_);
        transform_rows(forms->transformed[r][c]);
        forms->interface[r][c] = interface_part(b);
      }
    return forms;
  }
  std::shared_ptr<const SweepForms> sweep_forms_;  // read-only once made: a sweep's workers share it
};

SolveStatus FastSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& w,
                                       Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::Index n = Eigen::Index(R_) * C_;
  const std::size_t used = w.size();
  summary.iterations = 1;
  X.resize(n, 3);
  if (path_ == Path::kDst) {
    const SolveSummary inner = dst_->solve(combine_rhs(basis, w, n), X);
    summary.message = inner.message;
    return inner.status;
  }
  if (!fits(sweep_forms_.get(), basis)) sweep_forms_ = make_sweep_forms(basis);
  const bool kron = path_ == Path::kKronecker;
  const auto& forms_of_basis = kron ? sweep_forms_->physical : sweep_forms_->transformed;
  std::array<RowForm, 3> forms;
  for (int c = 0; c < 3; ++c) {
    std::vector<const RowForm*> parts;
    for (std::size_t r = 0; r < used; ++r) parts.push_back(&forms_of_basis[r][std::size_t(c)]);
    forms[std::size_t(c)] =
        kron ? detail::combine(parts, w, R_, unit_e0_, unit_e1_) : detail::combine(parts, w, R_, sine_e0_, sine_e1_);
  }
  if (!kron) {
    std::array<std::vector<double>, 3> interface_rhs;
    for (std::size_t c = 0; c < 3; ++c) {
      interface_rhs[c].assign(std::size_t(R_) * std::size_t(interface_), 0.0);
      for (std::size_t r = 0; r < used; ++r)
        if (w[r] != 0)
          for (std::size_t k = 0; k < interface_rhs[c].size(); ++k)
            interface_rhs[c][k] += w[r] * sweep_forms_->interface[r][c][k];
    }
    solve_transform(std::move(forms), interface_rhs, X);
    return SolveStatus::kSuccess;
  }
  Eigen::MatrixX3d B;  // formed only for a column with too many full rows for the rank form
  for (int c = 0; c < 3; ++c) {
    if (int(forms[std::size_t(c)].dense_rows.size()) > KroneckerSolve::kMaxRank && B.rows() == 0)
      B = combine_rhs(basis, w, n);
    kronecker_.solve(forms[std::size_t(c)], B.col(c).data(), X.col(c).data());
  }
  return SolveStatus::kSuccess;
}

}  // namespace

std::unique_ptr<LinearSolver> make_fast_solver(const SolverOptions& options) {
  return std::make_unique<FastSolver>(options);
}

}  // namespace coons::solvers
