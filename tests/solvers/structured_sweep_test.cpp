// LinearSolver::sweep on several threads: members solved side by side on one-thread workers
// (fast) or one after another with threads inside each solve (dst) must reach the sink in member
// order, from the calling thread, one at a time, with the one-thread sweep's solution and verdict
// bit for bit.
#include <catch2/catch.hpp>

#include "coons/config.h"

#if COONS_HAVE_FFTW

#include <atomic>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>
#include <thread>
#include <vector>

#include "solvers/structured_solvers.h"
#include "support/grid_fixtures.h"

using namespace coons::solvers;
using coons::test::alpha_grid_stencil;

namespace {

// Random values everywhere (dense) or only next to the frame (ring, as for a mask system).
Eigen::MatrixX3d random_rhs(const GridStencil& s, std::uint32_t seed, bool ring) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixX3d B(s.size(), 3);
  for (Eigen::Index k = 0; k < B.size(); ++k) B.data()[k] = u(rng);
  if (ring)
    for (int i = 1; i + 1 < s.rows; ++i)
      for (int j = 1; j + 1 < s.cols; ++j) B.row(Eigen::Index(i) * s.cols + j).setZero();
  return B;
}

struct Sunk {
  std::vector<std::size_t> order;
  std::vector<Eigen::MatrixX3d> X;
  std::vector<SolveSummary> summaries;
  bool all_on_caller = true, overlapped = false;
};

Sunk run_sweep(LinearSolver& solver, const std::vector<Eigen::MatrixX3d>& basis,
               const std::vector<LinearSolver::SweepMember>& members) {
  Sunk sunk;
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> inside{0};
  solver.sweep(basis, members, [&](std::size_t k, const Eigen::MatrixX3d& X, const SolveSummary& s) {
    if (inside.fetch_add(1) != 0) sunk.overlapped = true;
    if (std::this_thread::get_id() != caller) sunk.all_on_caller = false;
    sunk.order.push_back(k);
    sunk.X.push_back(X);
    sunk.summaries.push_back(s);
    inside.fetch_sub(1);
  });
  return sunk;
}

bool same_bits(double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

bool same_bits(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) {
  return a.rows() == b.rows() && std::memcmp(a.data(), b.data(), sizeof(double) * std::size_t(a.size())) == 0;
}

}  // namespace

TEST_CASE("LinearSolver::sweep: two and three threads give the one-thread members bit for bit, sunk in order",
          "[solvers]") {
  // 36 + 1 columns is prime: fast eliminates the last column (the capacitance path). The members take every
  // path: Kronecker (α = −1/4), transform, indefinite (α = 0.4), a dense basis member, weights
  // shorter than the basis, and one that cannot be factorized (no stencil: X = 0 and its status).
  const int rows = 21, cols = 36;
  const GridStencil base = alpha_grid_stencil(rows, cols, 0.0);
  const std::vector<Eigen::MatrixX3d> basis = {random_rhs(base, 80, true), random_rhs(base, 81, true),
                                               random_rhs(base, 82, false)};
  const Eigen::SparseMatrix<double> A = stencil_matrix(base);
  std::vector<LinearSolver::SweepMember> members;
  auto add = [&](double alpha, std::vector<double> weights) {
    LinearOperator op;
    op.stencil = alpha_grid_stencil(rows, cols, alpha);
    members.push_back({op, std::move(weights)});
  };
  add(-0.25, {1.0, -0.25, 0.0});
  add(-0.1, {1.0, -0.1, 0.0});
  LinearOperator matrix_only;
  matrix_only.matrix = &A;
  members.push_back({matrix_only, {1.0, 0.0, 0.0}});
  add(0.4, {1.0, 0.4, 0.0});
  add(-0.2, {1.0, -0.2, 0.5});
  add(0.1, {1.0, 0.1});
  add(0.25, {1.0, 0.25, 0.0});

  using Factory = std::function<std::unique_ptr<LinearSolver>(const SolverOptions&)>;
  for (const auto& [name, make] :
       {std::pair<const char*, Factory>{"dst", make_dst_solver}, {"fast", make_fast_solver}}) {
    auto one_thread = make({});
    const Sunk one = run_sweep(*one_thread, basis, members);
    REQUIRE(one.order.size() == members.size());
    CHECK(one.summaries[1].ok());
    CHECK(one.summaries[2].status == SolveStatus::kNotApplicable);
    CHECK(one.X[2].isZero(0));
    for (int threads : {2, 3}) {
      SolverOptions options;
      options.threads = threads;
      auto solver = make(options);
      const Sunk many = run_sweep(*solver, basis, members);
      INFO(name << ", " << threads << " threads");
      REQUIRE(many.order.size() == members.size());
      CHECK(many.all_on_caller);
      CHECK(!many.overlapped);
      for (std::size_t k = 0; k < members.size(); ++k) {
        INFO("member " << k << ": " << many.summaries[k].brief_report());
        CHECK(many.order[k] == k);
        CHECK(same_bits(many.X[k], one.X[k]));
        const SolveSummary &a = one.summaries[k], &b = many.summaries[k];
        CHECK(b.solver == a.solver);
        CHECK(b.status == a.status);
        CHECK(b.message == a.message);
        CHECK(b.iterations == a.iterations);
        CHECK(same_bits(b.relative_residual, a.relative_residual));
      }
      // Threaded or not, summary() is the last member's after a sweep.
      CHECK(solver->summary().status == one_thread->summary().status);
      CHECK(solver->summary().relative_residual == one_thread->summary().relative_residual);
    }
  }
}

#endif  // COONS_HAVE_FFTW
