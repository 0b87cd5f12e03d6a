#include "coons/tri/tri_solve.h"

#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <utility>

#include "solvers/registry.h"
#include "tri/tri_fixtures.h"

using namespace coons::tri;
using namespace coons::tri_test;
using coons::solvers::SolveStatus;

namespace {

TriNet solve_with(const TriNet& net, double c, const std::string& solver = "eigen-lu") {
  TriSolveOptions options;
  options.mask.c = c;
  options.solver = coons::solvers::find_solver(solver);
  REQUIRE(options.solver);
  const TriSolveResult r = solve_tri_net(boundary_of(net), options);
  REQUIRE(r.summary.ok());
  return r.net;
}

// The solve of `net`'s boundary by the backend `name`, whatever its status.
TriSolveResult solve_by(const TriNet& net, double c, const std::string& name, double tolerance = 1e-12) {
  TriSolveOptions options;
  options.mask.c = c;
  options.solver = coons::solvers::find_solver(name);
  REQUIRE(options.solver);
  options.solver_options.tolerance = tolerance;
  return solve_tri_net(boundary_of(net), options);
}

// Relative size of the interior error (the boundary is the same by construction).
double interior_error(const TriNet& a, const TriNet& b) {
  if (interior_size(a.n) == 0) return 0;
  return (interior_of(a) - interior_of(b)).cwiseAbs().maxCoeff();
}

}  // namespace

TEST_CASE("solve_tri_net: c = -1/6 reproduces degree-elevated quadratic patches, degrees 2 to 20", "[tri]") {
  for (int n = 2; n <= 20; ++n) {
    const TriNet q = elevated_quadratic(n, 600 + n);
    const TriNet solved = solve_with(q, -1.0 / 6);
    REQUIRE(max_abs_difference(solved, q) < 1e-10);
    REQUIRE(tri_mask_residual(q, TriMask::quadratic_precision()) < 1e-13);
  }
}

TEST_CASE("solve_tri_net: every other c fails quadratic precision", "[tri]") {
  for (int n = 3; n <= 20; n += 3) {
    const TriNet q = elevated_quadratic(n, 700 + n);
    for (const double c : {-0.17, -0.16, -0.1, 0.0, 0.1, 0.3}) {  // (no singular member: see below)
      const double error = interior_error(solve_with(q, c), q);
      INFO("n = " << n << ", c = " << c << ", error = " << error);
      REQUIRE(error > 1e-4 * std::abs(c + 1.0 / 6));
    }
  }
}

TEST_CASE("tri_mask_residual: on a quadratic net it is affine in c and vanishes only at c = -1/6", "[tri]") {
  for (int n = 3; n <= 20; ++n) {
    const TriNet q = elevated_quadratic(n, 800 + n);
    // residual(c) = b − a(c)ΣN − cΣC is affine in c; zero at −1/6 and non-zero at 0 make −1/6 the only root.
    const double r0 = tri_mask_residual(q, TriMask{0});
    REQUIRE(r0 > 1e-3);
    for (const double c : {-1.0, -0.5, 0.25, 1.0})
      REQUIRE(tri_mask_residual(q, TriMask{c}) == Approx(r0 * std::abs(c + 1.0 / 6) * 6).epsilon(1e-9));
  }
}

TEST_CASE("solve_tri_net: the cubic's centre is 1/4 (edge points) - 1/6 (corners) for c = -1/6", "[tri]") {
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const TriNet net = random_tri_net(3, seed);
    const TriNet solved = solve_with(net, -1.0 / 6);
    const Eigen::RowVector3d edges =
        net.at(2, 1, 0) + net.at(1, 2, 0) + net.at(0, 2, 1) + net.at(0, 1, 2) + net.at(1, 0, 2) + net.at(2, 0, 1);
    const Eigen::RowVector3d corners = net.at(3, 0, 0) + net.at(0, 3, 0) + net.at(0, 0, 3);
    REQUIRE((solved.at(1, 1, 1) - (edges / 4 - corners / 6)).norm() < 1e-14);
    // and for any c: a·edges + c·corners
    const double c = 0.05 * seed - 0.5;
    REQUIRE((solve_with(net, c).at(1, 1, 1) - (TriMask{c}.a() * edges + c * corners)).norm() < 1e-13);
  }
}

TEST_CASE("solve_tri_net: linear precision for every c", "[tri]") {
  for (int n = 3; n <= 20; n += 4)
    for (const double c : {-0.3, -1.0 / 6, 0.0, 0.2}) {
      const TriNet l = elevated_linear(n, 900 + n);
      REQUIRE(interior_error(solve_with(l, c), l) < 1e-10);
    }
}

TEST_CASE("solve_tri_net: affine invariance", "[tri]") {
  Eigen::Matrix3d M;
  M << 2, 0.3, -1, 0.1, -1.5, 0.2, 0.7, 0.4, 3;
  const Eigen::RowVector3d t(5, -2, 0.5);
  for (int n = 3; n <= 20; n += 2)
    for (const double c : {-1.0 / 6, 0.0, 0.15}) {
      const TriNet net = random_tri_net(n, 1000 + n);
      TriNet moved = net;
      moved.points = (net.points * M.transpose()).rowwise() + t;
      TriNet expected = solve_with(net, c);
      expected.points = (expected.points * M.transpose()).rowwise() + t;
      REQUIRE(max_abs_difference(solve_with(moved, c), expected) < 1e-9);
    }
}

TEST_CASE("solve_tri_net: permuting i, j, k permutes the solution", "[tri]") {
  for (int n = 3; n <= 20; n += 3)
    for (const double c : {-1.0 / 6, 0.0, -0.3}) {
      const TriNet net = random_tri_net(n, 1100 + n);
      const TriNet solved = solve_with(net, c);
      for (const auto& perm : all_permutations())
        REQUIRE(max_abs_difference(solve_with(permuted(net, perm), c), permuted(solved, perm)) < 1e-10);
    }
}

TEST_CASE("solve_tri_net: permanence on index sub-triangles", "[tri]") {
  // The sub-net on i >= i0, j >= j0, k >= k0 of a solved net, re-solved from its own boundary,
  // gives back its interior: every mask of the sub-net's interior only reaches into the sub-net.
  std::mt19937 rng(42);
  for (int n = 5; n <= 20; n += 5)
    for (const double c : {-1.0 / 6, 0.0, 0.2}) {
      const TriNet solved = solve_with(random_tri_net(n, 1200 + n), c);
      for (int trial = 0; trial < 6; ++trial) {
        std::uniform_int_distribution<int> pick(0, n - 3);
        const int i0 = pick(rng);
        const int j0 = std::uniform_int_distribution<int>(0, n - 3 - i0)(rng);
        const int k0 = std::uniform_int_distribution<int>(0, n - 3 - i0 - j0)(rng);
        const TriNet sub = sub_net(solved, i0, j0, k0);
        REQUIRE(sub.n >= 3);
        REQUIRE(max_abs_difference(solve_with(sub, c), sub) < 1e-10);
      }
    }
}

TEST_CASE("solve_tri_net: for c = -1/6 every cubic sub-net has the cubic's quadratic-precision centre", "[tri]") {
  // The mask's ten points are the cubic sub-net around b[i][j][k]: its six edge points are the
  // neighbours and its corners the far points, so the solution is the net whose every cubic sub-net
  // is the discrete Coons patch of its own boundary.
  for (const int n : {4, 8, 13}) {
    const TriNet solved = solve_with(random_tri_net(n, 1250 + n), -1.0 / 6);
    for (int k0 = 0; k0 <= n - 3; ++k0)
      for (int j0 = 0; j0 <= n - 3 - k0; ++j0) {
        const TriNet s = sub_net(solved, n - 3 - k0 - j0, j0, k0);
        const Eigen::RowVector3d edges =
            s.at(2, 1, 0) + s.at(1, 2, 0) + s.at(0, 2, 1) + s.at(0, 1, 2) + s.at(1, 0, 2) + s.at(2, 0, 1);
        const Eigen::RowVector3d corners = s.at(3, 0, 0) + s.at(0, 3, 0) + s.at(0, 0, 3);
        REQUIRE((s.at(1, 1, 1) - (edges / 4 - corners / 6)).norm() < 1e-11);
      }
  }
}

TEST_CASE("solve_tri_net: permanence does not hold for de Casteljau subdivision", "[tri]") {
  // The other reading of "permanence" (the patch of a subdivided part's boundary is that part) is
  // false for the mask family: shown at c = -1/6 on a random cubic.
  const TriNet solved = solve_with(random_tri_net(5, 1300), -1.0 / 6);
  const auto parts = subdivide_at(solved, {0.3, 0.3, 0.4});
  REQUIRE(interior_error(solve_with(parts[0], -1.0 / 6), parts[0]) > 1e-6);
}

TEST_CASE("assemble_tri_mask_system: the bubble ijk is a null vector at c = -1/6 - 1/(2(n-3))", "[tri]") {
  // With zero boundary, v_ijk = ijk gives (A v)_ijk = n/3 + 2c(n − 3) at every interior point, so the
  // family is singular at c*_n = −1/6 − 1/(2(n−3)) (n ≥ 4): −2/3, −5/12, −1/3, … → −1/6 from below.
  for (int n = 4; n <= 20; ++n) {
    const TriNet zero(n);
    Eigen::MatrixX3d v(interior_size(n), 3);
    for (int k = 1; k <= n - 2; ++k)
      for (int j = 1; j <= n - 1 - k; ++j) v.row(interior_index(n, j, k)).setConstant(double(n - k - j) * j * k);
    for (const double c : {-1.0 / 6, 0.0, 0.3}) {
      const Eigen::MatrixX3d Av = assemble_tri_mask_system(zero, TriMask{c}).A * v;
      REQUIRE((Av.array() - (n / 3.0 + 2 * c * (n - 3))).abs().maxCoeff() < 1e-11 * n * n * n);
    }
    const double c_star = -1.0 / 6 - 1.0 / (2.0 * (n - 3));
    REQUIRE(bubble_singular_c(n) == c_star);
    const Eigen::MatrixX3d Av = assemble_tri_mask_system(zero, TriMask{c_star}).A * v;
    REQUIRE(Av.cwiseAbs().maxCoeff() < 1e-11 * n * n * n);
    TriSolveOptions options;
    options.mask.c = c_star;
    const TriSolveResult r = solve_tri_net(boundary_of(random_tri_net(n, 1350 + n)), options);
    REQUIRE_FALSE(r.summary.ok());  // reported, not a wrong answer
    REQUIRE(interior_of(r.net).isZero());
    REQUIRE_FALSE(bubble_singular_c(3).has_value());
  }
}

TEST_CASE("assemble_tri_mask_system: no singular member between c*_n and 1/3, degrees 4 to 20", "[tri]") {
  // A(c) = A(0) + c·D is singular exactly when −1/c is a real eigenvalue of A(0)⁻¹D.
  for (int n = 4; n <= 20; ++n) {
    const TriNet zero(n);
    const Eigen::MatrixXd A0(assemble_tri_mask_system(zero, TriMask{0}).A);
    const Eigen::MatrixXd D = Eigen::MatrixXd(assemble_tri_mask_system(zero, TriMask{1}).A) - A0;
    const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(A0.inverse() * D).eigenvalues();
    const double c_star = -1.0 / 6 - 1.0 / (2.0 * (n - 3));
    bool found_c_star = false;
    for (Eigen::Index q = 0; q < lambda.size(); ++q) {
      if (std::abs(lambda(q).imag()) > 1e-8 || std::abs(lambda(q).real()) < 1e-12) continue;
      const double c = -1 / lambda(q).real();
      INFO("n = " << n << ": singular at c = " << c);
      REQUIRE_FALSE((c > c_star + 1e-9 && c <= 1.0 / 3));
      if (std::abs(c - c_star) < 1e-8) found_c_star = true;
    }
    REQUIRE(found_c_star);
  }
}

TEST_CASE("solve_tri_net: degree < 3 has nothing to solve", "[tri]") {
  for (const int n : {1, 2}) {
    const TriNet net = random_tri_net(n, 5);
    const TriSolveResult r = solve_tri_net(boundary_of(net));
    REQUIRE(r.summary.ok());
    REQUIRE(max_abs_difference(r.net, net) == 0.0);
  }
}

TEST_CASE("check_tri_backend: symmetric-only and grid backends are refused for c != 0", "[tri]") {
  for (const auto& info : coons::solvers::available_solvers()) {
    const bool matrix = check_tri_backend(info, TriMask{0}).applicable;  // takes an assembled matrix
    const bool general = matrix && !info.definite_only;
    INFO(info.name);
    if (info.needs_matrix) REQUIRE(matrix);
    REQUIRE(check_tri_backend(info, TriMask{-1.0 / 6}).applicable == general);
    if (!general) REQUIRE_FALSE(check_tri_backend(info, TriMask{0.1}).reason.empty());
  }
  const auto names = tri_applicable_solvers(TriMask{});
  REQUIRE(std::find(names.begin(), names.end(), "eigen-lu") != names.end());
  REQUIRE(std::find(names.begin(), names.end(), "bicgstab") != names.end());
  if (coons::solvers::find_solver("gmres"))  // a grid-stencil backend that also takes a matrix
    REQUIRE(std::find(names.begin(), names.end(), "gmres") != names.end());
  REQUIRE(std::find(names.begin(), names.end(), "eigen-ldlt") == names.end());
  REQUIRE(std::find(names.begin(), names.end(), "cg") == names.end());
  REQUIRE(std::find(names.begin(), names.end(), "jacobi") == names.end());
  const auto& chosen = default_tri_solver();
  REQUIRE((chosen.name == "umfpack" || chosen.name == "eigen-lu"));
  REQUIRE(check_tri_backend(chosen, TriMask{-1.0 / 6}).applicable);
}

TEST_CASE("solve_tri_net: a refused backend reports not_applicable and leaves the interior alone", "[tri]") {
  const TriNet net = random_tri_net(7, 9);
  for (const std::string name : {"eigen-ldlt", "eigen-llt", "cg", "jacobi"}) {
    TriSolveOptions options;
    options.solver = coons::solvers::find_solver(name);
    REQUIRE(options.solver);
    const TriSolveResult r = solve_tri_net(boundary_of(net), options);
    REQUIRE(r.summary.status == SolveStatus::kNotApplicable);
    REQUIRE_FALSE(r.summary.message.empty());
    REQUIRE(interior_of(r.net).isZero());
  }
  TriSolveOptions bad;
  bad.solver = nullptr;
  REQUIRE(solve_tri_net(boundary_of(net), bad).summary.status == SolveStatus::kFailure);
}

TEST_CASE("solve_tri_net: the refusal matters, a Cholesky-type backend is wrong on the c = -1/6 system", "[tri]") {
  const TriNet net = random_tri_net(9, 10);
  const TriMaskSystem sys = assemble_tri_mask_system(net, TriMask::quadratic_precision());
  auto ldlt = coons::solvers::make_solver("eigen-ldlt");
  coons::solvers::LinearOperator op;
  op.matrix = &sys.A;
  Eigen::MatrixX3d X = Eigen::MatrixX3d::Zero(sys.B.rows(), 3);
  const auto summary = ldlt->compute_and_solve(op, sys.B, X);
  const double true_residual = ((sys.A * X - sys.B).norm()) / sys.B.norm();
  INFO("status " << coons::solvers::to_string(summary.status) << ", residual " << true_residual);
  REQUIRE((!summary.ok() || true_residual > 1e-3));
}

TEST_CASE("solve_tri_net: every applicable backend gives the LU solution", "[tri]") {
  for (const double c : {-1.0 / 6, 0.0, 0.1}) {
    const TriNet net = random_tri_net(14, 1400);
    const TriNet reference = solve_with(net, c);
    for (const auto& name : tri_applicable_solvers(TriMask{c})) {
      INFO(name << " at c = " << c);
      const TriSolveResult r = solve_by(net, c, name, 1e-13);
      REQUIRE(r.summary.ok());
      REQUIRE(max_abs_difference(r.net, reference) < 1e-9);
      REQUIRE(tri_mask_residual(r.net, TriMask{c}) < 1e-9);
    }
  }
}

TEST_CASE("solve_tri_net: a singular member outside c*_n < c <= 1/3 is refused, on a flat triangle too", "[tri]") {
  // n = 8, c = 1 and n = 6, c = 2/3 make A singular for every boundary. On a linear (flat) net the
  // system is consistent: each backend used to return one of many nets with residual 1e-15 and
  // call it a success (thin-plate energy 19 to 40,000 where the flat net has 0).
  for (const auto& [n, c] : {std::pair{8, 1.0}, std::pair{6, 2.0 / 3}}) {
    REQUIRE_FALSE(in_regular_c_range(n, TriMask{c}));
    const TriNet flat = elevated_linear(n, 1500 + n);
    for (const auto& name : tri_applicable_solvers(TriMask{c})) {
      INFO(name << ", n = " << n << ", c = " << c);
      const TriSolveResult r = solve_by(flat, c, name);
      INFO(r.summary.brief_report());
      REQUIRE_FALSE(r.summary.ok());
      CHECK(r.summary.relative_residual == 1);  // X = 0, not solved
      CHECK(r.net.at(1, 1, n - 2).isZero(0));   // the interior is left as the frame has it
    }
  }
}

TEST_CASE("solve_tri_net: a member just above c*_n is as near singular as one just below, and refused alike", "[tri]") {
  // Only members outside (c*_n, 1/3] were checked: c*_6 + 3.3e-10 (min|λ|/‖A‖₁ about 1e-10) came
  // back a success with a net 4.7e-7 off and coordinates of 5e8, c*_6 − 1e-8 singular.
  const int n = 6;
  const double star = *bubble_singular_c(n);
  const TriNet net = random_tri_net(n, 1700);
  for (const double offset : {3.3e-10, 1e-8, -1e-8}) {
    const double c = star + offset;
    INFO("c = c*_6 + " << offset);
    CHECK(in_regular_c_range(n, TriMask{c}) == (offset > 0));
    const TriSolveResult r = solve_by(net, c, "eigen-lu");
    CHECK(r.summary.status == SolveStatus::kSingular);
    CHECK(r.summary.relative_residual == 1);
  }
  // well inside the interval the check passes and the member is solved
  const TriSolveResult inside = solve_by(net, -0.1, "eigen-lu");
  CHECK(inside.summary.ok());
}

TEST_CASE("solve_tri_net: a regular member outside c*_n < c <= 1/3 is still solved", "[tri]") {
  // c = 0.9 at n = 8 lies between the singular members 0.50 and 1 (generalised eigenvalues of the
  // pencil); c = -0.3 at n = 8 below c*_8 = -0.2667 and above the next singular member -0.7267.
  for (const double c : {0.9, -0.3}) {
    REQUIRE_FALSE(in_regular_c_range(8, TriMask{c}));
    const TriNet l = elevated_linear(8, 1600);
    for (const auto& name : tri_applicable_solvers(TriMask{c})) {
      INFO(name << ", c = " << c);
      const TriSolveResult r = solve_by(l, c, name, 1e-13);
      INFO(r.summary.brief_report());
      REQUIRE(r.summary.ok());
      CHECK(interior_error(r.net, l) < 1e-9);
    }
  }
}

TEST_CASE("in_regular_c_range: c*_n < c <= 1/3, and any c up to 1/3 for n < 4", "[tri]") {
  CHECK(in_regular_c_range(8, TriMask{1.0 / 3}));
  CHECK_FALSE(in_regular_c_range(8, TriMask{std::nextafter(1.0 / 3, 1.0)}));
  CHECK(in_regular_c_range(8, TriMask{-0.26}));
  CHECK_FALSE(in_regular_c_range(8, TriMask{-1.0 / 6 - 1.0 / 10}));  // c*_8 itself
  CHECK(in_regular_c_range(3, TriMask{-5}));
}
