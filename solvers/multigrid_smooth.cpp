// The line smoother of Multigrid (multigrid.h): factorisation of the row and column line blocks
// and the multicolour line Gauss–Seidel sweeps.
//
// Lines of one direction are coloured by their index (counted from the first line with a free
// point) modulo radius + 1: lines of one colour are further apart than the stencil reaches, so
// they do not couple and are solved together (a block Gauss–Seidel step over all lines of the
// colour). This makes the result independent of the order and of the number of threads, lets the
// column solves run across adjacent columns (contiguous in memory, no dependency between them) and
// the row solves interleave several rows (independent recurrences instead of one latency chain).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "multigrid_kernels.h"

// The loop over independent line groups on loop_threads(L) threads (a local `nt`).
#if defined(_OPENMP)
#define COONS_PARALLEL_LINES _Pragma("omp parallel for num_threads(nt) if (nt > 1) schedule(static)")
#else
#define COONS_PARALLEL_LINES
#endif

namespace coons::solvers::mg_detail {

namespace {

constexpr int kRowGroup = 8;         // rows of one colour solved together (interleaved recurrences)
constexpr int kMinColumnBlock = 32;  // columns of one colour per task of the column sweep, at least

// Banded LU without pivoting of an n × n matrix of half-bandwidth r, stored by rows:
// band[t·(2r+1) + k + r] = M(t, t + k). False on a zero (or non-finite) pivot.
bool band_factor(double* band, int n, int r) {
  const int w = 2 * r + 1;
  double scale = 0;
  for (int t = 0; t < n * w; ++t) scale = std::max(scale, std::abs(band[t]));
  for (int t = 0; t < n; ++t) {
    const double pivot = band[t * w + r];
    if (!std::isfinite(pivot) || std::abs(pivot) <= 1e-14 * scale) return false;
    for (int k = 1; k <= r && t + k < n; ++k) {
      double& l = band[(t + k) * w + r - k];
      l /= pivot;
      for (int s = 1; s <= r && t + s < n; ++s) band[(t + k) * w + r + s - k] -= l * band[t * w + r + s];
    }
  }
  return true;
}

// The first index ≥ 0 of colour c in a direction. Colour 0 starts one line after the first free
// one: at radius 1 these are the lines of the coarse points (multigrid.h), relaxed first, so the
// pre-smoothing ends on the other lines (8 V-cycles instead of 12 on the 5-point Laplacian).
int first_of_colour(int first_free, int colour, int colours) { return (first_free + 1 + colour) % colours; }

// Rows first, first + s, … (count of them) of colour c: residual, banded solve along j, update.
template <int kR, bool kConst>
void solve_row_group(const Level& L, const double* b, double* x, double* d, const int* rows, int count) {
  const int r = radius_of<kR>(L), C = L.cols;
  const double* lower[kRowGroup];
  const double* upper[kRowGroup];
  const double* inv[kRowGroup];
  for (int g = 0; g < count; ++g) {
    const Eigen::Index u = L.row_lu.line[std::size_t(rows[g])];
    lower[g] = L.row_lu.lower.data() + u * r * C;
    upper[g] = L.row_lu.upper.data() + u * r * C;
    inv[g] = L.row_lu.inv_pivot.data() + u * C;
  }
  for (int g = 0; g < count; ++g) eval_row<kR, kConst, false>(L, b, x, d + Eigen::Index(rows[g]) * C, rows[g], 0, C, 1);
  for (int t = 0; t < C; ++t)
    for (int g = 0; g < count; ++g) {
      const Eigen::Index p = Eigen::Index(rows[g]) * C + t;
      double y = d[p];
      for (int k = 1; k <= std::min(r, t); ++k) y -= lower[g][(k - 1) * C + t] * d[p - k];
      d[p] = y;
    }
  for (int t = C - 1; t >= 0; --t)
    for (int g = 0; g < count; ++g) {
      const Eigen::Index p = Eigen::Index(rows[g]) * C + t;
      double y = d[p];
      for (int k = 1; k <= std::min(r, C - 1 - t); ++k) y -= upper[g][(k - 1) * C + t] * d[p + k];
      d[p] = y * inv[g][t];
    }
  for (int g = 0; g < count; ++g) {
    const Eigen::Index base = Eigen::Index(rows[g]) * C;
    for (int t = 0; t < C; ++t) x[base + t] += d[base + t];
  }
}

// Columns first, first + step, … < end (K of them): residual, banded solve along i, update. d
// holds the block's K columns side by side (row i at d + i·K), so the eliminations run over
// contiguous values; a run of columns with the same line factors (all interior columns of a
// rectangle) reads each factor once per row.
template <int kR, bool kConst>
void solve_column_block(const Level& L, const double* b, double* x, double* d, int first, int end, int step) {
  const int r = radius_of<kR>(L), R = L.rows, C = L.cols;
  const int K = (end - first + step - 1) / step;
  const double* lower = L.col_lu.lower.data();
  const double* upper = L.col_lu.upper.data();
  const double* inv = L.col_lu.inv_pivot.data();
  const int* line = L.col_lu.line.data();
  struct Run {
    int begin, end;    // of the block's columns, k = (j − first)/step
    Eigen::Index off;  // of the run's line factors: lower/upper + off·r·R, inv + off·R
  };
  std::vector<Run> runs;
  for (int k = 0; k < K; ++k) {
    const int u = line[first + k * step];
    if (runs.empty() || runs.back().off != u) runs.push_back({k, k, u});
    runs.back().end = k + 1;
  }
  for (int i = 0; i < R; ++i) {
    double* di = d + Eigen::Index(i) * K;
    eval_row<kR, kConst, false, true>(L, b, x, di, i, first, end, step);
    const int reach = std::min(r, i);
    for (const Run& run : runs) {
      const double* lo = lower + run.off * r * R + i;
      for (int k = run.begin; k < run.end; ++k) {
        double y = di[k];
        for (int s = 1; s <= reach; ++s) y -= lo[(s - 1) * R] * di[k - Eigen::Index(s) * K];
        di[k] = y;
      }
    }
  }
  for (int i = R - 1; i >= 0; --i) {
    double* di = d + Eigen::Index(i) * K;
    double* xi = x + Eigen::Index(i) * C + first;
    const int reach = std::min(r, R - 1 - i);
    for (const Run& run : runs) {
      const double* up = upper + run.off * r * R + i;
      const double pivot = inv[run.off * R + i];
      for (int k = run.begin; k < run.end; ++k) {
        double y = di[k];
        for (int s = 1; s <= reach; ++s) y -= up[(s - 1) * R] * di[k + Eigen::Index(s) * K];
        y *= pivot;
        di[k] = y;
        xi[Eigen::Index(k) * step] += y;
      }
    }
  }
}

void sweep_rows(const Level& L, const Vector& b, Vector& x, Vector& d, int colour) {
  const int colours = L.radius + 1;
  const int first = first_of_colour(L.first_i, colour, colours);
  const int lines = first < L.rows ? (L.rows - 1 - first) / colours + 1 : 0;
  const int groups = (lines + kRowGroup - 1) / kRowGroup;
  [[maybe_unused]] const int nt = loop_threads(L);
  dispatch(L, [&](auto radius, auto constant) {
    constexpr int kR = decltype(radius)::value;
    constexpr bool kConst = decltype(constant)::value;
    COONS_PARALLEL_LINES
    for (int g = 0; g < groups; ++g) {
      int rows[kRowGroup];
      const int count = std::min(kRowGroup, lines - g * kRowGroup);
      for (int m = 0; m < count; ++m) rows[m] = first + (g * kRowGroup + m) * colours;
      solve_row_group<kR, kConst>(L, b.data(), x.data(), d.data(), rows, count);
    }
  });
}

void sweep_columns(const Level& L, const Vector& b, Vector& x, Vector& d, int colour) {
  const int colours = L.radius + 1;
  const int first = first_of_colour(L.first_j, colour, colours);
  const int lines = first < L.cols ? (L.cols - 1 - first) / colours + 1 : 0;
  // One block of columns per thread: long stretches of each grid row, which the hardware
  // prefetcher follows (narrow blocks jump to a new page at every row).
  [[maybe_unused]] const int nt = loop_threads(L);
  const int blocks = std::max(1, std::min(nt, lines / kMinColumnBlock));
  const int per_block = (lines + blocks - 1) / blocks;
  dispatch(L, [&](auto radius, auto constant) {
    constexpr int kR = decltype(radius)::value;
    constexpr bool kConst = decltype(constant)::value;
    COONS_PARALLEL_LINES
    for (int k = 0; k < blocks; ++k) {  // block k's columns side by side at d + k·per_block·rows
      const int begin = first + k * per_block * colours;
      const int end = std::min(L.cols, begin + per_block * colours);
      double* dk = d.data() + Eigen::Index(k) * per_block * L.rows;
      if (begin < end) solve_column_block<kR, kConst>(L, b.data(), x.data(), dk, begin, end, colours);
    }
  });
}

}  // namespace

// The line blocks: along a row (i fixed) or a column (j fixed); fixed points become identity rows.
bool factor_lines(Level& L) {
  const int r = L.radius, w = L.width(), R = L.rows, C = L.cols;
  L.first_i = R;
  L.first_j = C;
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j)
      if (L.free[std::size_t(i) * C + j]) {
        L.first_i = std::min(L.first_i, i);
        L.first_j = std::min(L.first_j, j);
      }
  std::vector<double> band, lower, upper, inv;
  // One line: its n points p(t) = start + t·stride; along = offset of the neighbour k along it in
  // the stencil (1 for a row, width for a column). Its factors go to lu as a new distinct line
  // unless an earlier line has the same block (found by a hash of its bytes; blocks[u] is the
  // block of distinct line u), which is then not factored again.
  std::unordered_map<std::uint64_t, int> seen;
  std::vector<std::vector<double>> blocks;
  auto hash = [](const std::vector<double>& v, std::uint64_t h) {
    for (double value : v) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      h = (h ^ bits) * 1099511628211ULL;
    }
    return h;
  };
  auto factor_line = [&](Level::LineLU& lu, int m, Eigen::Index start, Eigen::Index stride, int n, int along) {
    band.assign(std::size_t(n) * w, 0.0);
    for (int t = 0; t < n; ++t) {
      const Eigen::Index p = start + t * stride;
      double* row = &band[std::size_t(t) * w];
      if (!L.free[p]) {
        row[r] = 1;
        continue;
      }
      const double* a = L.at(p) + r * w + r;  // the stencil centre
      for (int k = -r; k <= r; ++k)
        if (t + k >= 0 && t + k < n && L.free[p + k * stride]) row[r + k] = a[k * along];
    }
    // A line whose block equals an earlier one's shares its factors (the hash picks the candidate,
    // the comparison decides): on a rectangle all lines but those near the boundary.
    const std::uint64_t key = hash(band, 1469598103934665603ULL);
    if (const auto it = seen.find(key); it != seen.end() && blocks[std::size_t(it->second)] == band) {
      lu.line[std::size_t(m)] = it->second;
      return true;
    }
    const int distinct = int(blocks.size());
    seen[key] = distinct;
    blocks.push_back(band);
    if (!band_factor(band.data(), n, r)) return false;
    lower.assign(std::size_t(n) * r, 0.0);
    upper.assign(std::size_t(n) * r, 0.0);
    inv.assign(std::size_t(n), 0.0);
    for (int t = 0; t < n; ++t) {
      for (int k = 1; k <= r; ++k) {
        lower[std::size_t(k - 1) * n + t] = band[std::size_t(t) * w + r - k];
        upper[std::size_t(k - 1) * n + t] = band[std::size_t(t) * w + r + k];
      }
      inv[std::size_t(t)] = 1.0 / band[std::size_t(t) * w + r];
    }
    lu.line[std::size_t(m)] = distinct;
    lu.lower.insert(lu.lower.end(), lower.begin(), lower.end());
    lu.upper.insert(lu.upper.end(), upper.begin(), upper.end());
    lu.inv_pivot.insert(lu.inv_pivot.end(), inv.begin(), inv.end());
    return true;
  };
  L.row_lu = {};
  L.col_lu = {};
  L.row_lu.line.assign(std::size_t(R), 0);
  L.col_lu.line.assign(std::size_t(C), 0);
  for (int i = 0; i < R; ++i)
    if (!factor_line(L.row_lu, i, Eigen::Index(i) * C, 1, C, 1)) return false;
  seen.clear();
  blocks.clear();
  for (int j = 0; j < C; ++j)
    if (!factor_line(L.col_lu, j, j, C, R, w)) return false;
  return true;
}

// Forward: rows of colour 0, 1, …, radius, then columns likewise. Backward (the adjoint): columns
// of colour radius … 0, then rows likewise. Each colour step is an exact block solve, so reversing
// the sequence gives the adjoint in the energy inner product: the V-cycle stays symmetric.
void smooth(const Level& L, const Vector& b, Vector& x, Vector& work, bool forward) {
  const int colours = L.radius + 1;
  work.resize(L.points());
  if (forward) {
    for (int c = 0; c < colours; ++c) sweep_rows(L, b, x, work, c);
    for (int c = 0; c < colours; ++c) sweep_columns(L, b, x, work, c);
  } else {
    for (int c = colours - 1; c >= 0; --c) sweep_columns(L, b, x, work, c);
    for (int c = colours - 1; c >= 0; --c) sweep_rows(L, b, x, work, c);
  }
}

}  // namespace coons::solvers::mg_detail
