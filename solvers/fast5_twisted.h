// fast5, the banded solves from both ends with the row transforms on the way back: the second
// sweep of fast5 (x̂ = A₁⁻¹(b̂ − U h), then the inverse sine transform of every grid row) for the
// modes q ≥ low (fast5_modes.h), without a separate pass of row transforms over the grid.
//
// M_q is symmetric Toeplitz, so persymmetric (J M_q J = M_q, J the reversal of the rows): its
// banded LDLᵀ from the bottom row upwards has the factors of the one from the top, mirrored. The
// rows 0 … h−1 (h = rows/2) are eliminated from the top and the rows h+2 … rows−1 from the bottom,
// each half on its own; the 2×2 system left on the rows h, h+1 is solved per mode; then each half
// is swept back from the middle outwards, and each grid row is transformed along j as soon as it
// is complete, while it is in the cache. With d_r, l1_r, l2_r the factors of row r (pivot and the
// multipliers of the rows r+1 and r+2) and m = rows − h − 2 (row h+1 counted from the bottom),
//   K = [ d_h − l2_{m−1}² d_{m−1}              l1_h d_h − l1_{m−1} l2_{m−1} d_{m−1} ]
//       [ l1_h d_h − l1_{m−1} l2_{m−1} d_{m−1}   d_m − l2_{h−1}² d_{h−1}            ]
// (the top's elimination leaves d_h and l1_h d_h on row h, the bottom's the mirrored terms, and each
// half reaches the far middle row through l2 only). Its right-hand side is the way down continued
// one row into the middle from each side (y_h from the top, y_{h+1} from the bottom) plus the other
// side's term −l2·y reaching across.
// Why: the chunked sweep writes x̂ into the grid a block of modes at a time, and the row
// transforms then read every row back from memory; here a row is transformed soon after it is
// finished, mostly from the cache, and the two halves share no rows, so two threads need one
// barrier (between the ways down and up); the transforms of finished rows go to whichever thread
// is free, so a thread on a slower CPU does not hold the other up.
// Sizes: per half 6·cols doubles of middle terms and 9·cols of scratch.
// Based on: G. Meurant, A review on the inverse of symmetric tridiagonal and block tridiagonal
// matrices, SIAM J. Matrix Anal. Appl. 13 (1992) 707–728 (twisted factorizations: elimination
// from both ends meeting at a twist); A. Cantoni & P. Butler, Eigenvalues and eigenvectors of
// symmetric centrosymmetric matrices, Linear Algebra Appl. 13 (1976) 275–288 (persymmetry).
#pragma once

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <functional>
#include <vector>

#include "fast5_low_modes.h"
#include "fast5_modes.h"
#include "sine_transform.h"

namespace coons::solvers::fast5_detail {

//! The fewest grid rows the twisted sweep takes (both halves at least two rows beyond the middle).
constexpr int kMinTwistRows = 8;

//! K⁻¹ of every mode q ≥ low (above): i11, i12, i22 (#cols; zero below low).
struct TwistFactors {
  int rows = 0, cols = 0, low = 0;
  int h = 0;  //!< the middle rows are h and h + 1
  Eigen::VectorXd i11, i12, i22;
};

//! The middle's K⁻¹ from the factors f (rows ≥ kMinTwistRows) for the modes [low, cols).
TwistFactors twist_factors(const ModeFactors& f, int low);

//! What a half leaves for the middle (per right-hand side c, cols each): y of its own middle row
//! (the way down continued into it) at [2c·cols, (2c+1)·cols), and its term −l2·y of the other
//! middle row at [(2c+1)·cols, (2c+2)·cols).
using TwistEnds = std::vector<double>;

//! The way down of one half (half 0: rows 0 … h−1 from the top; 1: rows rows−1 … h+2 from the
//! bottom) for the modes [low, cols) and three right-hand sides: L⁻¹ of the input (SweepInput,
//! count 3) into those rows of grid[c] (rows × cols, row-major; the columns < low not touched),
//! and the half's middle terms into ends.
void twisted_down(const ModeFactors& f, const TwistFactors& tw, int half, const SweepInput& in,
                  const std::array<double*, 3>& grid, TwistEnds& ends);

//! The ways up of both halves from the middle (after twisted_down of both): the middle rows'
//! values, then the half's rows outwards, each finished in place in grid (whose columns < low hold
//! the lowest modes, written before; scratch: 9·cols doubles per half), and every finished row
//! transformed in place along j (scale_j·S·row) once the two rows after it in its half, which read
//! it, are finished; done(c, r, row) after each.
//! Each half's rows are finished in order by one thread, its owner; any thread transforms finished
//! rows (the owner its own first, while they are in the cache), so a thread on a slower CPU
//! leaves its rows to the other. work(t, threads, along_j) from each of `threads` threads (t < threads;
//! along_j that thread's own); it returns when every row is claimed. The same bits on any count.
class TwistedUp {
 public:
  TwistedUp(const ModeFactors& f, const TwistFactors& tw, const std::array<TwistEnds, 2>& ends,
            const std::array<double*, 3>& grid, const std::array<double*, 2>& scratch, double scale_j,
            std::function<void(int, int, const double*)> done);
  void work(int thread, int threads, detail::SineTransform& along_j);

 private:
  struct Half {
    double* scratch = nullptr;
    int count = 0;                             // rows to finish: the middle row and the half's own
    int next = 0;                              // the owner's: the next row to finish
    std::atomic<int> finished{0}, claimed{0};  // rows that may be transformed, rows claimed for it
  };
  [[nodiscard]] int grid_row(int half, int k) const;
  void step(int half);
  void transform(int half, int k0, int k1, detail::SineTransform& along_j) const;

  const ModeFactors& f_;
  const TwistFactors& tw_;
  const std::array<TwistEnds, 2>& ends_;
  std::array<double*, 3> grid_;
  double scale_j_;
  std::function<void(int, int, const double*)> done_;
  std::array<Half, 2> halves_;
};

//! What twisted_solve keeps from one solve to the next (one per solver).
struct TwistedBuffers {
  std::array<TwistEnds, 2> ends;                   //!< what each half leaves the middle
  std::array<detail::AlignedBuffer, 2> scratch;    //!< each half's rows next to the middle (9·cols)
  std::vector<detail::SineTransform> low_along_i;  //!< the lowest modes' DST along i on the threads 1, 2, …
};

//! The buffers of twisted_solve on a rows × cols grid and `threads` threads (nothing below
//! kMinTwistRows rows); planning: the FFTW flags of the transforms.
TwistedBuffers twisted_buffers(int rows, int cols, int threads, unsigned planning);

//! x̂ = A₁⁻¹ (the input) for every mode and the inverse transform of every row of it, into grid
//! (rows × cols, row-major, per right-hand side; f.rows ≥ kMinTwistRows): the ways down of both halves
//! and the lowest modes (low, by the closed form, in four parts) are six units on `threads` threads,
//! then the two halves' ways up (TwistedUp). along_i: the DST along i of thread 0; along_j: one
//! DST along j per thread; done as in TwistedUp. Each unit writes its own rows or columns of the
//! grid: the same bits on any number of threads.
void twisted_solve(const ModeFactors& f, const TwistFactors& tw, const LowModes& low, const SweepInput& in,
                   const std::array<double*, 3>& grid, TwistedBuffers& buffers, detail::SineTransform& along_i,
                   std::vector<detail::SineTransform>& along_j, int threads,
                   const std::function<void(int, int, const double*)>& done);

}  // namespace coons::solvers::fast5_detail
