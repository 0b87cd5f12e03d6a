// The verdicts of LinearSolver's common path on a solution (solvers/solution_verdicts.cpp): here the
// condition estimate of SolverOptions::estimate_condition.
#include <Eigen/SparseCore>
#include <catch2/catch.hpp>
#include <limits>
#include <string>
#include <vector>

#include "solvers/registry.h"

using namespace coons::solvers;

namespace {

Eigen::SparseMatrix<double> diagonal(const std::vector<double>& d) {
  Eigen::SparseMatrix<double> A(Eigen::Index(d.size()), Eigen::Index(d.size()));
  for (std::size_t k = 0; k < d.size(); ++k) A.insert(Eigen::Index(k), Eigen::Index(k)) = d[k];
  A.makeCompressed();
  return A;
}

SolveSummary solve_with(const std::string& name, const Eigen::SparseMatrix<double>& A, bool estimate) {
  SolverOptions options;
  options.estimate_condition = estimate;
  LinearOperator op;
  op.matrix = &A;
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(A.rows(), 3);
  Eigen::MatrixX3d X;
  return make_solver(name, options)->compute_and_solve(op, B, X);
}

// The exact backends that factor an assembled matrix, as built here.
std::vector<std::string> matrix_factorisations() {
  std::vector<std::string> names;
  for (const SolverInfo& info : available_solvers())
    if (info.needs_matrix && make_solver(info.name)->exact()) names.push_back(info.name);
  return names;
}

}  // namespace

TEST_CASE("LinearSolver::solve: estimate_condition gives kappa of a diagonal matrix and says when kappa eps is large",
          "[solvers]") {
  // κ∞(diag(2, 1, 1, 1e−12)) = 2e12: each ±1 probe finds ‖A⁻¹g‖∞ = 1e12 exactly.
  const Eigen::SparseMatrix<double> ill = diagonal({2, 1, 1, 1e-12});
  const Eigen::SparseMatrix<double> fine = diagonal({1, 2, 3, 0.5});  // κ∞ = 3 / 0.5 = 6
  const std::vector<std::string> names = matrix_factorisations();
  REQUIRE(names.size() >= 3);  // eigen-ldlt, eigen-lu, eigen-llt at least
  for (const std::string& name : names) {
    INFO(name);
    const SolveSummary s = solve_with(name, ill, true);
    INFO(s.brief_report());
    REQUIRE(s.ok());
    CHECK(s.condition_estimate == Approx(2e12).epsilon(1e-12));
    CHECK(s.forward_error_bound() == Approx(2e12 * std::numeric_limits<double>::epsilon()));
    CHECK_THAT(s.message, Catch::StartsWith("ill-conditioned: condition estimate 2e+12"));
    const SolveSummary f = solve_with(name, fine, true);
    CHECK(f.ok());
    CHECK(f.condition_estimate == Approx(6).epsilon(1e-12));
    CHECK(f.message.empty());  // κε = 1.3e−15: nothing to say
  }
}

TEST_CASE("LinearSolver::solve: without estimate_condition, or for an iterative backend, no estimate is made",
          "[solvers]") {
  const Eigen::SparseMatrix<double> ill = diagonal({2, 1, 1, 1e-12});
  const SolveSummary off = solve_with("eigen-ldlt", ill, false);
  CHECK(off.ok());
  CHECK(off.condition_estimate == 0);
  CHECK(off.forward_error_bound() == 0);
  CHECK(off.message.empty());
  const SolveSummary cg = solve_with("cg", ill, true);  // an iteration's error is its tolerance's business
  CHECK(cg.ok());
  CHECK(cg.condition_estimate == 0);
}
