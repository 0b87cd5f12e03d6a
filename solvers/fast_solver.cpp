// fast: sine transform along j, tridiagonal solves along i (vectorised across the modes); a
// Kronecker-product path without transforms; the dst solver where elimination would be unsafe.
//
// For the sine mode q along j (y_q = cos(qπ/(cols+1))) the stencil acts along i as the
// tridiagonal matrix T_q = tridiag(e_i + 2d·y_q, c + 2e_j·y_q). When c·d = e_i·e_j the stencil
// is T_i ⊗ T_j with T_i = tridiag(e_i/c, 1), T_j = tridiag(e_j, c), so X = T_i⁻¹ B T_j⁻¹.
// When cols+1 has a prime factor above 13 (FFTW is then several times slower), the grid is
// widened by a few columns to a fast length and the capacitance matrix method keeps the
// solution zero on them.
// Based on: R. W. Hockney, A fast direct solution of Poisson's equation using Fourier analysis,
// J. ACM 12 (1965); R. E. Lynch, J. R. Rice & D. H. Thomas, Direct solution of partial difference
// equations by tensor product methods, Numer. Math. 6 (1964); B. L. Buzbee, F. W. Dorr,
// J. A. George & G. H. Golub, The direct solution of the discrete Poisson equation on irregular
// regions, SIAM J. Numer. Anal. 8 (1971).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "sine_transform.h"
#include "structured_solvers.h"

namespace coons::solvers {
namespace {

using detail::AlignedBuffer;
using detail::structured_grid;
using detail::SineTransform;
using detail::Tridiagonal;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A right-hand side column (rows × cols, row-major) kept row by row: a row whose interior
// (columns 1..cols−2) is zero is stored as its two end values, any other row in full. The right-
// hand side of a mask system has two full rows (next to the frame) and end values elsewhere.
struct RowForm {
  int width = 0;                    // length of the stored rows: cols, or the transform length
  std::vector<double> first, last;  // end values of the sparse rows (zero at dense rows)
  std::vector<int> dense_rows;      // the rows stored in full, ascending
  std::vector<int> slot;            // per row: −1, or its index in dense_rows
  std::vector<double> values;       // the full rows, width each (physical or sine-transformed)
};

// True when a value other than ±0 sits in row[1..C−2] (NaN included): an OR of the bits without
// the sign, which vectorises, unlike a compare-and-break loop.
COONS_VECTOR_CLONES bool has_interior(const double* row, int C) {
  std::uint64_t bits = 0;
  for (int j = 1; j + 1 < C; ++j) {
    std::uint64_t b;
    std::memcpy(&b, row + j, sizeof b);
    bits |= b << 1;
  }
  return bits != 0;
}

RowForm split_rows(const double* b, int R, int C) {
  RowForm f;
  f.width = C;
  f.first.assign(std::size_t(R), 0.0);
  f.last.assign(std::size_t(R), 0.0);
  f.slot.assign(std::size_t(R), -1);
  for (int i = 0; i < R; ++i) {
    const double* row = b + std::size_t(i) * std::size_t(C);
    if (!has_interior(row, C)) {
      f.first[std::size_t(i)] = row[0];
      f.last[std::size_t(i)] = C >= 2 ? row[C - 1] : 0.0;
    } else {
      f.slot[std::size_t(i)] = int(f.dense_rows.size());
      f.dense_rows.push_back(i);
      f.values.insert(f.values.end(), row, row + C);
    }
  }
  return f;
}

// Σ_r w_r · forms[r] (same rows and width). A sparse row expands as first·e0 + last·e1, where
// e0, e1 are the unit vectors (physical forms) or their sine transforms (transformed forms).
RowForm combine(const std::vector<const RowForm*>& forms, const std::vector<double>& w, int R,
                const std::vector<double>& e0, const std::vector<double>& e1) {
  const int C = forms.empty() ? int(e0.size()) : forms[0]->width;
  RowForm out;
  out.width = C;
  out.first.assign(std::size_t(R), 0.0);
  out.last.assign(std::size_t(R), 0.0);
  out.slot.assign(std::size_t(R), -1);
  for (int i = 0; i < R; ++i) {
    bool dense = false;
    for (std::size_t r = 0; r < forms.size(); ++r) dense |= w[r] != 0 && forms[r]->slot[std::size_t(i)] >= 0;
    if (!dense) {
      for (std::size_t r = 0; r < forms.size(); ++r) {
        out.first[std::size_t(i)] += w[r] * forms[r]->first[std::size_t(i)];
        out.last[std::size_t(i)] += w[r] * forms[r]->last[std::size_t(i)];
      }
      continue;
    }
    out.slot[std::size_t(i)] = int(out.dense_rows.size());
    out.dense_rows.push_back(i);
    const std::size_t at = out.values.size();
    out.values.resize(at + std::size_t(C), 0.0);
    double* row = out.values.data() + at;
    for (std::size_t r = 0; r < forms.size(); ++r) {
      const RowForm& f = *forms[r];
      const int s = f.slot[std::size_t(i)];
      if (w[r] == 0) continue;
      if (s >= 0) {
        const double* v = f.values.data() + std::size_t(s) * std::size_t(C);
        for (int q = 0; q < C; ++q) row[q] += w[r] * v[q];
      } else {
        const double a = w[r] * f.first[std::size_t(i)], b = w[r] * f.last[std::size_t(i)];
        for (int q = 0; q < C; ++q) row[q] += a * e0[std::size_t(q)] + b * e1[std::size_t(q)];
      }
    }
  }
  return out;
}

// --- the hot loops, on distinct arrays so that they vectorise -----------------------------------

// x = h − l∘p (p = nullptr: x = h).
COONS_VECTOR_CLONES void eliminate_dense(const double* __restrict h, const double* __restrict l,
                                         const double* __restrict p, double* __restrict x, int n) {
  if (!p) {
    for (int q = 0; q < n; ++q) x[q] = h[q];
    return;
  }
  for (int q = 0; q < n; ++q) x[q] = h[q] - l[q] * p[q];
}

// x = a·s + b·t − l∘p (p = nullptr: without the last term).
COONS_VECTOR_CLONES void eliminate_sparse(double a, double b, const double* __restrict s,
                                          const double* __restrict t, const double* __restrict l,
                                          const double* __restrict p, double* __restrict x, int n) {
  if (!p) {
    for (int q = 0; q < n; ++q) x[q] = a * s[q] + b * t[q];
    return;
  }
  for (int q = 0; q < n; ++q) x[q] = a * s[q] + b * t[q] - l[q] * p[q];
}

// l = o∘r.
COONS_VECTOR_CLONES void multiply(const double* __restrict o, const double* __restrict r,
                                  double* __restrict l, int n) {
  for (int q = 0; q < n; ++q) l[q] = o[q] * r[q];
}

// xh = (y − o∘xh)∘r.
COONS_VECTOR_CLONES void back_substitute(const double* __restrict y, const double* __restrict o,
                                         const double* __restrict r, double* __restrict xh,
                                         int n) {
  for (int q = 0; q < n; ++q) xh[q] = (y[q] - o[q] * xh[q]) * r[q];
}

// x = Σ_k a_k v_k (K ≥ 1 terms).
COONS_VECTOR_CLONES void rank_row(const double* a, const double* const* v, int K,
                                  double* __restrict x, int n) {
  int k = 0;
  if (K % 2) {
    const double a0 = a[0];
    const double* __restrict v0 = v[0];
    for (int j = 0; j < n; ++j) x[j] = a0 * v0[j];
    k = 1;
  } else {
    const double a0 = a[0], a1 = a[1];
    const double* __restrict v0 = v[0];
    const double* __restrict v1 = v[1];
    for (int j = 0; j < n; ++j) x[j] = a0 * v0[j] + a1 * v1[j];
    k = 2;
  }
  for (; k < K; k += 2) {
    const double a0 = a[k], a1 = a[k + 1];
    const double* __restrict v0 = v[k];
    const double* __restrict v1 = v[k + 1];
    for (int j = 0; j < n; ++j) x[j] += a0 * v0[j] + a1 * v1[j];
  }
}

// x = y − l·p (scalar l).
COONS_VECTOR_CLONES void axpy_rows(const double* __restrict y, double l, const double* __restrict p,
                                   double* __restrict x, int n) {
  for (int j = 0; j < n; ++j) x[j] = y[j] - l * p[j];
}

// x += a·v.
COONS_VECTOR_CLONES void add_scaled(double a, const double* __restrict v, double* __restrict x,
                                    int n) {
  for (int j = 0; j < n; ++j) x[j] += a * v[j];
}

double dot(const double* a, const double* b, int n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    s0 += a[j] * b[j];
    s1 += a[j + 1] * b[j + 1];
    s2 += a[j + 2] * b[j + 2];
    s3 += a[j + 3] * b[j + 3];
  }
  for (; j < n; ++j) s0 += a[j] * b[j];
  return (s0 + s1) + (s2 + s3);
}

// Largest prime factor of n ≥ 1.
int largest_prime_factor(int n) {
  int largest = 1;
  for (int f = 2; f * f <= n; ++f)
    while (n % f == 0) {
      largest = f;
      n /= f;
    }
  return std::max(largest, n);
}

// Columns to add so that the sine transform has a fast length: FFTW has codelets for the factors
// up to 13, and falls back to an O(p²) one for a larger prime p (a length of 1023 = 3·11·31 is 9×
// slower than 1024). Up to four extra columns, 7-smooth; 0 keeps the length.
int extra_columns(int cols) {
  if (largest_prime_factor(cols + 1) <= 13) return 0;
  for (int k = 1; k <= 4; ++k)
    if (largest_prime_factor(cols + k + 1) <= 7) return k;
  return 0;
}

// ------------------------------------------------------------------------------------------------

class FastSolver : public LinearSolver {
 public:
  explicit FastSolver(const SolverOptions& options) : LinearSolver(options) {}
  [[nodiscard]] std::string name() const override { return "fast"; }

  void sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis,
             const std::vector<SweepMember>& members, const SweepSink& sink) override;

 protected:
  SolveStatus do_analyze(const LinearOperator& op, SolveSummary& summary) override {
    const GridStencil* grid = structured_grid(op, summary);
    if (!grid) return SolveStatus::kNotApplicable;
    R_ = grid->rows;
    C_ = grid->cols;
    extra_ = extra_columns(C_);
    L_ = C_ + extra_;
    const std::size_t L = std::size_t(L_);
    sine_ = SineTransform(L_, detail::fft_planning(options_));
    sine_rows_ = extra_ > 0 ? SineTransform(R_, detail::fft_planning(options_)) : SineTransform();
    auto sine_column = [&](int j, std::vector<double>& v) {  // S·e_j, length L
      v.resize(L);
      for (int q = 0; q < L_; ++q) v[std::size_t(q)] = std::sin(M_PI * double(j + 1) * (q + 1) / (L_ + 1));
    };
    y_.resize(L);
    for (int q = 0; q < L_; ++q) y_[std::size_t(q)] = std::cos(M_PI * (q + 1) / (L_ + 1));
    sine_column(0, sine_e0_);
    if (C_ >= 2) sine_column(C_ - 1, sine_e1_);
    else sine_e1_.assign(L, 0.0);  // a row of one value has no second end
    sine_extra_.assign(std::size_t(extra_), {});
    for (int m = 0; m < extra_; ++m) sine_column(C_ + m, sine_extra_[std::size_t(m)]);
    unit_e0_.assign(std::size_t(C_), 0.0);
    unit_e1_.assign(std::size_t(C_), 0.0);
    unit_e0_[0] = 1;
    if (C_ >= 2) unit_e1_[std::size_t(C_ - 1)] = 1;
    off_ = AlignedBuffer(L);
    multipliers_ = AlignedBuffer(L);
    row_ = AlignedBuffer(L);
    for (auto& w : running_) w = AlignedBuffer(L);
    pivots_ = AlignedBuffer(L);
    for (auto& y : forward_) y = AlignedBuffer();  // made by the first solve that needs them
    // Blocks of the back substitution: 3·K rows of L doubles, to stay in the L2 cache.
    block_rows_ = std::max(2, std::min(R_, std::clamp(16384 / L_, 4, 32)));
    for (auto& b : block_) b = AlignedBuffer(std::size_t(block_rows_) * L);
    dst_.reset();
    return SolveStatus::kSuccess;
  }

  SolveStatus do_factorize(const LinearOperator& op, SolveSummary& summary) override {
    const GridStencil* grid = structured_grid(op, summary);
    if (!grid) return SolveStatus::kNotApplicable;
    const GridStencil& s = *grid;
    if (is_kronecker(s) && factor_kronecker(s)) {
      path_ = Path::kKronecker;
      return SolveStatus::kSuccess;
    }
    if (factor_transform(s) && (extra_ == 0 || factor_capacitance(s))) {
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

  SolveStatus do_solve(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X,
                       SolveSummary& summary) override {
    summary.iterations = 1;
    if (path_ == Path::kDst) {
      const SolveSummary inner = dst_->solve(B, X);
      summary.message = inner.message;
      return inner.status;
    }
    X.resize(B.rows(), 3);
    std::array<RowForm, 3> forms;
    for (int c = 0; c < 3; ++c) forms[std::size_t(c)] = split_rows(B.col(c).data(), R_, C_);
    if (path_ == Path::kKronecker) {
      for (int c = 0; c < 3; ++c) {
        if (int(forms[std::size_t(c)].dense_rows.size()) <= kMaxRank)
          solve_kronecker_rank(forms[std::size_t(c)], X.col(c).data());
        else
          solve_kronecker_dense(B.col(c).data(), X.col(c).data());
      }
    } else {
      for (auto& f : forms) transform_rows(f);
      solve_transform(forms, X);
    }
    return SolveStatus::kSuccess;
  }

 private:
  enum class Path { kKronecker, kTransform, kDst };
  // Dense rows up to which the Kronecker path writes X as a sum of outer products.
  static constexpr int kMaxRank = 8;

  static bool is_kronecker(const GridStencil& s) {
    if (s.center == 0) return false;
    const double cd = s.center * s.diag, ee = s.edge_i * s.edge_j;
    return std::abs(cd - ee) <= 4 * std::numeric_limits<double>::epsilon() * (std::abs(cd) + std::abs(ee));
  }

  // T_i = tridiag(e_i/c, 1) of order rows, T_j = tridiag(e_j, c) of order cols; both must be
  // safe to eliminate without pivoting.
  bool factor_kronecker(const GridStencil& s) {
    if (!ti_.factor(R_, 1.0, s.edge_i / s.center) || !tj_.factor(C_, s.center, s.edge_j)) return false;
    tj_e0_.assign(std::size_t(C_), 0.0);
    tj_e1_.assign(std::size_t(C_), 0.0);
    tj_.solve(unit_e0_.data(), tj_e0_.data());
    tj_.solve(unit_e1_.data(), tj_e1_.data());
    return true;
  }

  // The pivots of every T_q (q < L), row by row and vectorised across q:
  // m_0 = D_q, m_i = D_q − o_q²/m_{i−1}, with D_q = c + 2e_j·y_q, o_q = e_i + 2d·y_q.
  //
  // The recursion of a mode reaches its fixed point in floating point after a few rows for most
  // modes (bit for bit: once m_i = m_{i−1}, every later pivot is the same number), so only 3–6 %
  // of the table is computed and kept (at 1023², α ∈ [−0.2, 1/4]): row i stores the modes
  // [0, lo_i) ∪ [hi_i, L), where [lo_i, hi_i) is the run of converged modes around the one that
  // converges first, and the others take their limit. Nothing of the size of the grid is made.
  bool factor_transform(const GridStencil& s) {
    const std::size_t L = std::size_t(L_);
    std::vector<double> diag(L), m(L), smallest(L, HUGE_VAL);
    std::vector<char> positive(L, 0), negative(L, 0), converged(L, 0);
    double* o = off_.data();
    int first = 0;  // the mode expected to converge first: the most diagonally dominant one
    double best = -1;
    for (std::size_t q = 0; q < L; ++q) {
      o[q] = s.edge_i + 2 * s.diag * y_[q];
      diag[q] = s.center + 2 * s.edge_j * y_[q];
      m[q] = diag[q];
      const double dominance = o[q] == 0 ? HUGE_VAL : std::abs(diag[q] / o[q]);
      if (dominance > best) {
        best = dominance;
        first = int(q);
      }
    }
    std::array<std::vector<double>, 2> r{std::vector<double>(L), std::vector<double>(L)};
    auto track = [&](std::size_t q) {
      smallest[q] = std::min(smallest[q], std::abs(m[q]));
      (m[q] > 0 ? positive : negative)[q] = 1;
    };
    for (std::size_t q = 0; q < L; ++q) {
      r[0][q] = 1 / m[q];
      track(q);
    }
    pivot_lo_.assign(std::size_t(R_), 0);
    pivot_hi_.assign(std::size_t(R_), L_);
    pivot_offset_.assign(std::size_t(R_) + 1, 0);
    pivot_values_.clear();
    int lo = L_, hi = L_;  // the modes still computed: [0, lo) ∪ [hi, L)
    // Row k is stored once the modes that converged by row k are known (after row k+1).
    auto store = [&](int k, const std::vector<double>& row) {
      if (converged[std::size_t(first)]) {
        if (lo == L_) lo = hi = first, ++hi;
        while (lo > 0 && converged[std::size_t(lo - 1)]) --lo;
        while (hi < L_ && converged[std::size_t(hi)]) ++hi;
      }
      pivot_lo_[std::size_t(k)] = lo;
      pivot_hi_[std::size_t(k)] = hi;
      pivot_values_.insert(pivot_values_.end(), row.begin(), row.begin() + lo);
      pivot_values_.insert(pivot_values_.end(), row.begin() + hi, row.end());
      pivot_offset_[std::size_t(k) + 1] = pivot_values_.size();
    };
    for (int i = 1; i < R_; ++i) {
      const std::vector<double>& before = r[std::size_t((i - 1) % 2)];
      std::vector<double>& now = r[std::size_t(i % 2)];
      auto step = [&](int q0, int q1) {
        for (int q = q0; q < q1; ++q) {
          const std::size_t k = std::size_t(q);
          const double next = diag[k] - o[k] * o[k] * before[k];
          if (next == m[k]) converged[k] = 1;
          m[k] = next;
          now[k] = 1 / next;
          track(k);
        }
      };
      step(0, lo);
      step(hi, L_);
      store(i - 1, before);
    }
    const std::vector<double>& last = r[std::size_t((R_ - 1) % 2)];
    store(R_ - 1, last);
    // Converged modes hold the same value in both rows of r.
    pivot_limit_.assign(last.begin(), last.end());
    for (std::size_t q = 0; q < L; ++q) {
      const double scale = std::abs(diag[q]) + 2 * std::abs(o[q]);
      if (!(smallest[q] > detail::kZeroPivot * scale)) return false;
      if (positive[q] && negative[q] && smallest[q] < detail::kUnsafePivot * scale) return false;
    }
    return true;
  }

  // The running pivot row r_i (and l = o∘r) of the pipeline: from row `from` to row `to`, only
  // the modes stored in either row change.
  void load_pivots(int from, int to) {
    const double* o = off_.data();
    double* r = pivots_.data();
    double* l = multipliers_.data();
    const double* row = pivot_values_.data() + pivot_offset_[std::size_t(to)];
    const int lo = pivot_lo_[std::size_t(to)], hi = pivot_hi_[std::size_t(to)];
    auto value = [&](int q) {
      return q < lo ? row[q] : q >= hi ? row[lo + q - hi] : pivot_limit_[std::size_t(q)];
    };
    if (from < 0) {  // the whole row
      for (int q = 0; q < L_; ++q) r[q] = value(q);
      multiply(o, r, l, L_);
      return;
    }
    const int a = std::max(lo, pivot_lo_[std::size_t(from)]);
    const int b = std::max(a, std::min(hi, pivot_hi_[std::size_t(from)]));
    for (int q = 0; q < a; ++q) r[q] = value(q);
    for (int q = b; q < L_; ++q) r[q] = value(q);
    multiply(o, r, l, a);
    multiply(o + b, r + b, l + b, L_ - b);
  }

  // The grid is widened by `extra_` columns so that the transform length is fast; the solution
  // must vanish there, which sources U on those columns enforce (capacitance matrix method):
  // G U = −V, V the response there to B, G = Eᵀ A'⁻¹ E. The sine transform along i
  // block-diagonalises G: G_p(m, m') = 2/(L+1) Σ_q S(C+m, q) S(C+m', q) / λ'_pq.
  // Based on: B. L. Buzbee, F. W. Dorr, J. A. George & G. H. Golub, The direct solution of the
  // discrete Poisson equation on irregular regions, SIAM J. Numer. Anal. 8 (1971).
  bool factor_capacitance(const GridStencil& s) {
    const int k = extra_;
    capacitance_.assign(std::size_t(R_), Eigen::MatrixXd());
    std::vector<double> inv(static_cast<std::size_t>(L_));
    double largest = 0;
    for (int p = 0; p < R_; ++p) {
      const double x = std::cos(M_PI * (p + 1) / (R_ + 1));
      const double a = s.center + 2 * s.edge_i * x, b = 2 * s.edge_j + 4 * s.diag * x;
      for (int q = 0; q < L_; ++q) {
        const double lambda = a + b * y_[std::size_t(q)];
        largest = std::max(largest, std::abs(lambda));
        inv[std::size_t(q)] = lambda;
      }
      for (int q = 0; q < L_; ++q) inv[std::size_t(q)] = 1 / inv[std::size_t(q)];
      Eigen::MatrixXd G(k, k);
      for (int m = 0; m < k; ++m)
        for (int n = 0; n <= m; ++n) {
          double sum = 0;
          const double* sm = sine_extra_[std::size_t(m)].data();
          const double* sn = sine_extra_[std::size_t(n)].data();
          for (int q = 0; q < L_; ++q) sum += sm[q] * sn[q] * inv[std::size_t(q)];
          G(m, n) = G(n, m) = 2.0 / (L_ + 1) * sum;
        }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(G);
      if (!lu.isInvertible()) return false;
      capacitance_[std::size_t(p)] = lu.inverse();
      for (int q = 0; q < L_; ++q)
        if (!(std::abs(1 / inv[std::size_t(q)]) > detail::kZeroPivot * largest)) return false;
    }
    return true;
  }

  // Dense rows of a form → their sine transforms of length L (zero-padded).
  void transform_rows(RowForm& f) {
    const std::size_t C = std::size_t(f.width), L = std::size_t(L_);
    if (f.width == L_) {
      for (std::size_t k = 0; k < f.dense_rows.size(); ++k) {
        double* row = f.values.data() + k * L;
        sine_.apply(row, row, 1.0);
      }
      return;
    }
    std::vector<double> values(f.dense_rows.size() * L, 0.0);
    for (std::size_t k = 0; k < f.dense_rows.size(); ++k) {
      double* row = values.data() + k * L;
      std::copy(f.values.data() + k * C, f.values.data() + (k + 1) * C, row);
      sine_.apply(row, row, 1.0);
    }
    f.values = std::move(values);
    f.width = L_;
  }

  // For every mode q: X̂(:,q) = T_q⁻¹ (B̂(:,q) + sources on the extra columns), three columns at
  // once, each X̂ row handed to finish(i, c, x̂) as soon as the back substitution makes it (so the
  // inverse transform of a row runs while the row is in cache). Every loop runs over whole rows,
  // vectorised across the modes. The forward elimination keeps only the last row of each block of
  // K rows (in rows[c] + i·stride: X itself when L = C) and recomputes a block in cache before
  // substituting back through it: two passes over memory fewer for a little more arithmetic.
  template <class Finish>
  void pipeline(const std::array<RowForm, 3>& forms, const std::array<const double*, 3>& sources,
                const std::array<double*, 3>& rows, std::size_t stride, Finish&& finish) {
    const std::size_t L = std::size_t(L_);
    const int K = block_rows_;
    const double* o = off_.data();
    const double* l = multipliers_.data();
    const double* r = pivots_.data();
    auto saved = [&](int c, int i) { return rows[std::size_t(c)] + std::size_t(i) * stride; };
    auto slot_row = [&](int c, int t) { return block_[std::size_t(c)].data() + std::size_t(t) * L; };
    int at = -1;  // the row held by the running pivot row
    auto pivots_for = [&](int i) {
      if (at != i) load_pivots(at, i);
      at = i;
    };
    // Row i of the forward elimination: y_i = B̂_i − l_i ∘ y_{i−1}, l_i = o ∘ r_{i−1}.
    auto eliminate = [&](int i, int c, const double* p, double* y) {
      const RowForm& f = forms[std::size_t(c)];
      const int slot = f.slot[std::size_t(i)];
      if (slot >= 0)
        eliminate_dense(f.values.data() + std::size_t(slot) * L, l, p, y, L_);
      else
        eliminate_sparse(f.first[std::size_t(i)], f.last[std::size_t(i)], sine_e0_.data(),
                         sine_e1_.data(), l, p, y, L_);
      if (const double* u = sources[std::size_t(c)])
        for (int m = 0; m < extra_; ++m)
          add_scaled(u[std::size_t(i) * std::size_t(extra_) + std::size_t(m)],
                     sine_extra_[std::size_t(m)].data(), y, L_);
    };
    for (int i = 0; i < R_; ++i) {
      if (i > 0) pivots_for(i - 1);
      const int t = i % K;
      for (int c = 0; c < 3; ++c) {
        double* y = slot_row(c, t);
        eliminate(i, c, i > 0 ? slot_row(c, (t + K - 1) % K) : nullptr, y);
        if (t == K - 1 && i + 1 < R_) std::copy(y, y + L, saved(c, i));
      }
    }
    // Back substitution, x̂_i = (y_i − o ∘ x̂_{i+1}) ∘ r_i, block by block from the last one
    // (whose rows are still in the buffer).
    for (auto& w : running_) std::fill(w.data(), w.data() + L, 0.0);
    const int last_block = (R_ - 1) / K;
    for (int b = last_block; b >= 0; --b) {
      const int first = b * K, end = std::min(R_, first + K);
      if (b != last_block)
        for (int i = first; i < end; ++i) {
          if (i > 0) pivots_for(i - 1);
          for (int c = 0; c < 3; ++c) {
            const double* p = i == 0 ? nullptr : i == first ? saved(c, i - 1) : slot_row(c, i - first - 1);
            eliminate(i, c, p, slot_row(c, i - first));
          }
        }
      for (int i = end - 1; i >= first; --i) {
        pivots_for(i);
        for (int c = 0; c < 3; ++c) {
          double* xh = running_[std::size_t(c)].data();
          back_substitute(slot_row(c, i - first), o, r, xh, L_);
          finish(i, c, xh);
        }
      }
    }
  }

  // X = (2/(L+1)) S X̂, first C columns; with extra columns, the sources U are found first from a
  // pipeline that only records the solution on the extra columns.
  void solve_transform(const std::array<RowForm, 3>& forms, Eigen::MatrixX3d& X) {
    const std::size_t C = std::size_t(C_);
    const double scale = 2.0 / (L_ + 1);
    std::array<const double*, 3> sources{nullptr, nullptr, nullptr};
    std::array<std::vector<double>, 3> U;
    // The forward rows: in X itself when they fit, else in buffers of the widened grid.
    std::array<double*, 3> rows{X.col(0).data(), X.col(1).data(), X.col(2).data()};
    std::size_t stride = C;
    if (extra_ > 0) {
      stride = forward_stride();
      for (int c = 0; c < 3; ++c) {
        AlignedBuffer& y = forward_[std::size_t(c)];
        if (y.size() != std::size_t(R_) * stride) y = AlignedBuffer(std::size_t(R_) * stride);
        rows[std::size_t(c)] = y.data();
      }
    }
    if (extra_ > 0) {
      const std::size_t k = std::size_t(extra_), R = std::size_t(R_);
      std::array<std::vector<double>, 3> V;
      for (auto& v : V) v.assign(R * k, 0.0);
      pipeline(forms, sources, rows, stride, [&](int i, int c, const double* xh) {
        for (std::size_t m = 0; m < k; ++m)
          V[std::size_t(c)][std::size_t(i) * k + m] = scale * dot(sine_extra_[m].data(), xh, L_);
      });
      // U = −(2/(R+1)) S_R [G_p⁻¹ (S_R V)_p], per extra column m along i.
      std::vector<double> column(R), hat(R * k);
      for (int c = 0; c < 3; ++c) {
        std::vector<double>& v = V[std::size_t(c)];
        for (std::size_t m = 0; m < k; ++m) {
          for (std::size_t i = 0; i < R; ++i) column[i] = v[i * k + m];
          sine_rows_.apply(column.data(), column.data(), 1.0);
          for (std::size_t p = 0; p < R; ++p) hat[p * k + m] = column[p];
        }
        U[std::size_t(c)].assign(R * k, 0.0);
        for (std::size_t p = 0; p < R; ++p) {
          const Eigen::Map<const Eigen::VectorXd> vp(hat.data() + p * k, Eigen::Index(k));
          const Eigen::VectorXd up = -(capacitance_[p] * vp);
          for (std::size_t m = 0; m < k; ++m) hat[p * k + m] = up(Eigen::Index(m));
        }
        for (std::size_t m = 0; m < k; ++m) {
          for (std::size_t p = 0; p < R; ++p) column[p] = hat[p * k + m];
          sine_rows_.apply(column.data(), column.data(), 2.0 / (R_ + 1));
          for (std::size_t i = 0; i < R; ++i) U[std::size_t(c)][i * k + m] = column[i];
        }
        sources[std::size_t(c)] = U[std::size_t(c)].data();
      }
    }
    pipeline(forms, sources, rows, stride, [&](int i, int c, const double* xh) {
      sine_.apply(xh, row_.data(), scale);
      detail::stream_copy(row_.data(), X.col(c).data() + std::size_t(i) * C, C);
    });
    detail::stream_fence();
  }

  // X = T_i⁻¹ B T_j⁻¹ = Σ_k u_k v_kᵀ with (u, v) = (T_i⁻¹ first, T_j⁻¹ e_0), (T_i⁻¹ last,
  // T_j⁻¹ e_{C−1}) and (T_i⁻¹ e_r, T_j⁻¹ B_r) for each dense row r.
  void solve_kronecker_rank(const RowForm& f, double* x) {
    const int K = 2 + int(f.dense_rows.size());
    u_.assign(std::size_t(K) * std::size_t(R_), 0.0);
    v_.assign(std::size_t(K) * std::size_t(C_), 0.0);
    auto u = [&](int k) { return u_.data() + std::size_t(k) * std::size_t(R_); };
    auto v = [&](int k) { return v_.data() + std::size_t(k) * std::size_t(C_); };
    ti_.solve(f.first.data(), u(0));
    ti_.solve(f.last.data(), u(1));
    std::copy(tj_e0_.begin(), tj_e0_.end(), v(0));
    std::copy(tj_e1_.begin(), tj_e1_.end(), v(1));
    for (int k = 2; k < K; ++k) {
      const int r = f.dense_rows[std::size_t(k - 2)];
      u(k)[r] = 1;
      ti_.solve(u(k), u(k));
      tj_.solve(f.values.data() + std::size_t(k - 2) * std::size_t(C_), v(k));
    }
    std::vector<const double*> vs(static_cast<std::size_t>(K));
    std::vector<double> a(static_cast<std::size_t>(K));
    for (int k = 0; k < K; ++k) vs[std::size_t(k)] = v(k);
    for (int i = 0; i < R_; ++i) {
      for (int k = 0; k < K; ++k) a[std::size_t(k)] = u(k)[i];
      rank_row(a.data(), vs.data(), K, x + std::size_t(i) * std::size_t(C_), C_);
    }
  }

  // Y = T_i⁻¹ B by elimination along i over whole rows, then each row X_i = Y_i T_j⁻¹.
  void solve_kronecker_dense(const double* b, double* x) {
    const std::size_t C = std::size_t(C_);
    const double off = ti_.off;
    const double* r = ti_.inv_pivot.data();
    std::copy(b, b + C, x);
    for (int i = 1; i < R_; ++i)
      axpy_rows(b + std::size_t(i) * C, off * r[i - 1], x + (std::size_t(i) - 1) * C, x + std::size_t(i) * C, C_);
    double* y = running_[0].data();
    std::fill(y, y + C, 0.0);
    for (int i = R_ - 1; i >= 0; --i) {
      double* xi = x + std::size_t(i) * C;
      for (std::size_t j = 0; j < C; ++j) y[j] = (xi[j] - off * y[j]) * r[i];
      tj_.solve(y, xi);
    }
  }

  int R_ = 0, C_ = 0, L_ = 0, extra_ = 0, block_rows_ = 16;
  Path path_ = Path::kTransform;
  SineTransform sine_, sine_rows_;
  std::vector<double> y_, sine_e0_, sine_e1_, unit_e0_, unit_e1_;
  std::vector<std::vector<double>> sine_extra_;
  std::vector<Eigen::MatrixXd> capacitance_;  // G_p⁻¹, extra_ × extra_ each
  AlignedBuffer off_, multipliers_, pivots_, row_;
  // The pivot table, compressed (see compress_pivots).
  std::vector<int> pivot_lo_, pivot_hi_;
  std::vector<std::size_t> pivot_offset_;
  std::vector<double> pivot_values_, pivot_limit_;
  std::array<AlignedBuffer, 3> running_, forward_, block_;
  // Rows of forward_ (used when L > C) start at multiples of 64 bytes.
  [[nodiscard]] std::size_t forward_stride() const { return (std::size_t(L_) + 7) / 8 * 8; }
  Tridiagonal ti_, tj_;
  std::vector<double> tj_e0_, tj_e1_, u_, v_;
  std::unique_ptr<LinearSolver> dst_;
};

void FastSolver::sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis,
                       const std::vector<SweepMember>& members, const SweepSink& sink) {
  // The basis right-hand sides split by rows once, and sine-transformed once when needed.
  std::vector<std::array<RowForm, 3>> physical, transformed;
  Eigen::MatrixX3d B, X;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const SweepMember& member = members[k];
    const Eigen::Index n = member.op.size();
    if (factorize(member.op) != SolveStatus::kSuccess) {
      X.setZero(n, 3);
      sink(k, X, summary());
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::size_t used = std::min(rhs_basis.size(), member.rhs_weights.size());
    const std::vector<double> w(member.rhs_weights.begin(), member.rhs_weights.begin() + long(used));
    auto materialize = [&] {
      B.setZero(n, 3);
      for (std::size_t r = 0; r < used; ++r) B += w[r] * rhs_basis[r];
    };
    SolveSummary result = summary();
    result.iterations = 1;
    X.resize(n, 3);
    bool have_B = false;
    if (path_ == Path::kDst) {
      materialize();
      have_B = true;
      const SolveSummary inner = dst_->solve(B, X);
      result.status = inner.status;
      result.message = inner.message;
    } else {
      if (physical.size() != used || (used > 0 && physical[0][0].first.size() != std::size_t(R_))) {
        physical.assign(used, {});
        transformed.clear();
        for (std::size_t r = 0; r < used; ++r)
          for (int c = 0; c < 3; ++c)
            physical[r][std::size_t(c)] = split_rows(rhs_basis[r].col(c).data(), R_, C_);
      }
      const bool kron = path_ == Path::kKronecker;
      if (!kron && transformed.size() != used) {
        transformed = std::vector<std::array<RowForm, 3>>(used);
        for (std::size_t r = 0; r < used; ++r)
          for (int c = 0; c < 3; ++c) {
            transformed[r][std::size_t(c)] = physical[r][std::size_t(c)];
            transform_rows(transformed[r][std::size_t(c)]);
          }
      }
      const auto& basis = kron ? physical : transformed;
      std::array<RowForm, 3> forms;
      for (int c = 0; c < 3; ++c) {
        std::vector<const RowForm*> parts;
        for (std::size_t r = 0; r < used; ++r) parts.push_back(&basis[r][std::size_t(c)]);
        forms[std::size_t(c)] = kron ? combine(parts, w, R_, unit_e0_, unit_e1_)
                                     : combine(parts, w, R_, sine_e0_, sine_e1_);
      }
      if (!kron) {
        solve_transform(forms, X);
      } else {
        for (int c = 0; c < 3; ++c) {
          if (int(forms[std::size_t(c)].dense_rows.size()) <= kMaxRank) {
            solve_kronecker_rank(forms[std::size_t(c)], X.col(c).data());
          } else {
            if (!have_B) materialize();
            have_B = true;
            solve_kronecker_dense(B.col(c).data(), X.col(c).data());
          }
        }
      }
    }
    result.solve_seconds = seconds_since(start);
    if (options_.compute_residual) {
      if (!have_B) materialize();
      judge_exact_solve(member.op, B, X, result);
    }
    sink(k, X, result);
  }
}

}  // namespace

std::unique_ptr<LinearSolver> make_fast_solver(const SolverOptions& options) {
  return std::make_unique<FastSolver>(options);
}

}  // namespace coons::solvers
