// One backend on a general square system A X = B read from outside coons (e.g. a Matrix Market
// file): A n by n sparse, B n by k (any k ≥ 1). Runs analyze, factorize and solve (B in blocks of
// three columns, the backends' width, padded with zero columns), then measures the solution with
// its own norms rather than the backend's: the relative residual and the componentwise backward
// error. Backends that cannot take such a system (they need a grid stencil, or a symmetric matrix
// where A is not) are reported as skipped, with the reason.
// Based on: W. Oettli and W. Prager, Numer. Math. 6 (1964) 405–409 (the componentwise backward
// error); N. J. Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed., SIAM 2002, §7.2.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>

#include "linear_solver.h"
#include "registry.h"

namespace coons::solvers {

//! max over rows i and columns c of |B − A X|_ic / (|A| |X| + |B|)_ic, a row whose denominator is
//! zero counting as 0 (its residual is then zero too). Lies in [0, 1] up to rounding; the smallest
//! relative componentwise perturbation of A and B for which X is an exact solution (Oettli–Prager).
//! X must be finite, with the shape of B. A column whose sums overflow as they stand is measured on
//! x and b scaled down by a common power of two (the ratio does not change), as is relative_residual's.
double backward_error(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B);

//! max over columns of ‖B − A X‖₂ / ‖B‖₂ (a zero column of B: ‖A X‖₂).
double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B);

//! max over the entries of |a_ij − a_ji| / max(|a_ij|, |a_ji|) (1 where only one of the pair is
//! non-zero, 0 for an exactly symmetric or zero matrix): entry by entry, so that a large entry
//! elsewhere hides no asymmetry.
double symmetry_defect(const Eigen::SparseMatrix<double>& A);

//! A success whose componentwise backward error is at least this gets a note (GeneralRun::reason).
constexpr double kNotedBackwardError = 1e-6;

//! A is treated as symmetric when symmetry_defect(A) is at most this (rounding of written values).
constexpr double kSymmetryDefectLimit = 1e-14;

//! What one backend did on the system. Every number is measured; a phase not reached, or a
//! solution not worth measuring (none, diverged, not finite), leaves its fields empty.
struct GeneralRun {
  std::string solver;
  bool skipped = false;  //!< the backend does not apply to this system (reason says why)
  SolveStatus status = SolveStatus::kSuccess;
  std::string reason;  //!< why skipped, the backend's message when it did not succeed, or a note on a
                       //!< success (a componentwise backward error of at least kNotedBackwardError)
  std::optional<double> analyze_seconds, factorize_seconds, solve_seconds;  //!< solve: all blocks
  std::optional<int> iterations;                                            //!< the most over the column blocks
  std::optional<double> relative_residual, backward_error;
  std::optional<long long> factor_nnz;  //!< non-zeros of the factor(s) or preconditioner, when there is one
  int exponent = 0;                     //!< the backend saw 2^exponent A (GeneralSystem)

  [[nodiscard]] bool ok() const { return !skipped && status == SolveStatus::kSuccess; }
  //! "skipped" or to_string(status).
  [[nodiscard]] std::string status_name() const;
};

//! A whose non-zeros have binary exponents (std::ilogb) in [-kBalancedExponent, kBalancedExponent],
//! i.e. magnitudes in [2^-100, 2^101), is left alone.
constexpr int kBalancedExponent = 100;

//! The k for which 2^k A has the binary exponents of its largest and smallest non-zero magnitudes
//! centred on 0, when either lies outside ±kBalancedExponent; else 0 (also for a zero matrix). A
//! scaling up stops where the largest would pass 2^1015, and is none when it is already beyond (A's
//! magnitudes may span more than the doubles: diag(1e-320, 1e300) is scaled by 2^19, not 2^34).
//! The backends then solve (2^k A) Y = B and X = 2^k Y: exact (unless A's own range exceeds the
//! doubles'), and it keeps the backends' squares and row norms away from under- and overflow:
//! 1e-200·I, which has condition number 1, stopped an incomplete LU ("singular"), and 1e-310·I
//! every direct backend ("overflow"). B is not scaled: 2^k B can overflow where X does not.
int balancing_exponent(const Eigen::SparseMatrix<double>& A);

//! The system and what is known of it, computed once for every backend.
struct GeneralSystem {
  const Eigen::SparseMatrix<double>* A = nullptr;  //!< square, borrowed
  const Eigen::MatrixXd* B = nullptr;              //!< A.rows() by k, borrowed
  bool symmetric = false;                          //!< symmetry_defect(A) ≤ kSymmetryDefectLimit
  //! balancing_exponent(A): the backends see 2^exponent A (and B as given), X = 2^exponent Y;
  //! X and its measurements (residual, backward error) are those of A and B as given
  int exponent = 0;
};

//! Runs the backend `info` (a fresh solver with `options`) on the system: skipped when it needs a
//! symmetric matrix (info.definite_only) and A is not symmetric, or when the backend itself finds
//! it not applicable (it needs a grid stencil); otherwise the three phases, stopping at the first
//! that fails, and the measurements of X when it has one for every column.
GeneralRun run_general_system(const SolverInfo& info, const GeneralSystem& system, const SolverOptions& options);

}  // namespace coons::solvers
