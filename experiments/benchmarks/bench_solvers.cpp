// Solver benchmarks on the mask systems of docs/math.md §3: interior grids N×N, 3 right-hand sides.
// Every figure is meant to be read as a multiple of BM_MemoryPass at the same N, measured in the
// same run (scripts/bench.sh turns the JSON output into a table, a plot and scaling exponents).
//
//   bench_solvers [--sizes=63,127,...] [--alphas=-0.25,-0.1,0] [--backends=name,...] [--quick] [--large] [--hard]
//                 [--mg-iterations] [google benchmark flags, e.g. --benchmark_format=json]
//   bench_solvers --dump-mtx=DIR [--sizes=...] [--alphas=...]
//
// --dump-mtx writes, instead of running anything, every (N, α) system the suite times as
// DIR/mask_N<N>_alpha<α>.A.mtx and .B.mtx (Matrix Market, src/coons/io/matrix_market.h), so that
// other solvers (or `coons bench-matrix A.mtx B.mtx`) can rerun them.
//
// Default sizes per family keep the full run within minutes: direct backends up to 1023 (cholmod,
// umfpack; the slower simplicial and Eigen factorisations to 511),
// Krylov backends up to 255 (127 at α = −1/4, where CG needs O(N²) iterations), the classical
// mask iterations up to 63, structured backends up to 2047. The 5×5 set (BM_Stencil5: c1-coons,
// biharmonic, the c1 family at w = 0.5 on the full rectangle, and w = 0.5 with a hole, through
// separable-banded, fast5 and pcg-fast) runs at N = 127..511, and at 1023 with --large. --hard adds
// experiment E04 (BM_Hard: thirteen backends on the 5×5 problems, also an L-shape and a fixed line,
// each up to its hard_size_cap).
// The multigrid-class backends (mg, mg-cg,
// hypre-pfmg, hypre-smg) run up to 1023 at every α; hypre-amg up to 255 (127 at α = −1/4), and up
// to 1023 when --sizes asks for it (opt-in: it needs minutes at α = −1/4 from 255 on). --mg-iterations runs only
// BM_MgIterations: the iteration counts of mg, mg-cg, hypre-smg and hypre-pfmg at 1e−10 on the
// α family and the 5×5 set (scripts/bench_mg.sh puts them into docs/solvers.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/config.h"
#include "coons/io/matrix_market.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif
#include "coons/mask/assemble_mask_system.h"
#include "coons/net/coons_net.h"
#include "solvers/fast5_modes.h"
#include "solvers/registry.h"
#include "solvers/sine_transform.h"
#include "solvers/stencil_operator.h"

using namespace coons;
using namespace coons::solvers;

namespace {

struct Config {
  std::vector<int> sizes = {63, 127, 255, 511, 1023, 2047};
  std::vector<double> alphas = {-0.25, -0.1, 0.0};
  std::vector<std::string> backends;  // empty: all
  bool quick = false;
  bool large = false;          // the 5×5 set at N = 1023 too
  bool hard = false;           // experiment E04 (BM_Hard): every backend on the 5×5 problems
  bool mg_iterations = false;  // BM_MgIterations only (iteration counts of mg, mg-cg, hypre at 1e−10)
  bool sizes_given = false;    // --sizes: the multigrid-class backends run up to 1023
  std::string dump_dir;        // --dump-mtx: write the systems there and run nothing
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// A boundary whose net has an N×N interior: a smooth closed-form shape plus noise-free
// oscillation, so that all three coordinates carry data.
Boundary bench_boundary(int N) {
  const int m = N + 1, n = N + 1;
  ControlNet net(m, n);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = double(i) / m, v = double(j) / n;
      net.at(i, j) << u, v, std::sin(3 * u) * std::cos(2 * v) + 0.1 * std::sin(17 * u * v);
    }
  return boundary_of(net, "bench");
}

// The data of one (N, α) problem, built once and shared by every benchmark that needs it.
struct Problem {
  ControlNet frame;
  MaskSystem system;
};

const Problem& problem(int N, double alpha, bool with_matrix) {
  static std::map<std::tuple<int, double, bool>, Problem> cache;
  auto key = std::make_tuple(N, alpha, with_matrix);
  auto it = cache.find(key);
  if (it == cache.end()) {
    Problem p;
    p.frame = frame_net(bench_boundary(N));
    p.system = assemble_mask_system(p.frame, alpha_mask(alpha), with_matrix);
    it = cache.emplace(key, std::move(p)).first;
  }
  return it->second;
}

LinearOperator operator_of(const MaskSystem& s, bool with_matrix) {
  LinearOperator op;
  if (with_matrix) op.matrix = &s.A;
  op.stencil = s.stencil;
  return op;
}

void set_common_counters(benchmark::State& state, int N) {
  state.counters["unknowns"] = double(N) * N;
  state.counters["N"] = N;
}

// The physical floor: read the 3 right-hand-side columns, write the 3 solution columns.
void BM_MemoryPass(benchmark::State& state, int N) {
  const Problem& p = problem(N, -0.25, false);
  Eigen::MatrixX3d X(p.system.B.rows(), 3);
  for (auto _ : state) {
    X = p.system.B;
    benchmark::DoNotOptimize(X.data());
    benchmark::ClobberMemory();
  }
  set_common_counters(state, N);
}

#if COONS_HAVE_FFTW
// The timed loop of a floor benchmark: work(t) on `threads` threads (t = 0 on this one), X its
// output.
template <class Work>
void time_on_threads(benchmark::State& state, int N, int threads, const Work& work, const Eigen::MatrixX3d& X) {
  for (auto _ : state) {
    std::vector<std::thread> others;
    others.reserve(std::size_t(threads));
    for (int t = 1; t < threads; ++t) others.emplace_back(work, t);
    work(0);
    for (std::thread& other : others) other.join();
    benchmark::DoNotOptimize(X.data());
    benchmark::ClobberMemory();
  }
  set_common_counters(state, N);
  state.SetLabel("threads=" + std::to_string(threads));
}

// A floor for the transform solvers: the inverse sine transform of every row of the three columns
// of an N × N solution (solvers/sine_transform.h, the planner flag `fast` uses by default) and the
// write of the result, nothing else, on `threads` threads taking rows in turn. A `fast` solve does
// this and its eliminations; so does each member of its α sweep. scripts/mg_report.py sets it
// beside their targets.
void BM_SineRows(benchmark::State& state, int N, int threads) {
  const Problem& p = problem(N, -0.25, false);
  const Eigen::MatrixX3d& B = p.system.B;  // any values: the transform's cost does not depend on them
  Eigen::MatrixX3d X(B.rows(), 3);
  const std::size_t n = std::size_t(N);
  std::vector<detail::SineTransform> transforms;
  transforms.reserve(std::size_t(threads));
  for (int t = 0; t < threads; ++t) transforms.emplace_back(N, detail::fft_planning(SolverOptions{}));
  std::vector<std::vector<double>> rows(std::size_t(threads), std::vector<double>(n, 0.0));
  auto work = [&](int t) {
    for (int u = t; u < 3 * N; u += threads) {
      const Eigen::Index c = u / N, i = u % N;
      transforms[std::size_t(t)].apply(B.col(c).data() + i * N, rows[std::size_t(t)].data(), 1.0);
      detail::stream_copy(rows[std::size_t(t)].data(), X.col(c).data() + i * N, n);
    }
    detail::stream_fence();
  };
  time_on_threads(state, N, threads, work, X);
}

// The other half of fast5's floor: one banded sweep of the grid (down and up every mode's
// pentadiagonal LDLᵀ, factored before the loop, for the three columns of an N × N right-hand
// side, written into X; solvers/fast5_modes.h), nothing else, on `threads` threads taking chunks of
// 128 modes in turn. A fast5 solve on mask data does this once (its second sweep, the lowest modes
// in closed form instead) and one row transform (BM_SineRows), besides its set-up and capacitance
// solve; scripts/mg_report.py sets their sum beside its target.
void BM_Fast5Sweep(benchmark::State& state, int N, int threads) {
  const Problem& p = problem(N, -0.25, false);
  const Eigen::MatrixX3d& B = p.system.B;  // any values: the sweep's cost does not depend on them
  Eigen::MatrixX3d X(B.rows(), 3);
  const fast5_detail::ModeFactors f =
      fast5_detail::factor_modes(0, 1, fast5_detail::second_difference_eigenvalues(N), N, 1);  // biharmonic
  const std::vector<double> zeros(std::size_t(N), 0.0);
  fast5_detail::SweepInput in;
  in.hats = {B.col(0).data(), B.col(1).data(), B.col(2).data()};
  in.t_even = zeros.data();
  in.t_odd = zeros.data();
  fast5_detail::ChunkOutput out;
  out.grid = {X.col(0).data(), X.col(1).data(), X.col(2).data()};
  constexpr int kChunk = 128;
  const int chunks = (N + kChunk - 1) / kChunk;
  const Eigen::MatrixXd no_sines(N, 0);
  auto work = [&](int t) {
    std::vector<double> buf(3 * std::size_t(N) * kChunk);
    Eigen::MatrixXd dots;
    for (int k = t; k < chunks; k += threads)
      fast5_detail::solve_chunk(f, k * kChunk, std::min(N, (k + 1) * kChunk), 3, in, out, buf.data(), no_sines, dots);
  };
  time_on_threads(state, N, threads, work, X);
}
#endif

void BM_Assemble(benchmark::State& state, int N) {
  const ControlNet& frame = problem(N, -0.25, false).frame;
  for (auto _ : state) {
    MaskSystem s = assemble_mask_system(frame, alpha_mask(-0.1), true);
    benchmark::DoNotOptimize(s.A.valuePtr());
  }
  set_common_counters(state, N);
}

void BM_RefillValues(benchmark::State& state, int N) {
  MaskSystem s = problem(N, -0.25, true).system;
  const GridStencil other = mask_stencil(alpha_mask(-0.1), N, N);
  for (auto _ : state) {
    refill_stencil_matrix(other, s.A);
    benchmark::DoNotOptimize(s.A.valuePtr());
  }
  set_common_counters(state, N);
}

void BM_ClosedFormCoons(benchmark::State& state, int N) {
  const Boundary b = bench_boundary(N);
  for (auto _ : state) {
    ControlNet net = discrete_coons_net(b);
    benchmark::DoNotOptimize(net.points.data());
  }
  set_common_counters(state, N);
}

// SolverOptions::threads: the structured and mg rows run at 1 and 2 (label threads=K).
bool threaded(const std::string& name) {
  const SolverInfo* info = find_solver(name);
  return info && (info->family == SolverFamily::kStructured || name == "mg" || name == "mg-cg");
}

// One fresh solve: analyze + factorize + solve (the residual is computed once, untimed).
void BM_Solve(benchmark::State& state, const std::string& name, int N, double alpha, int threads = 1) {
  const SolverInfo* info = find_solver(name);
  std::string backend = name;
  if (name == "auto") backend = choose_auto_solver(mask_stencil(alpha_mask(alpha), N, N));
  if (!info) info = find_solver(backend);
  const Problem& p = problem(N, alpha, info->needs_matrix);
  const LinearOperator op = operator_of(p.system, info->needs_matrix);
  SolverOptions timed;
  timed.compute_residual = false;
  timed.threads = threads;
  Eigen::MatrixX3d X;
  SolveSummary s;
  // Structured backends plan their FFTs once per size per process (FFTW keeps the wisdom): one
  // untimed solve first, so that every timed solve is a fresh solver at steady state.
  if (find_solver(backend)->family == SolverFamily::kStructured)
    make_solver(backend, timed)->compute_and_solve(op, p.system.B, X);
  for (auto _ : state) {
    auto solver = make_solver(backend, timed);
    s = solver->compute_and_solve(op, p.system.B, X);
    benchmark::DoNotOptimize(X.data());
  }
  // the true residual of the last timed solution, computed outside the timing
  s.relative_residual = relative_residual(op, p.system.B, X);
  set_common_counters(state, N);
  state.counters["alpha"] = alpha;
  state.counters["iterations"] = s.iterations;
  state.counters["residual"] = s.relative_residual;
  state.counters["factor_nnz"] = double(s.factor_nnz);
  state.counters["ok"] = s.ok();
  state.counters["threads"] = threads;
  state.SetLabel(backend + (s.ordering.empty() ? "" : " ordering=" + s.ordering) +
                 (threaded(backend) ? " threads=" + std::to_string(threads) : "") +
                 (s.ok() ? "" : std::string(" status=") + to_string(s.status)));
}

// Analysis reused: only factorize + solve per α (what an α search pays per evaluation).
void BM_Refactorize(benchmark::State& state, const std::string& name, int N, double alpha) {
  const SolverInfo* info = find_solver(name);
  const Problem& p = problem(N, alpha, info->needs_matrix);
  const LinearOperator op = operator_of(p.system, info->needs_matrix);
  SolverOptions timed;
  timed.compute_residual = false;
  auto solver = make_solver(name, timed);
  solver->analyze(op);
  Eigen::MatrixX3d X;
  for (auto _ : state) {
    solver->factorize(op);
    solver->solve(p.system.B, X);
    benchmark::DoNotOptimize(X.data());
  }
  set_common_counters(state, N);
  state.counters["alpha"] = alpha;
}

// 101 values of α in [−1/4, 1/4] through the sweep API (right-hand side affine in α).
void BM_AlphaSweep(benchmark::State& state, const std::string& name, int N, int threads = 1) {
  const SolverInfo* info = find_solver(name);
  const Problem& p = problem(N, -0.25, info->needs_matrix);
  // B(α) = α·B_diag + β·B_edge: the two basis right-hand sides
  const std::vector<Eigen::MatrixX3d> basis = {mask_rhs(p.frame, Mask9{0, 0, 1}),
                                               mask_rhs(p.frame, Mask9{0.5, 0.5, 0})};
  std::vector<GridStencil> stencils;
  std::vector<Eigen::SparseMatrix<double>> matrices;
  std::vector<LinearSolver::SweepMember> members;
  for (int k = 0; k <= 100; ++k) stencils.push_back(mask_stencil(alpha_mask(-0.25 + 0.005 * k), N, N));
  if (info->needs_matrix)
    for (const auto& s : stencils) matrices.push_back(stencil_matrix(s));
  for (int k = 0; k <= 100; ++k) {
    LinearOperator op;
    op.stencil = stencils[k];
    if (info->needs_matrix) op.matrix = &matrices[k];
    const double alpha = -0.25 + 0.005 * k;
    members.push_back({op, {alpha, (0.25 - alpha) * 2}});  // basis[1] holds edge sums × 1/2
  }
  SolverOptions timed;
  timed.compute_residual = false;
  timed.threads = threads;
  double checksum = 0;
  for (auto _ : state) {
    auto solver = make_solver(name, timed);
    solver->sweep(basis, members,
                  [&](std::size_t, const Eigen::MatrixX3d& X, const SolveSummary&) { checksum += X(0, 0); });
  }
  benchmark::DoNotOptimize(checksum);
  set_common_counters(state, N);
  state.counters["alphas"] = 101;
  state.counters["threads"] = threads;
  if (threaded(name)) state.SetLabel(name + " threads=" + std::to_string(threads));
}

// CHOLMOD supernodal with each ordering it offers (α = −1/4, fresh solve), so the `cholmod`
// backend's choice can be checked against the best one in the same run.
void BM_CholmodOrdering(benchmark::State& state, Ordering ordering, int N) {
  const Problem& p = problem(N, -0.25, true);
  const LinearOperator op = operator_of(p.system, true);
  SolverOptions options;
  options.compute_residual = false;
  options.ordering = ordering;
  Eigen::MatrixX3d X;
  SolveSummary s;
  for (auto _ : state) {
    auto solver = make_solver("cholmod", options);
    s = solver->compute_and_solve(op, p.system.B, X);
    benchmark::DoNotOptimize(X.data());
  }
  set_common_counters(state, N);
  state.counters["factor_nnz"] = double(s.factor_nnz);
  state.SetLabel("ordering=" + s.ordering);
}

// A whole α search (coarse scan + Ceres, discrete thin-plate objective) to be read as a multiple
// of one solve of the same backend at the same N: `solve` evaluates each α by factorize + solves
// (its last evaluation holds the optimal net); `spectral` in the sine basis, set-up included, after
// which the optimal net costs one more solve: the report adds that solve at its measured cost.
void BM_SearchAlpha(benchmark::State& state, const std::string& name, int N, bool spectral) {
  const Boundary b = bench_boundary(N);
  std::string why;
  const Objective objective = *parse_objective("discrete_thin_plate", &why);
  AlphaSearchSummary s;
  {  // plan the FFTs once (as BM_Solve does)
    Eigen::MatrixX3d X;
    const Problem& p = problem(N, -0.1, false);
    make_solver(name)->compute_and_solve(operator_of(p.system, false), p.system.B, X);
  }
  SolverOptions options;
  options.compute_residual = false;
  for (auto _ : state) {
    if (spectral) {
#if COONS_HAVE_FFTW
      SpectralAlphaSearchObjective f(b, objective);
      s = search_mask_parameter(f);
#endif
    } else {
      MaskObjective f(
          b, objective, [](double a) { return alpha_family(a); }, *find_solver(name), options);
      s = search_mask_parameter(f);
    }
    benchmark::DoNotOptimize(s.value);
  }
  set_common_counters(state, N);
  state.counters["evaluations"] = s.evaluations;
  state.counters["solves"] = s.solves;
  state.counters["alpha_opt"] = s.parameter.value_or(NAN);
  state.SetLabel(name + (spectral ? " spectral " : " solve ") + to_string(s.status));
}

// The 5×5 problems: w·C + (1−w)·T on the N×N free points of a net with two data rings, every point
// free, or (hole) a centred square of side N/4 fixed too; the right-hand side is that of a mask
// system: the fixed points' values (a smooth surface, x, y and z) moved to the right-hand side.
struct Stencil5Problem {
  StencilOperator op;
  Eigen::MatrixX3d B;
  Eigen::SparseMatrix<double> A;  // assembled on demand (BM_Hard)
};

// kHole: a centred square of side N/4 fixed; kLShape: the quarter i, j ≥ N/2 fixed; kLine: the
// row i = N/2 fixed from j = N/8 to 7N/8 (an interior curve held).
enum class FreeShape { kFull, kHole, kLShape, kLine };

Stencil5Problem& stencil5_problem(double w, FreeShape shape, int N) {
  static std::map<std::tuple<double, FreeShape, int>, Stencil5Problem> cache;
  const auto key = std::make_tuple(w, shape, N);
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const double d4[5] = {1, -4, 6, -4, 1}, d2[5] = {0, 1, -2, 1, 0}, e[5] = {0, 0, 1, 0, 0};
  std::vector<double> weights(25);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      weights[std::size_t(i) * 5 + std::size_t(j)] =
          (w * d4[i] * d4[j] + (1 - w) * (d4[i] * e[j] + 2 * d2[i] * d2[j] + e[i] * d4[j])) / (20 + 16 * w);
  Stencil5Problem p;
  p.op = make_stencil_operator(N, N, weights);
  if (shape != FreeShape::kFull) {
    p.op.free.assign(std::size_t(N) * std::size_t(N), 1);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) {
        bool fixed = false;
        if (shape == FreeShape::kHole)
          fixed = i >= 3 * N / 8 && i < 3 * N / 8 + N / 4 && j >= 3 * N / 8 && j < 3 * N / 8 + N / 4;
        if (shape == FreeShape::kLShape) fixed = i >= N / 2 && j >= N / 2;
        if (shape == FreeShape::kLine) fixed = i == N / 2 && j >= N / 8 && j < N - N / 8;
        if (fixed) p.op.free[std::size_t(i) * std::size_t(N) + std::size_t(j)] = 0;
      }
  }
  // point (i, j) of the N×N grid is (i + 2, j + 2) of the (N + 4)² net
  const auto value = [N](int i, int j, int c) {
    const double u = double(i + 2) / (N + 3), v = double(j + 2) / (N + 3);
    return c == 0 ? u : c == 1 ? v : std::sin(3 * u) * std::cos(2 * v) + 0.1 * std::sin(17 * u * v);
  };
  const std::vector<Eigen::Index> number = free_numbering(p.op);
  p.B.setZero(p.op.size(), 3);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const Eigen::Index row = number[std::size_t(i) * std::size_t(N) + std::size_t(j)];
      if (row < 0) continue;
      for (int di = -2; di <= 2; ++di)
        for (int dj = -2; dj <= 2; ++dj) {
          const int ii = i + di, jj = j + dj;
          const bool inside = ii >= 0 && ii < N && jj >= 0 && jj < N;
          if (inside && number[std::size_t(ii) * std::size_t(N) + std::size_t(jj)] >= 0) continue;  // free
          for (int c = 0; c < 3; ++c) p.B(row, c) -= p.op.weight(di, dj) * value(ii, jj, c);
        }
    }
  return cache.emplace(key, std::move(p)).first->second;
}

// One fresh solve (analyze + factorize + solve) of a 5×5 problem, from the grid operator only, on
// `threads` threads (SolverOptions::threads; label threads=K for the structured backends).
void BM_Stencil5(benchmark::State& state, const std::string& name, double w, bool hole, int N, int threads) {
  const Stencil5Problem& p = stencil5_problem(w, hole ? FreeShape::kHole : FreeShape::kFull, N);
  LinearOperator op;
  op.grid = &p.op;
  SolverOptions timed;
  timed.compute_residual = false;
  timed.threads = threads;
  Eigen::MatrixX3d X;
  SolveSummary s = make_solver(name, timed)->compute_and_solve(op, p.B, X);  // plans the FFTs
  for (auto _ : state) {
    auto solver = make_solver(name, timed);
    s = solver->compute_and_solve(op, p.B, X);
    benchmark::DoNotOptimize(X.data());
  }
  s.relative_residual = relative_residual(op, p.B, X);
  set_common_counters(state, N);
  state.counters["w"] = w;
  state.counters["iterations"] = s.iterations;
  state.counters["residual"] = s.relative_residual;
  state.counters["ok"] = s.ok();
  state.counters["threads"] = threads;
  state.SetLabel(name + (threaded(name) ? " threads=" + std::to_string(threads) : "") +
                 (s.ok() ? "" : std::string(" status=") + to_string(s.status)));
}

// The largest N at which E04 (BM_Hard) runs a backend, so that one run of the whole experiment
// stays within about 20 minutes on 2 cores: the sparse direct factors of a 25-point stencil fill
// like N³ (`cholmod` took 4–83 s per solve at 511; `eigen-ldlt` and `umfpack` are slower than it
// at every N up to 255), plain `cg` stops at the 10 s limit from 127 on, BoomerAMG stops at 255
// too (its set-up is not bound by the limit, and it needs minutes at α = −1/4 on 3×3 masks from 255
// on, E03), and the multigrid-class
// backends and `pcg-fast` are stopped by that limit where they do not finish, so they run to 1023;
// only the exact structured solvers fit 2047 in a few seconds.
int hard_size_cap(const std::string& backend) {
  if (backend == "cholmod") return 511;
  if (backend == "eigen-ldlt" || backend == "umfpack" || backend == "cg" || backend == "hypre-amg") return 255;
  if (backend == "fast5" || backend == "separable-banded") return 2047;
  return 1023;
}

// Experiment E04: every backend on the 5×5 problems (matrix and grid operator both given), one
// fresh solve, iterative ones stopped after 10 s (`mg-cg` and `gmres` at N ≥ 1023: 60 s), reported
// as not_converged.
void BM_Hard(benchmark::State& state, const std::string& name, double w, FreeShape shape, int N) {
  Stencil5Problem& p = stencil5_problem(w, shape, N);
  // Both forms up to 1023 (gmres and pcg-fast use the matrix when given); at 2047 only the
  // structured solvers run, from the grid operator, without a 1.2 GB matrix.
  const bool needs_matrix = N <= 1023 || find_solver(name)->needs_matrix;
  if (needs_matrix && p.A.rows() == 0) p.A = stencil_operator_matrix(p.op);
  LinearOperator op;
  if (needs_matrix) op.matrix = &p.A;
  op.grid = &p.op;
  SolverOptions timed;
  timed.compute_residual = false;
  // 10 s; 60 s for the multigrid-preconditioned Krylov backends at N ≥ 1023, where `mg-cg` needs
  // about 30 s on the biharmonic (docs/solvers.md) and 10 s would only say it had not finished
  timed.time_limit_seconds = N >= 1023 && (name == "mg-cg" || name == "gmres") ? 60 : 10;
  Eigen::MatrixX3d X;
  SolveSummary s;
  if (find_solver(name)->family == SolverFamily::kStructured) make_solver(name, timed)->compute_and_solve(op, p.B, X);
  for (auto _ : state) {
    s = make_solver(name, timed)->compute_and_solve(op, p.B, X);
    benchmark::DoNotOptimize(X.data());
  }
  s.relative_residual = X.rows() == p.B.rows() ? relative_residual(op, p.B, X) : NAN;
  set_common_counters(state, N);
  state.counters["w"] = w;
  state.counters["iterations"] = s.iterations;
  state.counters["residual"] = s.relative_residual;
  state.counters["ok"] = s.ok();
  state.SetLabel(name + " status=" + to_string(s.status));
}

// Iteration counts of the multigrid-class backends (--mg-iterations): one fresh solve of the three
// right-hand sides to relative residual 1e−10 (the target of issue 14), from the grid operator.
// problem: "alpha" (the mask system at α) or "c1-coons" / "biharmonic" (the 5×5 set, w = 1 / 0).
void BM_MgIterations(benchmark::State& state, const std::string& name, const std::string& problem_name, double alpha,
                     int N) {
  LinearOperator op;
  const Eigen::MatrixX3d* B = nullptr;
  if (problem_name == "alpha") {
    const Problem& p = problem(N, alpha, false);
    op.stencil = p.system.stencil;
    B = &p.system.B;
  } else {
    const Stencil5Problem& p = stencil5_problem(problem_name == "c1-coons" ? 1.0 : 0.0, FreeShape::kFull, N);
    op.grid = &p.op;
    B = &p.B;
  }
  SolverOptions options;
  options.tolerance = 1e-10;
  options.compute_residual = false;
  Eigen::MatrixX3d X;
  SolveSummary s;
  for (auto _ : state) {
    s = make_solver(name, options)->compute_and_solve(op, *B, X);
    benchmark::DoNotOptimize(X.data());
  }
  set_common_counters(state, N);
  state.counters["alpha"] = alpha;
  state.counters["iterations"] = s.iterations;
  state.counters["residual"] = X.rows() == B->rows() ? relative_residual(op, *B, X) : NAN;
  state.counters["ok"] = s.ok();
  state.SetLabel(name + " " + (problem_name == "alpha" ? "alpha=" + std::to_string(alpha).substr(0, 5) : problem_name) +
                 " status=" + to_string(s.status));
}

bool multigrid_class(const std::string& name) {
  return name == "mg" || name == "mg-cg" || name.rfind("hypre-", 0) == 0;
}

// The systems BM_Solve times (the same boundary, mask and assembly), as Matrix Market files.
int dump_systems(const Config& config) {
  std::filesystem::create_directories(config.dump_dir);
  for (int N : config.sizes)
    for (double alpha : config.alphas) {
      const Problem& p = problem(N, alpha, true);
      std::ostringstream name;
      name << config.dump_dir << "/mask_N" << N << "_alpha" << alpha;
      try {
        write_matrix_market(name.str() + ".A.mtx", p.system.A);
        write_dense_matrix_market(name.str() + ".B.mtx", p.system.B);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 2;
      }
      std::printf("%s.A.mtx, %s.B.mtx: %lld unknowns, 3 right-hand sides\n", name.str().c_str(), name.str().c_str(),
                  static_cast<long long>(p.system.A.rows()));
    }
  return 0;
}

int size_cap(const SolverInfo& info, double alpha, const Config& config) {
  if (info.family == SolverFamily::kStructured) return 2047;
  // mg, mg-cg and hypre's Struct multigrid take seconds at 1023; BoomerAMG needs minutes at α = −1/4
  // from 255 on, so it stops at 255 (127 at α = −1/4) unless --sizes asks for more.
  if (info.name == "hypre-amg" && !config.sizes_given) return alpha <= -0.25 ? 127 : 255;
  if (multigrid_class(info.name)) return 1023;
  // The supernodal CHOLMOD and UMFPACK run to 1023; the simplicial and Eigen factorisations, 5–9×
  // slower there (26–45 s per solve), stop at 511 so that the whole suite stays near 15 minutes.
  if (info.family == SolverFamily::kDirect) return info.name == "cholmod" || info.name == "umfpack" ? 1023 : 511;
  if (info.name == "jacobi" || info.name == "gauss-seidel") return 63;
  return alpha <= -0.25 ? 127 : 255;
}

// The BM_MgIterations set: mg at α = 0 and −0.1, mg-cg at every α and on c1-coons and biharmonic,
// hypre-smg and hypre-pfmg beside them on the 3×3 systems.
void register_mg_iterations(const Config& config) {
  struct Case {
    const char* backend;
    const char* problem;
    double alpha;
  };
  const std::vector<Case> cases = {
      {"mg", "alpha", 0.0},          {"mg", "alpha", -0.1},        {"mg-cg", "alpha", 0.0},
      {"mg-cg", "alpha", -0.1},      {"mg-cg", "alpha", -0.25},    {"mg-cg", "c1-coons", 0},
      {"mg-cg", "biharmonic", 0},    {"hypre-smg", "alpha", 0.0},  {"hypre-smg", "alpha", -0.1},
      {"hypre-smg", "alpha", -0.25}, {"hypre-pfmg", "alpha", 0.0}, {"hypre-pfmg", "alpha", -0.1},
      {"hypre-pfmg", "alpha", -0.25}};
  for (int N : config.sizes)
    for (const Case& c : cases) {
      // c1-coons at N = 1023 (κ ≈ 2.6e22 > 1/ε): mg-cg took 112 iterations and 70 s with the
      // rounded weights, 20 and 15 s since multigrid keeps its integer factors (2026-12-02).
      if (!find_solver(c.backend) ||
          (!config.backends.empty() &&
           std::find(config.backends.begin(), config.backends.end(), c.backend) == config.backends.end()))
        continue;
      const std::string what =
          std::string(c.problem) == "alpha" ? "alpha:" + std::to_string(c.alpha).substr(0, 5) : std::string(c.problem);
      benchmark::RegisterBenchmark(("BM_MgIterations/" + what + "/" + c.backend + "/N:" + std::to_string(N)).c_str(),
                                   BM_MgIterations, std::string(c.backend), std::string(c.problem), c.alpha, N)
          ->UseRealTime()
          ->Iterations(1);
    }
}

}  // namespace

int main(int argc, char** argv) {
  Config config;
  std::vector<char*> rest = {argv[0]};
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&](const char* flag) { return arg.substr(std::strlen(flag)); };
    if (arg.rfind("--sizes=", 0) == 0) {
      config.sizes.clear();
      config.sizes_given = true;
      for (const auto& s : split(value("--sizes="))) config.sizes.push_back(std::stoi(s));
    } else if (arg.rfind("--alphas=", 0) == 0) {
      config.alphas.clear();
      for (const auto& s : split(value("--alphas="))) config.alphas.push_back(std::stod(s));
    } else if (arg.rfind("--backends=", 0) == 0) {
      config.backends = split(value("--backends="));
    } else if (arg == "--hard") {
      config.hard = true;
    } else if (arg == "--mg-iterations") {
      config.mg_iterations = true;
    } else if (arg == "--large") {
      config.large = true;
    } else if (arg.rfind("--dump-mtx=", 0) == 0) {
      config.dump_dir = value("--dump-mtx=");
    } else if (arg == "--quick") {
      config.quick = true;
      config.sizes = {15, 31};
    } else {
      rest.push_back(argv[a]);
    }
  }
  if (!config.dump_dir.empty()) return dump_systems(config);
  const double min_time = config.quick ? 0.01 : 0.2;
  auto wanted = [&](const std::string& name) {
    return config.backends.empty() ||
           std::find(config.backends.begin(), config.backends.end(), name) != config.backends.end();
  };

  if (config.mg_iterations) register_mg_iterations(config);
  for (int N : config.mg_iterations ? std::vector<int>{} : config.sizes) {
    benchmark::RegisterBenchmark(("BM_MemoryPass/N:" + std::to_string(N)).c_str(), BM_MemoryPass, N)->UseRealTime();
#if COONS_HAVE_FFTW
    if (wanted("fast") || wanted("dst"))
      for (int threads : {1, 2})
        benchmark::RegisterBenchmark(("BM_SineRows/N:" + std::to_string(N) + (threads > 1 ? "/threads:2" : "")).c_str(),
                                     BM_SineRows, N, threads)
            ->UseRealTime()
            ->MinTime(min_time);
    if (wanted("fast5"))
      for (int threads : {1, 2})
        benchmark::RegisterBenchmark(
            ("BM_Fast5Sweep/N:" + std::to_string(N) + (threads > 1 ? "/threads:2" : "")).c_str(), BM_Fast5Sweep, N,
            threads)
            ->UseRealTime()
            ->MinTime(min_time);
#endif
    benchmark::RegisterBenchmark(("BM_ClosedFormCoons/N:" + std::to_string(N)).c_str(), BM_ClosedFormCoons, N)
        ->UseRealTime();
    if (N <= 1023) {
      benchmark::RegisterBenchmark(("BM_Assemble/N:" + std::to_string(N)).c_str(), BM_Assemble, N)->UseRealTime();
      benchmark::RegisterBenchmark(("BM_RefillValues/N:" + std::to_string(N)).c_str(), BM_RefillValues, N)
          ->UseRealTime();
    }
    for (const SolverInfo& info : available_solvers()) {
      if (!wanted(info.name)) continue;
      if (info.name == "fast5" || info.name == "separable-banded") continue;  // 5×5 / separable: BM_Stencil5
      for (double alpha : config.alphas) {
        if (!config.quick && N > size_cap(info, alpha, config)) continue;
        const std::string tag =
            "/" + info.name + "/N:" + std::to_string(N) + "/alpha:" + std::to_string(alpha).substr(0, 6);
        benchmark::RegisterBenchmark(("BM_Solve" + tag).c_str(), BM_Solve, info.name, N, alpha, 1)
            ->UseRealTime()
            ->MinTime(min_time);
        if (threaded(info.name))
          benchmark::RegisterBenchmark(("BM_Solve" + tag + "/threads:2").c_str(), BM_Solve, info.name, N, alpha, 2)
              ->UseRealTime()
              ->MinTime(min_time);
        if (info.family != SolverFamily::kIterative)
          benchmark::RegisterBenchmark(("BM_Refactorize" + tag).c_str(), BM_Refactorize, info.name, N, alpha)
              ->UseRealTime()
              ->MinTime(min_time);
      }
      if (info.family == SolverFamily::kStructured && (config.quick || N >= 1023 || N == config.sizes.back())) {
        const std::string tag = "BM_AlphaSweep/" + info.name + "/N:" + std::to_string(N);
        benchmark::RegisterBenchmark(tag.c_str(), BM_AlphaSweep, info.name, N, 1)->UseRealTime();
        // (a name of its own, so that reports reading BM_AlphaSweep/ keep the one-thread figure)
        benchmark::RegisterBenchmark(
            ("BM_AlphaSweepThreads/" + info.name + "/N:" + std::to_string(N) + "/threads:2").c_str(), BM_AlphaSweep,
            info.name, N, 2)
            ->UseRealTime();
      }
      if (info.name == "fast" && N <= 1023) {
        benchmark::RegisterBenchmark(("BM_SearchAlpha/" + info.name + "/N:" + std::to_string(N)).c_str(),
                                     BM_SearchAlpha, info.name, N, false)
            ->UseRealTime();
        benchmark::RegisterBenchmark(("BM_SearchAlphaSpectral/" + info.name + "/N:" + std::to_string(N)).c_str(),
                                     BM_SearchAlpha, info.name, N, true)
            ->UseRealTime();
      }
    }
    if (find_solver("cholmod") && wanted("cholmod") && N <= 1023)
      for (Ordering o : {Ordering::kAmd, Ordering::kMetis, Ordering::kNestedDissection, Ordering::kCholmodDefault})
        benchmark::RegisterBenchmark(
            ("BM_CholmodOrdering/" + std::string(to_string(o)) + "/N:" + std::to_string(N)).c_str(), BM_CholmodOrdering,
            o, N)
            ->UseRealTime()
            ->MinTime(min_time);
    if (config.quick || (N >= 127 && (N <= 511 || (N <= 1023 && config.large)))) {
      struct Case {
        const char* name;
        const char* backend;
        double w;
        bool hole;
      };
      for (const Case& c : {Case{"c1-coons", "separable-banded", 1.0, false}, Case{"c1-coons", "fast5", 1.0, false},
                            Case{"biharmonic", "fast5", 0.0, false}, Case{"c1-family-0.5", "fast5", 0.5, false},
                            Case{"hole-0.5", "pcg-fast", 0.5, true}}) {
        if (!find_solver(c.backend) || !wanted(c.backend)) continue;
        const std::string tag = "BM_Stencil5/" + std::string(c.name) + "/" + c.backend + "/N:" + std::to_string(N);
        benchmark::RegisterBenchmark(tag.c_str(), BM_Stencil5, std::string(c.backend), c.w, c.hole, N, 1)
            ->UseRealTime()
            ->MinTime(min_time);
        if (threaded(c.backend))
          benchmark::RegisterBenchmark((tag + "/threads:2").c_str(), BM_Stencil5, std::string(c.backend), c.w, c.hole,
                                       N, 2)
              ->UseRealTime()
              ->MinTime(min_time);
      }
    }
    if (config.hard) {
      struct HardCase {
        const char* name;
        double w;
        FreeShape shape;
      };
      for (const HardCase& c :
           {HardCase{"c1-coons", 1.0, FreeShape::kFull}, HardCase{"biharmonic", 0.0, FreeShape::kFull},
            HardCase{"c1-family-0.5", 0.5, FreeShape::kFull}, HardCase{"hole-0.5", 0.5, FreeShape::kHole},
            HardCase{"L-shape-0.5", 0.5, FreeShape::kLShape}, HardCase{"line-0.5", 0.5, FreeShape::kLine}})
        for (const char* backend : {"cholmod", "eigen-ldlt", "umfpack", "cg", "mg", "mg-cg", "gmres", "hypre-amg",
                                    "hypre-pfmg", "hypre-smg", "fast5", "separable-banded", "pcg-fast"}) {
          if (!find_solver(backend) || !wanted(backend) || N > hard_size_cap(backend)) continue;
          benchmark::RegisterBenchmark(
              ("BM_Hard/" + std::string(c.name) + "/" + backend + "/N:" + std::to_string(N)).c_str(), BM_Hard,
              std::string(backend), c.w, c.shape, N)
              ->UseRealTime()
              ->MinTime(0.01);
        }
    }
    if (wanted("auto"))
      for (double alpha : config.alphas)
        benchmark::RegisterBenchmark(
            ("BM_Solve/auto/N:" + std::to_string(N) + "/alpha:" + std::to_string(alpha).substr(0, 6)).c_str(), BM_Solve,
            std::string("auto"), N, alpha, 1)
            ->UseRealTime()
            ->MinTime(min_time);
  }
  int rest_argc = int(rest.size());
  benchmark::Initialize(&rest_argc, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
