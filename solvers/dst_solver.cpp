// dst: X = S_R (B̂ ./ λ) S_C · 4/((rows+1)(cols+1)), B̂ = S_R B S_C, where S_n is the DST-I of
// length n (sine_transform.h, on a real FFT) and λ(p, q) the stencil's eigenvalues. The 2-D
// transforms are done by rows (length cols) and by strips of 16 columns (length rows), whose
// division by λ (computed on the fly: no table of the grid's size) and both column transforms run
// in cache. A right-hand side next to the frame only (every mask system) has a closed-form B̂ from
// the 1-D transforms of its four sides, so it needs no forward transform at all.
// Threads (SolverOptions::threads, OpenMP): the rows and the strips are shared out between them
// in small chunks, dynamically (on a busy machine a running thread takes a descheduled one's
// share); each row and strip is computed alike whoever takes it, so results agree bit for bit.
// Sizes: #interior by 3 in and out (X holds the intermediate grids); per thread 3 strip buffers
// of 16·rows and one inverse column; a sweep keeps the transformed basis, #basis·3 grids.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965); eigenvalues from G. Farin & D. Hansford, Discrete Coons patches, CAGD 16 (1999).
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "row_form.h"
#include "sine_transform.h"
#include "structured_solvers.h"
#include "vector_clones.h"

namespace coons::solvers {
namespace {

using detail::AlignedBuffer;
using detail::SineTransform;

constexpr int kStrip = 16;          // columns per strip: two cache lines of a row
constexpr std::size_t kAhead = 16;  // rows to prefetch ahead in a strip

// The transforms of a right-hand side next to the frame: B̂(p, q) = σ_p t̂_q + σ'_p b̂_q + τ_q l̂_p
// + τ'_q r̂_p, with t̂, b̂ the transforms of the first and last rows, l̂, r̂ those of the first and
// last columns without their corners, σ = S e_0, σ' = S e_{rows−1} (σ with signs (−1)^p), τ, τ'
// the same along the rows.
struct RingSides {
  std::vector<double> top, bottom, left, right;
};

// out = σ·t + σ'·b + l·tau + r·tau' over p (one column q of B̂ of a ring right-hand side).
COONS_VECTOR_CLONES void ring_column(double t, double b, double tau, double tau_signed, const double* __restrict sigma,
                                     const double* __restrict sigma_signed, const double* __restrict l,
                                     const double* __restrict r, double* __restrict out, int n) {
  for (int p = 0; p < n; ++p) out[p] = t * sigma[p] + b * sigma_signed[p] + tau * l[p] + tau_signed * r[p];
}

// inv = norm / (a + b·y) (the scaled inverse eigenvalues of one column of modes).
COONS_VECTOR_CLONES void inverse_column(double norm, double y, const double* __restrict a, const double* __restrict b,
                                        double* __restrict inv, int n) {
  for (int p = 0; p < n; ++p) inv[p] = norm / (a[p] + b[p] * y);
}

// x = x ∘ v.
COONS_VECTOR_CLONES void scale_by(double* __restrict x, const double* __restrict v, int n) {
  for (int p = 0; p < n; ++p) x[p] *= v[p];
}

// x = Σ_k w_k v_k.
COONS_VECTOR_CLONES void combine_column(const std::vector<std::pair<double, const double*>>& terms,
                                        double* __restrict x, int n) {
  std::fill(x, x + n, 0.0);
  for (const auto& [w, v] : terms) {
    const double* __restrict column = v;
    for (int p = 0; p < n; ++p) x[p] += w * column[p];
  }
}

class DstSolver : public detail::StructuredSolver {
 public:
  explicit DstSolver(const SolverOptions& options) : StructuredSolver(options) {}
  [[nodiscard]] std::string name() const override { return "dst"; }

 protected:
  // A sweep transforms each basis right-hand side once (hat_[r][c]: B̂ by columns, cols × rows)
  // and combines the transforms per member.
  void do_begin_sweep() override { hat_.clear(); }
  SolveStatus do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::MatrixX3d& X, SolveSummary& summary) override;

  SolveStatus analyze_grid(SolveSummary& summary) override;
  SolveStatus factorize_grid(const LinearOperator& op, const GridStencil& s, SolveSummary& summary) override;
  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) override;
  // One pass over B (on `threads_` threads, by bands of rows) for both what the common solve path
  // asks, the largest magnitude of each column, and what do_solve() on this B needs, whether each
  // column lies on the ring (on_ring): the ring test reads each row again while it is in the L1
  // cache. Before, each was a pass of its own over the 24 MB of B at N = 1023.
  ColumnExponents rhs_scaling(const Eigen::MatrixX3d& B) override;

 private:
  static constexpr double kSingularEigenvalue = 1e-13;

  // Where column q of B̂ comes from: the closed form of a ring right-hand side; the row
  // transforms of B (row-major R×C, S_R still to apply); or a sum of columns of stored B̂.
  struct Spectrum {
    const RingSides* ring = nullptr;
    const double* rows = nullptr;
    std::vector<std::pair<double, const std::vector<double>*>> terms;
  };
  // Per thread: the transforms (they have scratch) and the buffers of a strip.
  struct Scratch {
    SineTransform along_rows, along_cols;  // lengths C and R
    std::array<AlignedBuffer, 3> strip;
    AlignedBuffer inv;
  };

  [[nodiscard]] bool on_ring(const double* b) const;
  void ring_sides(const double* b, RingSides& sides);
  // out = column q of B̂ (length R).
  void spectrum_column(const Spectrum& source, int q, Scratch& scratch, double* out) const;
  // X = S_R (B̂ ./ λ) S_C·norm, column by column, for the three sources; B̂ from `rows` sources
  // is read from X itself (the rows of B already transformed there).
  void invert(const std::array<Spectrum, 3>& sources, Eigen::MatrixX3d& X, const Eigen::MatrixX3d* forward_rows_of);

  int threads_ = 1;
  std::vector<Scratch> scratch_;
  std::vector<double> a_, b_, y_;             // λ(p, q) = a_p + b_p·y_q
  std::vector<double> sigma_, sigma_signed_;  // S e_0, S e_{R−1}
  std::vector<double> tau_, tau_signed_;      // S e_0, S e_{C−1} along the rows
  std::array<RingSides, 3> ring_;
  std::vector<std::vector<std::vector<double>>> hat_;  // a sweep's transformed basis
  // rhs_scaling's verdict on_ring for the B at `source` (nullptr: none), for the do_solve() that
  // follows (a B scaled by the common path is another array, tested anew).
  struct RingScan {
    const double* source = nullptr;
    std::array<bool, 3> ring{};
  };
  RingScan scanned_;
};

SolveStatus DstSolver::analyze_grid(SolveSummary& /*summary*/) {
#if defined(_OPENMP)
  threads_ = std::max(1, std::min(resolved_threads(options_.threads), std::max(R_, C_) / 32));
#else
  threads_ = 1;
#endif
  const unsigned planning = detail::fft_planning(options_);
  scratch_.clear();
  scratch_.resize(std::size_t(threads_));
  for (Scratch& s : scratch_) {
    s.along_rows = SineTransform(C_, planning);
    s.along_cols = SineTransform(R_, planning);
    for (AlignedBuffer& b : s.strip) b = AlignedBuffer(std::size_t(kStrip) * std::size_t(R_));
    s.inv = AlignedBuffer(std::size_t(R_));
  }
  const double* sr = scratch_[0].along_cols.first_column();
  const double* sc = scratch_[0].along_rows.first_column();
  sigma_.assign(sr, sr + R_);
  tau_.assign(sc, sc + C_);
  sigma_signed_ = sigma_;
  tau_signed_ = tau_;
  for (int p = 1; p < R_; p += 2) sigma_signed_[std::size_t(p)] = -sigma_[std::size_t(p)];
  for (int q = 1; q < C_; q += 2) tau_signed_[std::size_t(q)] = -tau_[std::size_t(q)];
  return SolveStatus::kSuccess;
}

SolveStatus DstSolver::factorize_grid(const LinearOperator& /*op*/, const GridStencil& s, SolveSummary& summary) {
  a_.resize(std::size_t(R_));
  b_.resize(std::size_t(R_));
  y_.resize(std::size_t(C_));
  for (int q = 0; q < C_; ++q) y_[std::size_t(q)] = std::cos(M_PI * (q + 1) / (C_ + 1));
  // λ(p, ·) is monotone in q (y_q decreases): |λ| is largest at an end and smallest at an end or
  // where λ changes sign.
  double smallest = HUGE_VAL, largest = 0;
  for (int p = 0; p < R_; ++p) {
    const double x = std::cos(M_PI * (p + 1) / (R_ + 1));
    const double a = s.center + 2 * s.edge_i * x, b = 2 * s.edge_j + 4 * s.diag * x;
    a_[std::size_t(p)] = a;
    b_[std::size_t(p)] = b;
    auto lambda = [&](int q) { return a + b * y_[std::size_t(q)]; };
    const double first = lambda(0), last = lambda(C_ - 1);
    largest = std::max({largest, std::abs(first), std::abs(last)});
    smallest = std::min({smallest, std::abs(first), std::abs(last)});
    if ((first > 0) != (last > 0)) {  // a sign change in (0, C−1]: find it by bisection
      int lo = 0, hi = C_ - 1;
      while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        ((lambda(mid) > 0) == (first > 0) ? lo : hi) = mid;
      }
      smallest = std::min({smallest, std::abs(lambda(lo)), std::abs(lambda(hi))});
    }
  }
  if (!(smallest > kSingularEigenvalue * largest)) {
    summary.message = "smallest |eigenvalue| " + format_g(smallest) + " of largest " + format_g(largest) +
                      ": the stencil is singular";
    return SolveStatus::kSingular;
  }
  return SolveStatus::kSuccess;
}

// True when only the ring next to the frame can be non-zero: rows 1..R−2 are zero at 1..C−2.
bool DstSolver::on_ring(const double* b) const {
  if (R_ < 3 || C_ < 3) return false;
  for (int i = 1; i + 1 < R_; ++i) {
    if (detail::has_interior(b + std::size_t(i) * std::size_t(C_), C_)) return false;
  }
  return true;
}

void DstSolver::ring_sides(const double* b, RingSides& sides) {
  Scratch& s = scratch_[0];
  const auto C = std::size_t(C_);
  sides.top.resize(C);
  sides.bottom.resize(C);
  sides.left.assign(std::size_t(R_), 0.0);
  sides.right.assign(std::size_t(R_), 0.0);
  s.along_rows.apply(b, sides.top.data());
  s.along_rows.apply(b + std::size_t(R_ - 1) * C, sides.bottom.data());
  for (int i = 1; i + 1 < R_; ++i) {
    sides.left[std::size_t(i)] = b[std::size_t(i) * C];
    sides.right[std::size_t(i)] = b[std::size_t(i) * C + C - 1];
  }
  s.along_cols.apply(sides.left.data(), sides.left.data());
  s.along_cols.apply(sides.right.data(), sides.right.data());
}

void DstSolver::spectrum_column(const Spectrum& source, int q, Scratch& scratch, double* out) const {
  const auto k = std::size_t(q);
  if (source.ring) {
    const RingSides& g = *source.ring;
    ring_column(g.top[k], g.bottom[k], tau_[k], tau_signed_[k], sigma_.data(), sigma_signed_.data(), g.left.data(),
                g.right.data(), out, R_);
  } else if (source.rows) {
    for (int p = 0; p < R_; ++p) out[p] = source.rows[std::size_t(p) * std::size_t(C_) + k];
    scratch.along_cols.apply(out, out);
  } else {
    std::vector<std::pair<double, const double*>> terms;
    terms.reserve(source.terms.size());
    for (const auto& [w, hat] : source.terms) terms.emplace_back(w, hat->data() + k * std::size_t(R_));
    combine_column(terms, out, R_);
  }
}

void DstSolver::invert(const std::array<Spectrum, 3>& sources, Eigen::MatrixX3d& X,
                       const Eigen::MatrixX3d* forward_rows_of) {
  const auto C = std::size_t(C_), R = std::size_t(R_);
  const double norm = 4.0 / ((R_ + 1.0) * (C_ + 1.0));
  const int strips = (C_ + kStrip - 1) / kStrip;
#if defined(_OPENMP)
#pragma omp parallel num_threads(threads_) if (threads_ > 1)
#endif
  {
    Scratch& scratch = scratch_[std::size_t(thread_index())];
    if (forward_rows_of) {  // X(:, c) = B(:, c) S_C row by row for the `rows` sources
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 32)
#endif
      for (int k = 0; k < 3 * R_; ++k) {
        const int c = k / R_;
        const std::size_t i = std::size_t(k % R_);
        if (sources[std::size_t(c)].rows)
          scratch.along_rows.apply(forward_rows_of->col(c).data() + i * C, X.col(c).data() + i * C);
      }
    }
    // Strips of columns: B̂ column, ./ λ, S_R, back into X.
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 2)
#endif
    for (int strip = 0; strip < strips; ++strip) {
      const int q0 = strip * kStrip, width = std::min(kStrip, C_ - q0);
      for (int w = 0; w < width; ++w) {
        inverse_column(norm, y_[std::size_t(q0) + std::size_t(w)], a_.data(), b_.data(), scratch.inv.data(), R_);
        for (int c = 0; c < 3; ++c) {
          double* column = scratch.strip[std::size_t(c)].data() + std::size_t(w) * R;
          spectrum_column(sources[std::size_t(c)], q0 + w, scratch, column);
          scale_by(column, scratch.inv.data(), R_);
          scratch.along_cols.apply(column, column);
        }
      }
      for (int c = 0; c < 3; ++c) {
        const double* s = scratch.strip[std::size_t(c)].data();
        double* x = X.col(c).data() + q0;
        for (std::size_t p = 0; p < R; ++p) {
          // the rows ahead: a stride of a whole row defeats the hardware prefetcher
          if (p + kAhead < R) {
            __builtin_prefetch(x + (p + kAhead) * C, 1);
            __builtin_prefetch(x + (p + kAhead) * C + std::size_t(width - 1), 1);
          }
          for (int w = 0; w < width; ++w) x[p * C + std::size_t(w)] = s[std::size_t(w) * R + p];
        }
      }
    }
    // Rows, in place: X = (S_R (B̂ ./ λ)) S_C.
#if defined(_OPENMP)
#pragma omp for schedule(dynamic, 32)
#endif
    for (int k = 0; k < 3 * R_; ++k) {
      double* row = X.col(k / R_).data() + std::size_t(k % R_) * C;
      scratch.along_rows.apply(row, row);
    }
  }
}

ColumnExponents DstSolver::rhs_scaling(const Eigen::MatrixX3d& B) {
  scanned_.source = nullptr;
  const auto C = std::size_t(C_);
  const int bands = threads_;
  // per band and column: the largest magnitude, and whether a row 1..R−2 has a non-zero inside
  std::vector<std::array<double, 3>> largest(std::size_t(bands), {0.0, 0.0, 0.0});
  std::vector<std::array<bool, 3>> interior(std::size_t(bands), {false, false, false});
  detail::for_each_row_band(R_, bands, [&](int p, int r0, int r1) {
    for (int c = 0; c < 3; ++c) {
      const double* b = B.col(c).data();
      double& m = largest[std::size_t(p)][std::size_t(c)];
      bool inside = false;
      for (int i = r0; i < r1; ++i) {
        const double* row = b + std::size_t(i) * C;
        m = detail::larger_magnitude(m, largest_abs(Eigen::Map<const Eigen::VectorXd>(row, C_)));
        if (!inside && i > 0 && i + 1 < R_) inside = detail::has_interior(row, C_);
      }
      interior[std::size_t(p)][std::size_t(c)] = inside;
    }
  });
  ColumnExponents e{};
  for (std::size_t c = 0; c < 3; ++c) {
    double m = 0;
    bool inside = false;
    for (std::size_t p = 0; p < std::size_t(bands); ++p) {
      m = detail::larger_magnitude(m, largest[p][c]);
      inside = inside || interior[p][c];
    }
    e[c] = scaling_exponent(m);
    scanned_.ring[c] = R_ >= 3 && C_ >= 3 && !inside;  // on_ring's verdict
  }
  scanned_.source = B.data();
  return e;
}

SolveStatus DstSolver::do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) {
  const bool scanned = scanned_.source == B.data();
  scanned_.source = nullptr;
  X.resize(B.rows(), 3);
  std::array<Spectrum, 3> sources;
  bool any_rows = false;
  for (int c = 0; c < 3; ++c) {
    if (scanned ? scanned_.ring[std::size_t(c)] : on_ring(B.col(c).data())) {
      ring_sides(B.col(c).data(), ring_[std::size_t(c)]);
      sources[std::size_t(c)].ring = &ring_[std::size_t(c)];
    } else {
      sources[std::size_t(c)].rows = X.col(c).data();
      any_rows = true;
    }
  }
  invert(sources, X, any_rows ? &B : nullptr);
  summary.iterations = 1;
  return SolveStatus::kSuccess;
}

SolveStatus DstSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                                      Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::Index n = Eigen::Index(R_) * C_;
  const std::size_t used = weights.size();
  if (hat_.size() < used || (!hat_.empty() && hat_[0][0].size() != std::size_t(n))) {
    // B̂ of each basis member by columns (cols × rows): the strip pass without division.
    hat_.assign(used, std::vector<std::vector<double>>(3));
    std::vector<double> rows(static_cast<std::size_t>(n));
    Scratch& scratch = scratch_[0];
    RingSides sides;
    for (std::size_t r = 0; r < used; ++r)
      for (int c = 0; c < 3; ++c) {
        const double* b = basis[r].col(c).data();
        Spectrum source;
        if (on_ring(b)) {
          ring_sides(b, sides);
          source.ring = &sides;
        } else {
          for (int i = 0; i < R_; ++i)
            scratch.along_rows.apply(b + std::size_t(i) * std::size_t(C_),
                                     rows.data() + std::size_t(i) * std::size_t(C_));
          source.rows = rows.data();
        }
        std::vector<double>& hat = hat_[r][std::size_t(c)];
        hat.resize(std::size_t(n));
        for (int q = 0; q < C_; ++q) spectrum_column(source, q, scratch, hat.data() + std::size_t(q) * std::size_t(R_));
      }
  }
  X.resize(n, 3);
  std::array<Spectrum, 3> sources;
  for (int c = 0; c < 3; ++c)
    for (std::size_t r = 0; r < used; ++r)
      if (weights[r] != 0) sources[std::size_t(c)].terms.emplace_back(weights[r], &hat_[r][std::size_t(c)]);
  invert(sources, X, nullptr);
  summary.iterations = 1;
  return SolveStatus::kSuccess;
}

}  // namespace

std::unique_ptr<LinearSolver> make_dst_solver(const SolverOptions& options) {
  return std::make_unique<DstSolver>(options);
}

}  // namespace coons::solvers
