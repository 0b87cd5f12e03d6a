// The common solve path scales each right-hand-side column by a power of two (solvers/column_scaling.h):
// tiny and huge right-hand sides, whose squared norms underflow or overflow, solve like ordinary ones.
#include "solvers/column_scaling.h"

#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

namespace {

LinearOperator operator_of(const MaskSystem& s) {
  LinearOperator op;
  op.matrix = &s.A;
  op.stencil = s.stencil;
  return op;
}

Eigen::MatrixX3d times_power_of_two(const Eigen::MatrixX3d& M, int e) {
  return M.unaryExpr([e](double x) { return std::ldexp(x, e); });
}

// An SPD mask system (α = 0.1: Jacobi and Gauss–Seidel converge too) whose second right-hand-side
// column is zero.
MaskSystem spd_system() {
  MaskSystem s = assemble_mask_system(make_random_net(9, 11, 31), alpha_mask(0.1));
  s.B.col(1).setZero();
  return s;
}

// 2^-600 ≈ 2.4e-181: every square underflows to zero. 2^500 ≈ 3.3e150 and 2^540 ≈ 3.6e162: the
// squares of the largest entries come near the largest double, then overflow.
constexpr int kExponents[] = {-600, 500, 540};

// The backends that may decline this system (α = 0.1 is neither a 5×5 stencil nor separable); any
// other backend that declines it is a failure, not a skip.
bool may_decline(const std::string& name) { return name == "fast5" || name == "separable-banded"; }

}  // namespace

TEST_CASE("every solver: right-hand sides scaled by 2^-600 2^500 or 2^540 give X scaled alike", "[solvers]") {
  const MaskSystem s = spd_system();
  std::size_t checked = 0;
  for (const SolverInfo& info : available_solvers()) {
    Eigen::MatrixX3d X;
    const SolveSummary plain = make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X);
    INFO(info.name << ": " << plain.brief_report());
    if (plain.status == SolveStatus::kNotApplicable) {
      CHECK(may_decline(info.name));
      continue;
    }
    ++checked;
    REQUIRE(plain.ok());
    REQUIRE(X.col(1).isZero(0));
    const double size = X.cwiseAbs().maxCoeff();
    for (const int e : kExponents) {
      Eigen::MatrixX3d Xe;
      const SolveSummary scaled =
          make_solver(info.name)->compute_and_solve(operator_of(s), times_power_of_two(s.B, e), Xe);
      INFO("B * 2^" << e << ": " << scaled.brief_report());
      CHECK(scaled.ok());
      CHECK(scaled.relative_residual < 1e-10);
      REQUIRE(Xe.rows() == X.rows());
      CHECK(Xe.col(1).isZero(0));  // a zero column stays zero
      CHECK((times_power_of_two(Xe, -e) - X).cwiseAbs().maxCoeff() <= 1e-12 * size);
    }
  }
  CHECK(checked + 2 >= available_solvers().size());  // all but fast5 and separable-banded
}

TEST_CASE("every solver: a sweep member scaled by 2^-600 gives X scaled alike", "[solvers]") {
  const MaskSystem s = spd_system();
  const int e = -600;
  std::size_t checked = 0;
  for (const SolverInfo& info : available_solvers()) {
    Eigen::MatrixX3d X;
    INFO(info.name);
    if (make_solver(info.name)->compute_and_solve(operator_of(s), s.B, X).status == SolveStatus::kNotApplicable) {
      CHECK(may_decline(info.name));
      continue;
    }
    ++checked;
    const std::vector<Eigen::MatrixX3d> basis{times_power_of_two(s.B, e)};
    const std::vector<LinearSolver::SweepMember> members{{operator_of(s), {1.0}}};
    Eigen::MatrixX3d Xe;
    SolveSummary summary;
    make_solver(info.name)->sweep(basis, members, [&](std::size_t, const Eigen::MatrixX3d& x, const SolveSummary& r) {
      Xe = x;
      summary = r;
    });
    INFO(summary.brief_report());
    CHECK(summary.ok());
    CHECK(summary.relative_residual < 1e-10);
    REQUIRE(Xe.rows() == X.rows());
    CHECK(Xe.col(1).isZero(0));
    CHECK((times_power_of_two(Xe, -e) - X).cwiseAbs().maxCoeff() <= 1e-12 * X.cwiseAbs().maxCoeff());
  }
  CHECK(checked + 2 >= available_solvers().size());  // all but fast5 and separable-banded
}

TEST_CASE("every solver: a solution below the normal doubles is a failure not success", "[solvers]") {
  // A net scaled to 1e-315: the system scaled by powers of two was solved to 6.5e-16, but the X
  // returned, whose entries are subnormal, has a relative residual of 1.8e-7, and cg said success.
  // At 2^-1065 an entry of X keeps about 9 bits.
  const MaskSystem s = spd_system();
  const Eigen::MatrixX3d B = times_power_of_two(s.B, -1065);
  std::size_t failed = 0;
  for (const SolverInfo& info : available_solvers()) {
    Eigen::MatrixX3d X;
    const SolveSummary summary = make_solver(info.name)->compute_and_solve(operator_of(s), B, X);
    INFO(info.name << ": " << summary.brief_report());
    if (summary.status == SolveStatus::kNotApplicable) {
      CHECK(may_decline(info.name));
      continue;
    }
    CHECK(summary.status != SolveStatus::kSuccess);
    CHECK(summary.relative_residual > 1e-6);  // that of the X returned
    if (summary.status == SolveStatus::kFailure && summary.message.find("underflow") != std::string::npos) ++failed;
  }
  CHECK(failed >= 10);
}

TEST_CASE("relative_residual: tiny and huge columns give the residual of the unscaled system", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(9, 11, 31), alpha_mask(0.1));
  const LinearOperator op = operator_of(s);
  const Eigen::MatrixX3d X = Eigen::MatrixX3d::Constant(s.B.rows(), 3, 0.25);  // not the solution
  const double plain = relative_residual(op, s.B, X);
  REQUIRE(plain > 0.01);
  for (const int e : {-600, 540})
    CHECK(relative_residual(op, times_power_of_two(s.B, e), times_power_of_two(X, e)) == Approx(plain).epsilon(1e-14));
}

TEST_CASE("rhs_exponents: 0 for a column with a NaN or an infinity wherever it lies", "[solvers]") {
  // A column whose largest finite value is 2^600 is scaled by 2^-601, unless it holds a NaN or an
  // infinity (Eigen's maxCoeff alone dropped a NaN that did not come first: exponent 601).
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    for (const Eigen::Index at : {Eigen::Index(0), Eigen::Index(1), Eigen::Index(4)}) {
      Eigen::MatrixX3d B = Eigen::MatrixX3d::Constant(5, 3, 0x1p600);
      B(at, 1) = bad;
      INFO(bad << " at row " << at);
      const ColumnExponents e = rhs_exponents(B);
      CHECK(e[0] == 601);
      CHECK(e[1] == 0);
      CHECK(e[2] == 601);
      CHECK(magnitude_exponent(B.col(1)) == 0);
    }
}
