#include "general_system.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "column_scaling.h"

namespace coons::solvers {

namespace {
using SpMat = Eigen::SparseMatrix<double>;

// A X − B with A X formed first: Eigen evaluates B − A X as R = B, then R −= x_j·A(:, j) column by
// column, where b = 1 vanished in (1 + 2^105) − 2^105 and a residual of 1 was measured as 0.
//
// Both figures of a column are ratios of its residual to its B or to |A||x| + |b|, which scaling x
// and b by one power of two leaves as they are. A column whose sums overflow as they stand (a row
// 2·0.95e308 − 2·0.6e308 of a finite A x = b went through +inf: every backend `failure`, or
// |A||x| = inf made the backward error r/inf = 0) is taken again with x and b times 2^−k, k the
// least that keeps every partial sum within the doubles; entries that this pushes below the
// smallest double are those far beneath the column's largest (at most 2^−1000 of it).
struct ColumnResidual {
  Eigen::VectorXd r, b, scale;  // A x − b, b and (when asked) |A||x| + |b|, all times 2^−k
};

// k ≥ 0 such that Σ_j |a_ij| |x_j| 2^−k + |b_i| 2^−k stays below 2^1021 for every row.
int overflow_exponent(const SpMat& A, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  Eigen::Index longest = 0;  // the most entries of a row
  Eigen::VectorXi per_row = Eigen::VectorXi::Zero(A.rows());
  double largest = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SpMat::InnerIterator it(A, j); it; ++it) {
      longest = std::max<Eigen::Index>(longest, ++per_row(it.row()));
      largest = std::max(largest, std::abs(it.value()));
    }
  const int rows_bits = exponent_of(double(longest + 1));  // longest + 1 < 2^rows_bits
  const int sum = std::max(exponent_of(largest) + magnitude_exponent(x) + rows_bits, magnitude_exponent(b) + 1);
  return std::max(0, sum - 1021);
}

ColumnResidual column_residual(const SpMat& A, const SpMat* absolute, const Eigen::VectorXd& x,
                               const Eigen::VectorXd& b) {
  ColumnResidual c;
  const auto evaluate = [&](const Eigen::VectorXd& xs) {
    c.r = A * xs;
    c.r -= c.b;
    if (absolute) c.scale = *absolute * xs.cwiseAbs() + c.b.cwiseAbs();
    return c.r.allFinite() && (!absolute || c.scale.allFinite());
  };
  c.b = b;
  if (evaluate(x)) return c;
  const int k = overflow_exponent(A, x, b);
  if (k == 0) return c;  // not an overflow of the sums (or x or b not finite): left as found
  Eigen::VectorXd xs = x;
  scale_by_power_of_two(xs, -k);
  scale_by_power_of_two(c.b, -k);
  evaluate(xs);
  return c;
}
}  // namespace

double backward_error(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  const SpMat absolute = A.cwiseAbs();
  double worst = 0;
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    const ColumnResidual col = column_residual(A, &absolute, X.col(c), B.col(c));
    for (Eigen::Index i = 0; i < col.r.size(); ++i) {
      const double r = std::abs(col.r(i));
      if (r == 0) continue;  // also covers a zero denominator (then the residual is zero)
      if (std::isnan(r)) return r;
      worst = std::max(worst, col.scale(i) > 0 ? r / col.scale(i) : 1.0);
    }
  }
  return worst;
}

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& X, const Eigen::MatrixXd& B) {
  Eigen::MatrixXd R(B.rows(), B.cols()), Bk(B.rows(), B.cols());  // each column as column_residual forms it
  for (Eigen::Index c = 0; c < B.cols(); ++c) {
    const ColumnResidual col = column_residual(A, nullptr, X.col(c), B.col(c));
    R.col(c) = col.r;
    Bk.col(c) = col.b;
  }
  return max_relative_norm(R, Bk);  // no underflow or overflow of ‖·‖²
}

double symmetry_defect(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() != A.cols()) return HUGE_VAL;
  // Entry by entry: measured against max |A| instead, A(2,3) = 1 beside A(3,2) = 0 passed as
  // rounding wherever some other entry was 1e15, and the Cholesky-type backends solved the
  // symmetric matrix of A's lower triangle, reporting success with a wrong X.
  Eigen::SparseMatrix<double> At = A.transpose();
  At.makeCompressed();
  double defect = 0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) {
      const double a = it.value(), b = At.coeff(it.row(), it.col());  // b = A(col, row)
      if (a == b) continue;
      defect = std::max(defect, std::abs(a - b) / std::max(std::abs(a), std::abs(b)));
    }
  // An entry whose mirror is not stored at all: A(j, i) = 0 ≠ A(i, j) (found from Aᵀ's side).
  for (Eigen::Index j = 0; j < At.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(At, j); it; ++it)
      if (it.value() != 0 && A.coeff(it.row(), it.col()) == 0) defect = std::max(defect, 1.0);
  return defect;
}

int balancing_exponent(const Eigen::SparseMatrix<double>& A) {
  int largest = std::numeric_limits<int>::min(), smallest = std::numeric_limits<int>::max();
  for (Eigen::Index k = 0; k < A.nonZeros(); ++k) {
    const double a = A.valuePtr()[k];
    if (a == 0 || !std::isfinite(a)) continue;
    const int e = std::ilogb(a);  // exact for subnormals too
    largest = std::max(largest, e);
    smallest = std::min(smallest, e);
  }
  if (largest == std::numeric_limits<int>::min()) return 0;
  if (largest <= kBalancedExponent && smallest >= -kBalancedExponent) return 0;
  // centred: the largest ends at 2^((largest − smallest)/2), the smallest as far below 1; but a
  // scaling up stops where the largest would pass 2^1015, so that A stays finite (diag(1e-320,
  // 1e300) was centred by 2^34: 1e300 became inf and every backend failed with a made-up reason),
  // and a largest already beyond it is not scaled down instead (5e-324 would become 0)
  const int centred = -static_cast<int>(std::floor((double(largest) + double(smallest)) / 2));
  if (centred <= 0) return centred;  // scaling down cannot overflow
  return std::min(centred, std::max(0, 1015 - largest));
}

std::string GeneralRun::status_name() const { return skipped ? "skipped" : to_string(status); }

namespace {

// Runs the solve phase block by block; true when every column was solved (whatever the status).
// `met` is the largest relative residual the backend reported for a block (above an exact
// backend's limit only where it found the system ill-conditioned and still solved it).
// "column 4 of B" or "columns 1-3 of B": a block of B's columns by their numbers from 1.
std::string block_name(Eigen::Index first, Eigen::Index width) {
  if (width == 1) return "column " + std::to_string(first + 1) + " of B";
  return "columns " + std::to_string(first + 1) + "-" + std::to_string(first + width) + " of B";
}

bool solve_blocks(LinearSolver& solver, const Eigen::MatrixXd& B, Eigen::MatrixXd& X, GeneralRun& run, double& met) {
  X.setZero(B.rows(), B.cols());
  double seconds = 0;
  int iterations = 0;
  met = 0;
  for (Eigen::Index first = 0; first < B.cols(); first += 3) {
    const Eigen::Index width = std::min<Eigen::Index>(3, B.cols() - first);
    Eigen::MatrixX3d block = Eigen::MatrixX3d::Zero(B.rows(), 3);
    block.leftCols(width) = B.middleCols(first, width);
    Eigen::MatrixX3d solution;
    const SolveSummary s = solver.solve(block, solution);
    seconds += s.solve_seconds;
    iterations = std::max(iterations, s.iterations);
    if (!s.ok() && run.status == SolveStatus::kSuccess) {
      run.status = s.status;
      // The backend counts the columns of its block of three ("right-hand side 1 of 3"), which
      // are B's only when B has three.
      run.reason = B.cols() == 3 ? s.message
                                 : block_name(first, width) + (width < 3 ? " (a block of 3 padded with zeros)" : "") +
                                       ": " + s.message;
    }
    if (s.ok()) {
      met = std::max(met, s.relative_residual);
      if (run.reason.empty()) run.reason = s.message;  // e.g. "ill-conditioned: …"
    }
    if (solution.rows() != B.rows() || s.status == SolveStatus::kDiverged || s.status == SolveStatus::kFailure) {
      run.solve_seconds = seconds;
      return false;
    }
    X.middleCols(first, width) = solution.leftCols(width);
  }
  run.solve_seconds = seconds;
  run.iterations = iterations;
  return true;
}

}  // namespace

GeneralRun run_general_system(const SolverInfo& info, const GeneralSystem& system, const SolverOptions& options) {
  GeneralRun run;
  run.solver = info.name;
  run.exponent = system.exponent;
  if (info.definite_only && !system.symmetric) {
    run.skipped = true;
    run.reason =
        "needs a symmetric positive definite matrix; A is not symmetric (max |a_ij - a_ji| / max(|a_ij|, |a_ji|) = " +
        format_g(symmetry_defect(*system.A)) + ")";
    return run;
  }
  // the backend's copy of A, balanced by 2^exponent (general_system.h); A as given otherwise,
  // without a copy. B is not scaled (the backends scale each column themselves): the backend
  // solves (2^k A) Y = B, and X = 2^k Y.
  Eigen::SparseMatrix<double> scaled_a;
  if (system.exponent != 0) {
    scaled_a = *system.A;
    scale_by_power_of_two(Eigen::Map<Eigen::VectorXd>(scaled_a.valuePtr(), scaled_a.nonZeros()), system.exponent);
  }
  const std::unique_ptr<LinearSolver> solver = make_solver(info.name, options);  // after what it borrows
  LinearOperator op;
  op.matrix = system.exponent != 0 ? &scaled_a : system.A;
  SolveStatus status = solver->analyze(op);
  if (status == SolveStatus::kNotApplicable) {
    run.skipped = true;
    run.reason = solver->summary().message;
    return run;
  }
  run.analyze_seconds = solver->summary().analyze_seconds;
  if (status == SolveStatus::kSuccess) {
    status = solver->factorize(op);
    run.factorize_seconds = solver->summary().factorize_seconds;
  }
  if (status == SolveStatus::kNotApplicable) {  // found out only with the values
    GeneralRun skipped;
    skipped.solver = info.name;
    skipped.exponent = system.exponent;
    skipped.skipped = true;
    skipped.reason = solver->summary().message;
    return skipped;
  }
  if (status != SolveStatus::kSuccess) {
    run.status = status;
    run.reason = solver->summary().message;
    return run;
  }
  if (solver->summary().factor_nnz > 0) run.factor_nnz = solver->summary().factor_nnz;
  Eigen::MatrixXd X;
  double met = 0;
  if (!solve_blocks(*solver, *system.B, X, run, met)) return run;
  scale_by_power_of_two(Eigen::Map<Eigen::VectorXd>(X.data(), X.size()), system.exponent);
  // The backend met its test on the balanced system; X = 2^k Y can still leave the doubles, above
  // (1e-300 x = 1e10: success with no numbers) or below (1e300 x = 1e-20 and 1e30 x = 1e-300:
  // success with a relative residual of 1e-5 and 1). The verdict is on the X returned.
  const std::string balanced = system.exponent == 0 ? std::string()
                                                    : " (2^" + std::to_string(system.exponent) +
                                                          " times the backend's solution of the balanced system)";
  if (!X.allFinite()) {
    if (run.ok()) {
      run.status = SolveStatus::kFailure;
      run.reason = "the solution is not finite (overflow): X" + balanced + " lies beyond the doubles";
    }
    return run;
  }
  run.relative_residual = relative_residual(*system.A, X, *system.B);
  run.backward_error = backward_error(*system.A, X, *system.B);
  if (!std::isfinite(*run.relative_residual) || !std::isfinite(*run.backward_error)) {
    run.relative_residual.reset();
    run.backward_error.reset();
    if (run.ok()) {
      run.status = SolveStatus::kFailure;
      run.reason = "the residual of X" + balanced + " is not finite (overflow)";
    }
    return run;
  }
  const double accepted = solver->exact() ? options.singular_residual : options.tolerance;
  // The verdict is normwise (one target for every backend); where the componentwise backward error
  // is large, entries of X that are small against the rest may be wrong in every digit
  // (diag(1, 1e-20) by cg: x₂ = 1e-20 for 1, success with a residual of 1e-20): said beside it.
  if (run.ok() && *run.backward_error >= kNotedBackwardError)
    run.reason = "the relative residual meets the target, but the componentwise backward error is " +
                 format_g(*run.backward_error) + ": small entries of X may be wrong";
  if (run.ok() && *run.relative_residual > accepted && met <= accepted) {
    run.status = SolveStatus::kFailure;
    run.reason = "X" + balanced + " has the relative residual " + format_g(*run.relative_residual) + ", above " +
                 format_g(accepted) + (solver->exact() ? " (an exact backend's limit)" : " (the tolerance)") +
                 ", where the system the backend solved met it: X lies below the range of the doubles (underflow)";
  }
  return run;
}

}  // namespace coons::solvers
