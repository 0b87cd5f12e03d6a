// Internal to the structured solvers (dst, fast): FFTW-aligned buffers, the 1-D discrete sine
// transform of a row built on a real FFT, and the factored tridiagonal solves shared by them.
//
//   DST-I:  F_k = Σ_{j=1..n} f_j sin(π j k / (n+1)),  k = 1..n   (FFTW's RODFT00 is 2·F)
//           S·S = (n+1)/2 · I, so the inverse is 2/(n+1) times the transform itself.
//
// The transform goes through a real FFT of length n+1 with a symmetric pre-pass and a running-sum
// post-pass, which is 2–6× faster than FFTW's r2r RODFT00 (whose r2hc codelets are not vectorised).
// Based on: W. H. Press et al., Numerical Recipes, 3rd ed. (2007), §12.4 (sinft);
// P. N. Swarztrauber, Vectorizing the FFTs, in Parallel Computations (1982) (FFTPACK's sint).
#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

#include "linear_solver.h"
#include "vector_clones.h"

namespace coons::solvers::detail {

//! A fixed-size array of doubles starting on a 64-byte cache line (SIMD-aligned for FFTW too),
//! not initialised (so that making a large one costs nothing until it is written).
class AlignedBuffer {
 public:
  AlignedBuffer() = default;
  explicit AlignedBuffer(std::size_t n);
  ~AlignedBuffer();
  AlignedBuffer(AlignedBuffer&& other) noexcept;
  AlignedBuffer& operator=(AlignedBuffer&& other) noexcept;
  AlignedBuffer(const AlignedBuffer&) = delete;
  AlignedBuffer& operator=(const AlignedBuffer&) = delete;

  [[nodiscard]] double* data() { return data_; }
  [[nodiscard]] const double* data() const { return data_; }
  [[nodiscard]] std::size_t size() const { return size_; }
  double& operator[](std::size_t k) { return data_[k]; }
  double operator[](std::size_t k) const { return data_[k]; }

 private:
  double* data_ = nullptr;
  std::size_t size_ = 0;
};

//! The FFTW planner flag for SolverOptions::measure_fft_plans: FFTW_MEASURE when asked,
//! otherwise FFTW_ESTIMATE (no timing, so the same plan, and the same rounding, in every run).
unsigned fft_planning(const SolverOptions& options);

//! Held around every call of the FFTW planner (making or destroying a plan): FFTW allows only
//! fftw_execute from several threads at once, and a threaded sweep may make plans (fast's dst
//! fallback) while other members are being solved.
std::mutex& fftw_planner_mutex();

//! Makes the FFTW plans created next use `threads` threads (FFTW's OpenMP library; resolved as in
//! resolved_threads). Without libfftw3_omp in the build it does nothing. Call it with 1 after
//! making a threaded plan: the setting is process-wide.
void fft_plan_threads(int threads);

//! The DST-I of length n (see above) of one row at a time. Plans are made once (with the
//! planner flag `planning`, see fft_planning) on internal buffers; apply() works on arrays of any
//! alignment. Not thread-safe (shared scratch).
class SineTransform {
 public:
  SineTransform() = default;
  SineTransform(int n, unsigned planning);
  ~SineTransform();
  SineTransform(SineTransform&& other) noexcept;
  SineTransform& operator=(SineTransform&& other) noexcept;
  SineTransform(const SineTransform&) = delete;
  SineTransform& operator=(const SineTransform&) = delete;

  [[nodiscard]] int size() const { return n_; }
  //! out = scale · S · in (length n). in and out may be the same array.
  void apply(const double* in, double* out, double scale = 1.0);
  //! sin(π k/(n+1)), k = 1..n: S·e_1. (S·e_n is the same with signs (−1)^(k+1).)
  [[nodiscard]] const double* first_column() const { return first_column_.data(); }

 private:
  void release();

  int n_ = 0;
  void* plan_ = nullptr;        // fftw_plan (r2c of length n+1)
  AlignedBuffer y_;             // real FFT input, length n+1
  AlignedBuffer z_;             // half-complex FFT output, 2·((n+1)/2 + 1)
  std::vector<double> weight_;  // sin(π j/(n+1)), j = 0..n
  std::vector<double> sums_;    // running sums of the post-pass
  std::vector<double> first_column_;
};

//! The LDLᵀ-type factors of the symmetric constant tridiagonal matrix tridiag(off, diag) of order
//! n, without pivoting: pivots m_0 = diag, m_k = diag − off²/m_{k−1}; inv_pivot[k] = 1/m_k.
struct Tridiagonal {
  double diag = 0, off = 0;
  std::vector<double> inv_pivot;

  //! false when a pivot is (near) zero, or when the pivots change sign (indefinite matrix) and
  //! one is small enough for elimination without pivoting to lose accuracy.
  bool factor(int n, double diag, double off);
  //! x = T⁻¹ b for a vector with unit stride; x may alias b.
  void solve(const double* b, double* x) const;
  //! x = T⁻¹ b for a vector with stride `stride`.
  void solve_strided(const double* b, double* x, std::ptrdiff_t stride) const;
  [[nodiscard]] int size() const { return int(inv_pivot.size()); }
};

//! The common frame of the structured solvers (dst, fast): the check both need (kNotApplicable
//! without a stencil or with an empty grid), the grid size R_ × C_, and the value-dependent set-up
//! on the stencil itself.
class StructuredSolver : public LinearSolver {
 public:
  using LinearSolver::LinearSolver;

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) final;
  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) final;
  //! Plans and buffers for an R_ × C_ grid (set before the call).
  virtual SolveStatus analyze_grid(SolveSummary& summary) = 0;
  //! The factorisation for the stencil s of op (op is passed on for fallbacks).
  virtual SolveStatus factorize_grid(const LinearOperator& op, const GridStencil& s, SolveSummary& summary) = 0;

  int R_ = 0, C_ = 0;

 private:
  // The stencil of op, or nullptr with the reason in the summary.
  static const GridStencil* grid_of(const LinearOperator& op, SolveSummary& summary);
};

//! Relative threshold below which a pivot of an indefinite tridiagonal matrix counts as unsafe.
constexpr double kUnsafePivot = 1e-4;
//! Relative threshold below which any pivot counts as zero.
constexpr double kZeroPivot = 1e-13;

//! dst[0..n) = src[0..n) with non-temporal stores where the target is aligned (x86-64 SSE2), so
//! that writing a large output does not first read it into the cache. Call stream_fence() after
//! the last one.
void stream_copy(const double* src, double* dst, std::size_t n);
void stream_fence();

}  // namespace coons::solvers::detail
