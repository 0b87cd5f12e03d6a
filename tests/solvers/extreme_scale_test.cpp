// Systems at the ends of the double range: no backend may loop on a start test that Eigen cannot
// pass, and a success must be a true one (tiny and huge right-hand sides: rhs_scaling_test.cpp).
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

TEST_CASE("iterative solvers: a huge mask weight ends every solve with a status and a finite residual", "[solvers]") {
  // α = 1e160 puts entries of 1e160 into A and B: Eigen's start test (tol²‖b‖²) overflowed, its
  // solver returned after 0 steps and the wrapper called it again forever. Now every backend
  // stops; a success must be a true one.
  const MaskSystem s = assemble_mask_system(make_random_net(4, 4, 9), alpha_mask(1e160));
  LinearOperator op;
  op.matrix = &s.A;
  op.stencil = s.stencil;
  for (const SolverInfo& info : available_solvers()) {
    if (info.family != SolverFamily::kIterative) continue;
    SolverOptions options;
    options.max_iterations = 50;
    Eigen::MatrixX3d X;
    const SolveSummary summary = make_solver(info.name, options)->compute_and_solve(op, s.B, X);
    INFO(info.name << ": " << summary.brief_report());
    CHECK(std::isfinite(summary.relative_residual));
    if (summary.ok()) CHECK(relative_residual(op, s.B, X) <= options.tolerance);
  }
}
