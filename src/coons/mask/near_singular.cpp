#include "near_singular.h"

#include <algorithm>
#include <cmath>

namespace coons {

EigenvalueRatioEstimate estimate_eigenvalue_ratio(const Eigen::SparseMatrix<double>& A,
                                                  solvers::LinearSolver& factorized, int max_steps) {
  EigenvalueRatioEstimate out;
  const Eigen::Index size = A.rows();
  if (size == 0) return out;
  Eigen::VectorXd column_sums = Eigen::VectorXd::Zero(size);
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it)
      column_sums(A.IsRowMajor ? it.col() : c) += std::abs(it.value());
  const double norm = column_sums.maxCoeff();  // ‖A‖₁ ≥ max|λ|
  if (!(norm > 0)) {
    out.ratio = 0;
    return out;
  }
  // three fixed start vectors, smooth and oscillating: none is orthogonal to a mode by symmetry
  Eigen::MatrixX3d x(size, 3);
  for (Eigen::Index k = 0; k < size; ++k)
    for (int c = 0; c < 3; ++c) x(k, c) = 1 + 0.5 * std::sin((1.7 + 0.9 * c) * double(k) + c);
  x.colwise().normalize();
  double smallest = HUGE_VAL;  // the estimate of min|λ|
  for (int step = 0; step < max_steps; ++step) {
    Eigen::MatrixX3d y;
    const solvers::SolveSummary s = factorized.solve(x, y);
    ++out.solves;
    // an exact solve whose residual stays large says `singular`: its vector still steps towards
    // the near-null one, and the estimate names the ratio
    const bool usable = s.ok() || (s.status == solvers::SolveStatus::kSingular && y.rows() == size);
    if (!usable) {
      out.failure = s;
      out.ratio = std::isfinite(smallest) ? smallest / norm : 0;
      return out;
    }
    double estimate = HUGE_VAL;
    for (int c = 0; c < 3; ++c) {
      const double len = y.col(c).norm();
      if (!(len > 0) || !std::isfinite(len)) {
        out.ratio = 0;
        return out;
      }
      estimate = std::min(estimate, 1 / len);
      x.col(c) = y.col(c) / len;
    }
    const bool settled = std::abs(estimate - smallest) <= 0.01 * estimate;
    smallest = std::min(smallest, estimate);
    if (settled) break;
  }
  out.ratio = smallest / norm;
  return out;
}

solvers::SolveSummary near_singular_summary(double ratio, const std::string& how, double threshold, bool estimated) {
  solvers::SolveSummary s;
  s.solver = how;
  s.status = solvers::SolveStatus::kSingular;
  s.relative_residual = 1;      // not solved: X = 0, whose residual ‖B‖/‖B‖ every failed solve reports
  if (!std::isfinite(ratio)) {  // α = 1e308: the eigenvalues overflow, and their ratio is NaN
    s.status = solvers::SolveStatus::kFailure;
    s.message = "the mask system's eigenvalues at this alpha are beyond the range of doubles (overflow); not solved";
    return s;
  }
  s.message = "the mask system is singular or nearly so at this alpha: min|eigenvalue|/max|eigenvalue| " +
              std::string(estimated ? "~ " : "= ") + solvers::format_g(ratio) + " <= " + solvers::format_g(threshold) +
              (estimated ? " (estimated by inverse iteration as min|eigenvalue|/||A||_1)" : "");
  return s;
}

std::optional<solvers::SolveSummary> near_singular_refusal(const Eigen::SparseMatrix<double>& A,
                                                           solvers::LinearSolver& factorized, double threshold,
                                                           int* solves) {
  const EigenvalueRatioEstimate r = estimate_eigenvalue_ratio(A, factorized);
  if (solves) *solves += r.solves;
  if (!r.failure.ok()) {
    // the failed solve was one of the check's own (an arbitrary unit right-hand side), not of B
    solvers::SolveSummary failed = r.failure;
    // (X = 0 is returned, so the residual reported is 1; the inner message's residual is that of
    // the check's own right-hand side, which the line said as if it were the system's)
    failed.message =
        "not solved (X = 0): the check for a near-singular system stopped at one of its own "
        "inverse-iteration solves, of an arbitrary right-hand side: " +
        (failed.message.empty() ? std::string(solvers::to_string(failed.status)) : failed.message);
    failed.relative_residual = 1;
    return failed;
  }
  if (r.ratio > threshold) return std::nullopt;
  return near_singular_summary(r.ratio, factorized.name() + " and inverse iteration", threshold, true);
}

}  // namespace coons
