// A mask that reproduces constants is solved for its data moved to a centre c (data_centre in
// stencil_problem.h): A Y = B_c with B_c the right-hand side of the moved data, X = Y + 1c. The
// solver's residual and its verdict are then those of B_c, not of the system as given (B, the
// right-hand side of the data where they lie): where ‖B_c‖ > ‖B‖ the moved system is judged the
// more leniently (gauss-seidel at α = −1/4 on a 200 × 3 net reported 9.99e-13, success for the
// tolerance 1e-12, where the system as given had 2.65e-12). finish_centred_solve measures the
// system as given, refines against it when it misses the tolerance, and reports that.
// Sizes: op of n unknowns; B, X: n × 3.
// Based on: N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM (2002),
// ch. 12 (iterative refinement, the residual of the system as given).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>

#include "solvers/linear_solver.h"

namespace coons {

//! The stencil's Σ|w| (≥ ‖A‖∞, ≥ ‖|A|‖₂): the scale of a residual's rounding floor.
double weight_sum(const Eigen::MatrixXd& weights);

//! After solver solved op·Y = B_c (summary: its summary, Y in X): X = Y + 1·centre; when the
//! centre is not zero, summary.relative_residual becomes the residual of the system as given
//! (given_rhs(): B, assembled from the data where they lie; B_c + A·1c would carry the rounding of
//! the moved data, ε·|c|, into it); for an iterative backend, up to two refinement rounds
//! X += A⁻¹(B − A X) by the same solver while it is above the solver's tolerance, and
//! not_converged, with the reason, if it stays above. A summary that is not ok is left as it is
//! (X unchanged).
//! A column whose residual is above the tolerance but within the rounding floor of b − A x (the
//! size of its rounding, which smooth data make larger than a tolerance of 1e-12: the mask
//! equations of a smooth net cancel) is not refined and keeps success, with a message.
void finish_centred_solve(solvers::LinearSolver& solver, const solvers::LinearOperator& op,
                          const std::function<Eigen::MatrixX3d()>& given_rhs, double weight_sum,
                          const Eigen::RowVector3d& centre, Eigen::MatrixX3d& X, solvers::SolveSummary& summary);

//! The same verdict for a member of a sweep, whose solver has moved on (no refinement): X is the
//! solution moved back, given_rhs the member's right-hand side of the data where they lie.
void judge_centred_member(const std::string& backend, double tolerance, const solvers::LinearOperator& op,
                          const Eigen::MatrixX3d& given_rhs, double weight_sum, const Eigen::MatrixX3d& X,
                          solvers::SolveSummary& summary);

}  // namespace coons
