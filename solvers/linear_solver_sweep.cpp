// Sweeps of a family of systems on one sparsity pattern or grid (LinearSolver::sweep,
// linear_solver.h): one member after another through one factorisation each, or, where a backend
// offers workers (make_sweep_worker), as many members side by side as there are threads, handed
// to the sink in member order from the calling thread.
#if defined(_OPENMP)
#include <omp.h>
#endif
#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <exception>
#include <memory>
#include <vector>

#include "linear_solver_steps.h"

namespace coons::solvers {

using detail::return_zero_solution;
using detail::seconds_since;
using detail::solve_scaled;

Eigen::MatrixX3d combine_rhs(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                             Eigen::Index rows) {
  Eigen::MatrixX3d B = Eigen::MatrixX3d::Zero(rows, 3);
  for (std::size_t r = 0; r < basis.size() && r < weights.size(); ++r) B += weights[r] * basis[r];
  return B;
}

SolveStatus LinearSolver::do_sweep_solve(const std::vector<Eigen::MatrixX3d>& basis, const std::vector<double>& weights,
                                         Eigen::MatrixX3d& X, SolveSummary& summary) {
  const Eigen::MatrixX3d B = combine_rhs(basis, weights, op_.size());
  return solve_scaled(rhs_exponents(B), B, X,
                      [&](const Eigen::MatrixX3d& Bs, Eigen::MatrixX3d& Xs) { return do_solve(Bs, Xs, summary); });
}

std::unique_ptr<LinearSolver> LinearSolver::make_sweep_worker(const std::vector<Eigen::MatrixX3d>& /*basis*/,
                                                              const LinearOperator& /*op*/) {
  return nullptr;
}

void LinearSolver::sweep_member(const std::vector<Eigen::MatrixX3d>& basis, const SweepMember& member,
                                Eigen::MatrixX3d& X) {
  const std::size_t used = std::min(basis.size(), member.rhs_weights.size());
  const std::vector<double> weights(member.rhs_weights.begin(), member.rhs_weights.begin() + long(used));
  if (factorize(member.op) != SolveStatus::kSuccess) {
    return_zero_solution(combine_rhs(basis, weights, member.op.size()), X, summary_);
    return;
  }
  summary_.message.clear();
  summary_.relative_residual = 0;
  summary_.condition_estimate = 0;
  summary_.normwise_backward_error = 0;
  solve_start_ = std::chrono::steady_clock::now();
  summary_.status = do_sweep_solve(basis, weights, X, summary_);
  summary_.solve_seconds = seconds_since(solve_start_);
  if (options_.compute_residual) judge_solution(combine_rhs(basis, weights, member.op.size()), X);
}

void LinearSolver::sweep(const std::vector<Eigen::MatrixX3d>& rhs_basis, const std::vector<SweepMember>& members,
                         const SweepSink& sink) {
  do_begin_sweep();
#if defined(_OPENMP)
  const std::size_t threads = std::min(std::size_t(resolved_threads(options_.threads)), members.size());
#else
  const std::size_t threads = 1;
#endif
  std::vector<std::unique_ptr<LinearSolver>> workers;
  for (std::size_t t = 0; threads >= 2 && t < threads; ++t) {
    auto worker = make_sweep_worker(rhs_basis, members.front().op);
    if (!worker) {
      workers.clear();
      break;
    }
    workers.push_back(std::move(worker));
  }
  if (!workers.empty()) {
    sweep_on_workers(workers, rhs_basis, members, sink);
    return;
  }
  Eigen::MatrixX3d X;
  for (std::size_t k = 0; k < members.size(); ++k) {
    sweep_member(rhs_basis, members[k], X);
    sink(k, X, summary_);
  }
}

void LinearSolver::sweep_on_workers(const std::vector<std::unique_ptr<LinearSolver>>& workers,
                                    const std::vector<Eigen::MatrixX3d>& basis, const std::vector<SweepMember>& members,
                                    const SweepSink& sink) {
  const int T = int(workers.size());
  std::vector<Eigen::MatrixX3d> X(workers.size());
  std::vector<std::exception_ptr> errors(workers.size());
  for (std::size_t first = 0; first < members.size(); first += workers.size()) {
    const int batch = int(std::min(workers.size(), members.size() - first));
#if defined(_OPENMP)
#pragma omp parallel for num_threads(batch) schedule(static, 1)
#endif
    for (int t = 0; t < batch; ++t) {
      const auto w = std::size_t(t);
      try {  // (an exception must not leave the parallel region: it is rethrown below)
        workers[w]->sweep_member(basis, members[first + w], X[w]);
      } catch (...) {
        errors[w] = std::current_exception();
      }
    }
    for (int t = 0; t < batch; ++t) {
      const auto w = std::size_t(t);
      if (errors[w]) std::rethrow_exception(errors[w]);
      sink(first + w, X[w], workers[w]->summary_);
    }
  }
  // This solver holds no factorisation of its own now; its summary is the last member's.
  summary_ = workers[(members.size() - 1) % std::size_t(T)]->summary_;
  factorized_ = false;
}

}  // namespace coons::solvers
