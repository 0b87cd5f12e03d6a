// Systems at the ends of the double range: no backend may loop on a start test that Eigen cannot
// pass, and a success must be a true one (tiny and huge right-hand sides: column_scaling_test.cpp).
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
  int iterative = 0;
  for (const SolverInfo& info : available_solvers()) {
    if (info.family != SolverFamily::kIterative) continue;
    ++iterative;
    SolverOptions options;
    options.max_iterations = 50;
    Eigen::MatrixX3d X;
    const SolveSummary summary = make_solver(info.name, options)->compute_and_solve(op, s.B, X);
    INFO(info.name << ": " << summary.brief_report());
    CHECK(std::isfinite(summary.relative_residual));
    if (summary.ok()) CHECK(relative_residual(op, s.B, X) <= options.tolerance);
  }
  CHECK(iterative >= 9);  // cg, cg-jacobi, cg-ic, bicgstab, jacobi, gauss-seidel, mg, mg-cg, gmres (+ pcg-fast, hypre)
}

TEST_CASE("bicgstab and eigen-ldlt: a regular matrix they cannot factor is not called singular", "[solvers]") {
  // diag(1e-200, 1e-200) has condition number 1, but IncompleteLUT's row norms underflow;
  // [[0, 1], [1, 0]] is regular, but LDLT without pivoting meets a zero pivot at once.
  Eigen::SparseMatrix<double> tiny(2, 2), swap(2, 2);
  tiny.insert(0, 0) = 1e-200;
  tiny.insert(1, 1) = 1e-200;
  swap.insert(0, 1) = 1;
  swap.insert(1, 0) = 1;
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(2, 3);
  const auto status_of = [&](const char* name, const Eigen::SparseMatrix<double>& A) {
    LinearOperator op;
    op.matrix = &A;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(name)->compute_and_solve(op, B, X);
    INFO(name << ": " << s.brief_report());
    CHECK_FALSE(s.ok());
    return s.status;
  };
  CHECK(status_of("bicgstab", tiny) == SolveStatus::kNotApplicable);
  CHECK(status_of("eigen-ldlt", swap) == SolveStatus::kNotPositiveDefinite);
}
