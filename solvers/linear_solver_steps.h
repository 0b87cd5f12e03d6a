// The small steps that the units of LinearSolver's common path share (internal to solvers/):
// linear_solver.cpp (analyze, factorize, solve), solution_verdicts.cpp (the verdict on a
// solution, its refinement) and linear_solver_sweep.cpp (sweeps of a family).
#pragma once

#include <Eigen/Core>
#include <chrono>
#include <utility>

#include "column_scaling.h"
#include "linear_solver.h"

namespace coons::solvers::detail {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

//! The relative residual of X = 0 for a non-zero B: what a summary reports when analyze or
//! factorize failed (a search copied such a summary and printed "singular, 0 iterations, residual
//! 0" although nothing was solved) and what return_zero_solution reports.
inline constexpr double kUnsolvedResidual = 1;

//! What a solve that could not run (no factorisation) returns: X = 0, and the relative residual of
//! that X, max over the columns of ‖A·0 − b‖/‖b‖ = 1 (‖A·0‖ = 0 for a zero column), as every report
//! promises for a failed solve (docs/formats.md, "The solver block").
inline void return_zero_solution(const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, SolveSummary& summary) {
  X.setZero(B.rows(), 3);
  summary.relative_residual = B.isZero(0) ? 0 : kUnsolvedResidual;
}

//! X = A⁻¹B by `solve` (a backend's do_solve), with each column of B whose largest magnitude is far
//! from 1 scaled by a power of two to one in [1/2, 1) (e: rhs_exponents(B)) and X scaled back:
//! exact, and no backend's squared norms underflow or overflow (column_scaling.h). A zero column
//! stays zero.
template <class Solve>
SolveStatus solve_scaled(const ColumnExponents& e, const Eigen::MatrixX3d& B, Eigen::MatrixX3d& X, Solve&& solve) {
  if (is_identity(e)) return solve(B, X);
  const SolveStatus status = solve(scaled_columns(B, e, -1), X);
  if (X.rows() == B.rows()) X = scaled_columns(std::move(X), e, +1);
  return status;
}

}  // namespace coons::solvers::detail
