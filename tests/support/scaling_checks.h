// The check shared by the tests of the backends that find the scaling of B in their own read of
// it (structured_solvers_test.cpp: fast; separable_banded_solver_test.cpp: separable-banded):
// one solver object, factorized, given B times powers of two, then B with a NaN, then B again.
#pragma once

#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "solvers/linear_solver.h"

namespace coons::test {

//! X(2^e B) = 2^e X bit for bit for each e (scaling by a power of two is exact, and the scaling
//! the solver finds must not change that), with a residual below `tolerance`; a NaN at `nan_at`
//! of column `nan_column` fails the solve with a finite residual; B afterwards gives X again.
inline void check_scaled_solves(solvers::LinearSolver& solver, const Eigen::MatrixX3d& B, const Eigen::MatrixX3d& X,
                                double tolerance, Eigen::Index nan_at, Eigen::Index nan_column) {
  Eigen::MatrixX3d Xe;
  for (const int e : {-600, 500, 0, 300}) {
    const Eigen::MatrixX3d Be = B.unaryExpr([e](double v) { return std::ldexp(v, e); });
    const solvers::SolveSummary summary = solver.solve(Be, Xe);
    INFO("B * 2^" << e << ": " << summary.brief_report());
    REQUIRE(summary.ok());
    CHECK(summary.relative_residual < tolerance);
    CHECK((Xe.unaryExpr([e](double v) { return std::ldexp(v, -e); }) - X).cwiseAbs().maxCoeff() == 0);
  }
  Eigen::MatrixX3d Bnan = B;
  Bnan(nan_at, nan_column) = std::numeric_limits<double>::quiet_NaN();
  const solvers::SolveSummary failed = solver.solve(Bnan, Xe);
  INFO(failed.brief_report());
  CHECK(!failed.ok());
  CHECK(std::isfinite(failed.relative_residual));
  REQUIRE(solver.solve(B, Xe).ok());
  CHECK((Xe - X).cwiseAbs().maxCoeff() == 0);
}

}  // namespace coons::test
