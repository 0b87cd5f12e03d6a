// The backend registry (solvers/registry.h): what a SolverInfo says of a backend is what the
// backend does.
#include "solvers/registry.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <map>
#include <set>
#include <string>

#include "coons/mask/assemble_mask_system.h"
#include "support/fixtures.h"
#include "support/grid_fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

TEST_CASE("available_solvers: names are unique and find_solver finds each, nothing else", "[solvers]") {
  std::set<std::string> names;
  for (const SolverInfo& info : available_solvers()) {
    CHECK(names.insert(info.name).second);
    CHECK(find_solver(info.name) == &info);
    CHECK(make_solver(info.name) != nullptr);
    CHECK(uses_threads(info.name) == info.uses_threads);
  }
  CHECK(find_solver("no-such-backend") == nullptr);
  CHECK_FALSE(uses_threads("no-such-backend"));
}

TEST_CASE("uses_threads: a threaded backend gives on 2 threads what it gives on 1, on every problem it takes",
          "[solvers]") {
  // the reference problems of the stencil conformance tests (3x3 and 5x5 stencils on full, L-shaped
  // and holed grids): each threaded backend must take some of them, and where it solves one on 1
  // thread it must solve it on 2, to the same numbers (the --threads help: "the result is the same
  // for every count")
  std::map<std::string, int> solved;
  const auto check_threads = [&](const LinearOperator& op, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& reference,
                                 const std::string& label) {
    for (const SolverInfo& info : available_solvers()) {
      if (!info.uses_threads) continue;
      INFO(info.name << " on " << label);
      Eigen::MatrixX3d X1, X2;
      SolverOptions one, two;
      two.threads = 2;
      const SolveSummary s1 = make_solver(info.name, one)->compute_and_solve(op, B, X1);
      const SolveSummary s2 = make_solver(info.name, two)->compute_and_solve(op, B, X2);
      CHECK(s1.status == s2.status);
      if (!s1.ok() || !s2.ok()) continue;
      ++solved[info.name];
      CHECK(max_relative_error(X2, X1) == 0);
      CHECK(max_relative_error(X1, reference) < 1e-6);
    }
  };
  for_each_reference_problem([&](const ReferenceProblem& p) {
    LinearOperator op;
    op.matrix = &p.A;
    op.grid = &p.op;
    check_threads(op, p.B, p.reference, p.label());
  });
  // the 3x3 alpha family as a bare grid stencil (what dst and fast take)
  for (double alpha : {-0.25, -0.1, 0.0}) {
    const solvers::GridStencil stencil = alpha_grid_stencil(31, 24, alpha);
    const Eigen::SparseMatrix<double> A = stencil_matrix(stencil);
    const Eigen::MatrixX3d B = Eigen::MatrixX3d::Random(A.rows(), 3);
    const Eigen::MatrixX3d reference = Eigen::MatrixXd(A).ldlt().solve(Eigen::MatrixXd(B));
    LinearOperator op;
    op.matrix = &A;
    op.stencil = stencil;
    check_threads(op, B, reference, "alpha " + std::to_string(alpha) + ", 31 x 24");
  }
  for (const SolverInfo& info : available_solvers()) {
    if (!info.uses_threads) continue;
    INFO(info.name);
    CHECK(solved[info.name] > 0);
  }
}

TEST_CASE("default_matrix_solver: a Cholesky-type backend for a definite system, an LU otherwise", "[solvers]") {
  const SolverInfo& definite = default_matrix_solver(true);
  const SolverInfo& indefinite = default_matrix_solver(false);
  CHECK(definite.name == (find_solver("cholmod") ? "cholmod" : "eigen-ldlt"));
  CHECK(indefinite.name == "eigen-lu");
  CHECK(definite.needs_matrix);
  CHECK(definite.definite_only);
  CHECK(indefinite.needs_matrix);
  CHECK_FALSE(indefinite.definite_only);
  // and each solves the system it is for: alpha = 0.1 is definite, alpha = 0.4 is not
  for (const auto& [alpha, info] : {std::pair<double, const SolverInfo*>{0.1, &definite}, {0.4, &indefinite}}) {
    const MaskSystem s = assemble_mask_system(make_random_net(9, 7, 2), alpha_mask(alpha));
    LinearOperator op;
    op.matrix = &s.A;
    Eigen::MatrixX3d X;
    INFO(info->name << " at alpha " << alpha);
    const SolveSummary summary = make_solver(info->name)->compute_and_solve(op, s.B, X);
    CHECK(summary.ok());
    CHECK((Eigen::MatrixXd(s.A) * X - Eigen::MatrixXd(s.B)).cwiseAbs().maxCoeff() < 1e-10);
  }
}
