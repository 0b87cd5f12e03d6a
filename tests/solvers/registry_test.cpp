// The backend registry (solvers/registry.h): what a SolverInfo says of a backend is what the
// backend does.
#include "solvers/registry.h"

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <set>
#include <string>

#include "coons/mask/assemble_mask_system.h"
#include "support/fixtures.h"

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

TEST_CASE("uses_threads: every backend answers alike on 1 and 2 threads, the flag marks the threaded ones",
          "[solvers]") {
  // a 3x3 member of the alpha family that every backend solves (mg and the transforms included)
  const MaskSystem s = assemble_mask_system(make_random_net(17, 13, 4), alpha_mask(0.0));
  LinearOperator op;
  op.matrix = &s.A;
  op.stencil = s.stencil;
  const Eigen::MatrixXd reference = Eigen::MatrixXd(s.A).fullPivLu().solve(Eigen::MatrixXd(s.B));
  for (const SolverInfo& info : available_solvers()) {
    if (info.name.rfind("hypre", 0) == 0) continue;  // (MPI-initialised backends: tests/solvers/hypre_solvers_test)
    INFO(info.name);
    for (int threads : {1, 2}) {
      SolverOptions options;
      options.threads = threads;
      const auto solver = make_solver(info.name, options);
      Eigen::MatrixX3d X;
      const SolveSummary summary = solver->compute_and_solve(op, s.B, X);
      if (!summary.ok()) continue;  // (jacobi and the like where they do not apply: the conformance tests)
      CHECK((X - reference).cwiseAbs().maxCoeff() < 1e-6 * (1 + reference.cwiseAbs().maxCoeff()));
    }
  }
  // the threaded ones are those whose --threads changes how they run, never what they answer
  for (const char* name : {"dst", "fast", "fast5", "separable-banded", "mg", "mg-cg", "gmres"})
    if (const SolverInfo* info = find_solver(name)) CHECK(info->uses_threads);
  for (const char* name : {"eigen-ldlt", "eigen-lu", "cholmod", "umfpack", "cg", "bicgstab", "jacobi"})
    if (const SolverInfo* info = find_solver(name)) CHECK_FALSE(info->uses_threads);
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
