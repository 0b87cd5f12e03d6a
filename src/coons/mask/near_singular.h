// Near-singular mask systems: the one criterion by which the α searches refuse to evaluate.
// A system is near-singular when min|λ|/max|λ| ≤ kNearSingularEigenvalueRatio (mask9.h, 1e-6).
// The ratio comes in closed form where the sine modes diagonalise the system (the one-ring
// rectangle: mask9_eigenvalue_ratio) and from estimate_eigenvalue_ratio otherwise (two data rings,
// a free set, the non-uniform system of a B-spline boundary): inverse iteration with the
// factorisation the evaluation has made anyway. An evaluation refused there fails with
// near_singular_summary (status singular, the ratio named), so the search reports it as any
// failed evaluation and never takes a value from that system.
// Based on: G. H. Golub, C. F. Van Loan, Matrix Computations, §8.2 (inverse iteration).
#pragma once

#include <Eigen/SparseCore>
#include <optional>
#include <string>

#include "coons/mask/mask9.h"
#include "solvers/linear_solver.h"

namespace coons {

struct EigenvalueRatioEstimate {
  //! min|λ|/max|λ| estimated: 1/‖A⁻¹x‖ after inverse iteration from three fixed unit vectors x
  //! (the smallest over them; it is ≥ min|λ| and converges to it, within two or three steps
  //! once min|λ| is far below the next |λ|), over ‖A‖₁ (≥ max|λ|). 0 when a solve that the
  //! backend accepts (success or singular) gives a non-finite or zero vector; 1 for an empty
  //! system. A backend that reports a non-finite solution as a failure ends in `failure`.
  double ratio = 1;
  int solves = 0;  //!< solves made (each of three columns)
  //! The first solve that failed other than `singular` (status success when none did); a
  //! `singular` solve's vector is used (an exact solve's large residual on a near-singular A).
  solvers::SolveSummary failure;
};

//! The estimate for a square system A whose factorisation `factorized` holds (factorize(A) has
//! succeeded); A symmetric, or similar to a symmetric matrix. Stops after `max_steps` steps or
//! when a step changes the estimate by less than 1%.
EigenvalueRatioEstimate estimate_eigenvalue_ratio(const Eigen::SparseMatrix<double>& A,
                                                  solvers::LinearSolver& factorized, int max_steps = 6);

//! The summary of a system refused at `ratio` (≤ `threshold`): status singular, solver `how`
//! (e.g. "closed-form eigenvalues"), relative residual 1 (not solved: that of X = 0), the message
//! naming the ratio (`estimated`: an estimate_eigenvalue_ratio, said so) and the threshold.
solvers::SolveSummary near_singular_summary(double ratio, const std::string& how,
                                            double threshold = kNearSingularEigenvalueRatio, bool estimated = false);

//! The check of an evaluation outside the definite range, after factorize(A) has succeeded on
//! `factorized`: nullopt when the estimated ratio is above `threshold`; otherwise the summary to
//! fail with (the estimate's own failure, its message saying that a solve of the check failed, or
//! near_singular_summary, estimated). The estimate's
//! solves are added to *solves.
std::optional<solvers::SolveSummary> near_singular_refusal(const Eigen::SparseMatrix<double>& A,
                                                           solvers::LinearSolver& factorized, double threshold,
                                                           int* solves = nullptr);

}  // namespace coons
