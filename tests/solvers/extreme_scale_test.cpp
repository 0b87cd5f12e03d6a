// Systems at the ends of the double range: the residual that judges every solve must not under- or
// overflow, and no backend may loop on a start test that Eigen cannot pass.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

TEST_CASE("relative_residual: columns of 1e-170s and 1e+170s give the scale-free value", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(5, 4, 3), alpha_mask(-0.1));
  LinearOperator op;
  op.matrix = &s.A;
  const Eigen::MatrixX3d X = Eigen::MatrixXd(s.A).fullPivLu().solve(Eigen::MatrixXd(s.B));
  const Eigen::MatrixX3d Xoff = X * (1 + 1e-3);  // a wrong answer with a known residual
  const double reference = relative_residual(op, s.B, Xoff);
  REQUIRE(reference > 1e-4);
  for (const double scale : {1e-170, 1e-300, 1e+170, 1e+300}) {
    INFO("scale " << scale);
    // ‖scale·B‖ underflows to 0 (or overflows to inf) in a plain norm(): the unsolved X = 0 then
    // read as a perfect answer, and a wrong one as residual 0.
    CHECK(relative_residual(op, scale * s.B, Eigen::MatrixX3d::Zero(s.B.rows(), 3)) == Approx(1).epsilon(1e-12));
    CHECK(relative_residual(op, scale * s.B, scale * Xoff) == Approx(reference).epsilon(1e-9));
  }
}

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
