// Multigrid, multigrid-preconditioned CG and GMRES on grid stencils (3×3 and 5×5, full rectangles
// and free sets), against sparse direct solves; symmetry of the V-cycle; iteration counts; the fast
// paths of the levels (common-stencil stretches, shared line factors, restriction table) against
// written-out references, bit for bit.
#include "solvers/multigrid.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "solvers/gmres.h"
#include "solvers/multigrid_kernels.h"
#include "solvers/multigrid_levels.h"
#include "solvers/multigrid_solvers.h"
#include "solvers/registry.h"
#include "solvers/stencil_operator.h"
#include "support/grid_fixtures.h"

using namespace coons::solvers;
using namespace coons::test;

TEST_CASE("apply_stencil_operator: equals the product with stencil_operator_matrix on a masked 5x5 stencil",
          "[solvers][mg]") {
  StencilOperator op = make_stencil_operator(9, 7, biharmonic());
  op.weights[3] = 0.7;  // make it nonsymmetric: w(−2, 1) ≠ w(2, −1)
  op.free = shape_mask(Shape::kHole, 9, 7);
  REQUIRE(op.is_valid(nullptr));
  CHECK(!op.symmetric());
  const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
  REQUIRE(A.rows() == op.size());
  REQUIRE(op.size() < 63);
  const Eigen::MatrixXd X = Eigen::MatrixXd::Random(op.size(), 3);
  Eigen::MatrixXd Y;
  apply_stencil_operator(op, X, Y);
  CHECK((Y - A * X).cwiseAbs().maxCoeff() < 1e-13);
  // The 3×3 GridStencil and its operator give the same matrix.
  const GridStencil s{6, 5, 1.0, -0.3, -0.2, 0.05};
  CHECK((Eigen::MatrixXd(stencil_matrix(s)) - Eigen::MatrixXd(stencil_operator_matrix(stencil_operator(s)))).norm() ==
        0);
}

TEST_CASE("apply_stencil_operator: the row-by-row products equal a coupling-by-coupling loop bit for bit",
          "[solvers][mg]") {
  // The reference: every free point sums w(di, dj)·x over its free neighbours, (di, dj) in
  // increasing order, as the function did before its row-by-row passes.
  auto reference = [](const StencilOperator& op, const Eigen::MatrixXd& X) {
    const std::vector<Eigen::Index> number = free_numbering(op);
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(X.rows(), X.cols());
    const int r = op.radius;
    for (int i = 0; i < op.rows; ++i)
      for (int j = 0; j < op.cols; ++j) {
        const Eigen::Index row = number[std::size_t(i) * op.cols + j];
        if (row < 0) continue;
        for (int di = -r; di <= r; ++di)
          for (int dj = -r; dj <= r; ++dj) {
            const int ii = i + di, jj = j + dj;
            if (ii < 0 || ii >= op.rows || jj < 0 || jj >= op.cols) continue;
            const Eigen::Index col = number[std::size_t(ii) * op.cols + jj];
            const double w = op.weight(di, dj);
            if (col >= 0 && w != 0) Y.row(row) += w * X.row(col);
          }
      }
    return Y;
  };
  for (const auto& [rows, cols] : std::vector<std::pair<int, int>>{{1, 1}, {2, 9}, {9, 7}, {31, 40}}) {
    for (const std::vector<double>& weights :
         {biharmonic(), std::vector<double>{0.05, -0.3, 0.05, -0.2, 1.0, -0.2, 0.05, -0.3, 0.05}}) {
      for (const Shape shape : {Shape::kFull, Shape::kHole, Shape::kLShape}) {
        if (shape != Shape::kFull && (rows < 9 || cols < 7)) continue;
        INFO(rows << " x " << cols << ", radius " << (weights.size() == 25 ? 2 : 1) << ", shape " << int(shape));
        StencilOperator op = make_stencil_operator(rows, cols, weights);
        op.weights[1] = 0.7;  // nonsymmetric, and a weight that is not a round number
        if (shape != Shape::kFull) op.free = shape_mask(shape, rows, cols);
        REQUIRE(op.is_valid(nullptr));
        Eigen::MatrixXd X = Eigen::MatrixXd::Random(op.size(), 3);
        X(0, 0) = -0.0;
        Eigen::MatrixXd Y;
        apply_stencil_operator(op, X, Y);
        CHECK(Y == reference(op, X));
      }
    }
  }
}

TEST_CASE("StencilOperator::is_valid: rejects wrong sizes and radii", "[solvers][mg]") {
  std::string why;
  StencilOperator op = make_stencil_operator(5, 4, nine_point(1, -0.25, 0));
  CHECK(op.is_valid(&why));
  op.weights.pop_back();
  CHECK(!op.is_valid(&why));
  CHECK_THAT(why, Catch::Contains("weights"));
  op = make_stencil_operator(5, 4, nine_point(1, -0.25, 0));
  op.free.assign(7, 1);
  CHECK(!op.is_valid(&why));
  op.free.clear();
  op.radius = 3;
  CHECK(!op.is_valid(&why));
}

namespace {

// The weights divided by their centre, as the mask layer stores them (c1-coons: 1/36 rounded).
std::vector<double> centre_one(std::vector<double> w) {
  const double centre = w[w.size() / 2];
  for (double& v : w) v /= centre;
  return w;
}

}  // namespace

TEST_CASE("integer_separable_form: finds the integer factors of c1-coons and of the alpha = -1/4 mask, none elsewhere",
          "[solvers][mg]") {
  const auto c1 = integer_separable_form(make_stencil_operator(9, 7, centre_one(c1_coons())));
  REQUIRE(c1);
  CHECK(c1->along_i == std::vector<double>{1, -4, 6, -4, 1});
  CHECK(c1->along_j == std::vector<double>{1, -4, 6, -4, 1});
  CHECK(c1->scale == Approx(1.0 / 36).epsilon(1e-15));
  // the stored weights sum to rounding, the integer form to exactly 0
  double stored = 0, exact = 0;
  for (double w : centre_one(c1_coons())) stored += w;
  for (double a : c1->along_i)
    for (double b : c1->along_j) exact += a * b;
  CHECK(exact == 0);
  CHECK(stored != 0);
  const auto quarter = integer_separable_form(make_stencil_operator(6, 5, nine_point(1, -0.5, 0.25)));
  REQUIRE(quarter);
  CHECK(quarter->along_i == std::vector<double>{-1, 2, -1});
  CHECK(quarter->scale == 0.25);
  CHECK(!integer_separable_form(make_stencil_operator(9, 7, centre_one(biharmonic()))));
  CHECK(!integer_separable_form(make_stencil_operator(6, 5, nine_point(1, -0.25, 0))));
  // separable, but the ratio of its entries is not an integer: π
  const double pi = std::acos(-1.0);
  CHECK(!integer_separable_form(make_stencil_operator(6, 5, {pi * pi, pi, pi * pi, pi, 1, pi, pi * pi, pi, pi * pi})));
}

TEST_CASE("Multigrid::apply: c1-coons annihilates a grid cubic in each index exactly, the rounded weights do not",
          "[solvers][mg]") {
  // δ⁴ ⊗ δ⁴ is 0 on a cubic in each index wherever the 5×5 stencil stays in the grid. The values
  // are integers below 2⁵³ and so are the factored sums, which are therefore exact; the 25 stored
  // weights (1/36 … rounded) sum to 2⁻⁵⁴ and leave rounding of the size of the values.
  const int N = 63;
  const StencilOperator op = make_stencil_operator(N, N, centre_one(c1_coons()));
  Eigen::VectorXd x(Eigen::Index(N) * N);
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j)
      x[Eigen::Index(i) * N + j] = double(i * i * i - 7 * i * i + 3) * double(j * j * j + 2 * j - 5);
  Multigrid mg;
  REQUIRE(mg.setup(op) == SolveStatus::kSuccess);
  Eigen::VectorXd y;
  mg.apply(x, y);
  Eigen::MatrixXd rounded;
  apply_stencil_operator(op, x, rounded);
  double factored_inside = 0, rounded_inside = 0, boundary = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      const Eigen::Index k = Eigen::Index(i) * N + j;
      if (i >= 2 && i < N - 2 && j >= 2 && j < N - 2) {
        factored_inside = std::max(factored_inside, std::abs(y[k]));
        rounded_inside = std::max(rounded_inside, std::abs(rounded(k, 0)));
      } else {
        boundary = std::max(boundary, std::abs(y[k] - rounded(k, 0)));
      }
    }
  CHECK(factored_inside == 0);
  CHECK(rounded_inside > 0);
  // near the edge, where the product is not 0, both forms agree to rounding of the values' size
  CHECK(boundary < 1e-14 * x.cwiseAbs().maxCoeff());
  CHECK(y.cwiseAbs().maxCoeff() > 1e-3 * x.cwiseAbs().maxCoeff());
}

TEST_CASE("multigrid backends: agree with a sparse direct solve on 3x3 and 5x5 stencils and free sets",
          "[solvers][mg]") {
  SolverOptions options;
  options.tolerance = 1e-11;
  for_each_reference_problem([&](const ReferenceProblem& p) {
    LinearOperator lop;
    lop.matrix = &p.A;
    lop.grid = &p.op;
    // Solutions agree to the condition number: O(N²) for the second-order stencils, O(N⁴)
    // at α = −1/4 and for the biharmonic, O(N⁸) for c1-coons.
    const std::string& stencil = p.stencil->name;
    const double error_bound = stencil == "c1-coons" ? 1e-4 : p.op.radius == 2 || stencil == "alpha -1/4" ? 1e-6 : 1e-8;
    for (const char* name : {"mg", "mg-cg", "gmres"}) {
      Eigen::MatrixX3d X;
      const SolveSummary s = make_solver(name, options)->compute_and_solve(lop, p.B, X);
      INFO(name << " on " << p.label() << ": " << s.brief_report());
      REQUIRE(s.ok());
      CHECK(s.relative_residual < 1e-10);
      CHECK(max_relative_error(X, p.reference) < error_bound);
      // The stationary iteration on c1-coons with a re-entrant corner or a hole is the one slow
      // case (a few modes near the corner; CG removes them): measured 95 cycles at 30x41.
      const bool slow = std::string(name) == "mg" && stencil == "c1-coons" && p.shape != Shape::kFull;
      CHECK(s.iterations <= (slow ? 200 : 40));
    }
  });
}

TEST_CASE("multigrid backends: one two and three threads give the same solution bit for bit", "[solvers][mg]") {
  // The threaded loops (residual, restriction, operator) write disjoint points: no reordering of
  // sums. With two threads two columns of B are solved side by side and the third with the level
  // loops on both threads; with three, all three side by side.
  for (Shape shape : {Shape::kFull, Shape::kHole})
    for (const NamedStencil& stencil : symmetric_stencils()) {
      StencilOperator op = make_stencil_operator(63, 57, stencil.weights);
      op.free = shape_mask(shape, 63, 57);
      const Eigen::MatrixX3d B = boundary_rhs(op);
      LinearOperator lop;
      lop.grid = &op;
      for (const char* name : {"mg", "mg-cg", "gmres"}) {
        SolverOptions one;
        one.tolerance = 1e-10;
        Eigen::MatrixX3d X1;
        const SolveSummary s1 = make_solver(name, one)->compute_and_solve(lop, B, X1);
        for (int threads : {2, 3}) {
          SolverOptions more = one;
          more.threads = threads;
          Eigen::MatrixX3d X2;
          const SolveSummary s2 = make_solver(name, more)->compute_and_solve(lop, B, X2);
          INFO(name << " on " << stencil.name << ", shape " << int(shape) << ", " << threads
                    << " threads: " << s1.brief_report() << " / " << s2.brief_report());
          CHECK(s1.status == s2.status);
          CHECK(s1.iterations == s2.iterations);
          CHECK(s1.message == s2.message);
          CHECK(X1 == X2);
        }
      }
    }
}

TEST_CASE(
    "multigrid backends: stop at SolverOptions::time_limit_seconds with not_converged, their best iterate and its "
    "residual",
    "[solvers][mg]") {
  // A limit already passed after the first iteration: each column stops after one cycle or
  // iteration (the time is checked after it), says so, and returns an iterate better than x = 0.
  StencilOperator op = make_stencil_operator(63, 57, symmetric_stencils().front().weights);
  const Eigen::MatrixX3d B = boundary_rhs(op);
  const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
  LinearOperator lop;
  lop.grid = &op;
  for (const char* name : {"mg", "mg-cg", "gmres"}) {
    SolverOptions options;
    options.tolerance = 1e-14;
    options.time_limit_seconds = 1e-9;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(name, options)->compute_and_solve(lop, B, X);
    INFO(name << ": " << s.brief_report() << " " << s.message);
    CHECK(s.status == SolveStatus::kNotConverged);
    CHECK(s.message.find("time limit") != std::string::npos);
    CHECK_THAT(s.message, Catch::StartsWith("right-hand side 1 of 3: "));  // the column it speaks of
    CHECK(s.iterations >= 1);
    CHECK(s.iterations <= 2);
    CHECK((A * X - B).norm() < 0.5 * B.norm());
    // the residual it reached, not 0: the report of a solve that stopped early
    double reached = 0;
    for (int c = 0; c < 3; ++c) reached = std::max(reached, (A * X.col(c) - B.col(c)).norm() / B.col(c).norm());
    CHECK(s.relative_residual > 0);
    CHECK(s.relative_residual == Approx(reached).epsilon(1e-6));
  }
}

TEST_CASE("Multigrid::precondition: a V-cycle is a symmetric positive definite operator", "[solvers][mg]") {
  for (const NamedStencil& stencil : symmetric_stencils()) {
    StencilOperator op = make_stencil_operator(37, 29, stencil.weights);
    op.free = shape_mask(Shape::kHole, 37, 29);
    Multigrid mg;
    MultigridOptions options;
    options.coarsest_unknowns = 20;
    // As the backends: two sweeps per side at radius 2 (with one, the multicolour line smoother
    // leaves c1-coons on this holed grid converging by a factor 0.9 per V-cycle after the first ones).
    options.pre_smoothing = options.post_smoothing = op.radius;
    REQUIRE(mg.setup(op, options) == SolveStatus::kSuccess);
    REQUIRE(mg.levels().size() >= 3);
    const Eigen::VectorXd x = Eigen::VectorXd::Random(mg.size()), y = Eigen::VectorXd::Random(mg.size());
    Eigen::VectorXd Mx, My;
    mg.precondition(x, Mx);
    mg.precondition(y, My);
    INFO(stencil.name);
    CHECK(std::abs(y.dot(Mx) - x.dot(My)) < 1e-12 * Mx.norm() * y.norm());
    CHECK(x.dot(Mx) > 0);  // and positive definite
    // An F-cycle is not symmetric in general, but it is a (better) solver.
    options.cycle = CycleType::kF;
    Multigrid mgf;
    REQUIRE(mgf.setup(op, options) == SolveStatus::kSuccess);
    const Eigen::VectorXd b = boundary_rhs(op).col(0);
    Eigen::VectorXd xv, xf;
    const IterationSummary v = mg.solve(b, xv), f = mgf.solve(b, xf);
    REQUIRE(v.ok());
    REQUIRE(f.ok());
    CHECK(f.iterations <= v.iterations);
  }
}

TEST_CASE(
    "multigrid backends: mg within 10 cycles on second-order stencils and mg-cg within 40 iterations on fourth-order "
    "ones at 63x63",
    "[solvers][mg]") {
  SolverOptions options;
  options.tolerance = 1e-10;
  for (const NamedStencil& stencil : symmetric_stencils()) {
    const StencilOperator op = make_stencil_operator(63, 63, stencil.weights);
    const Eigen::MatrixX3d B = boundary_rhs(op);
    LinearOperator lop;
    lop.grid = &op;
    const bool second_order = stencil.name == "laplace" || stencil.name == "alpha -0.1";
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(second_order ? "mg" : "mg-cg", options)->compute_and_solve(lop, B, X);
    INFO(stencil.name << ": " << s.brief_report());
    REQUIRE(s.ok());
    CHECK(s.relative_residual <= 1e-10);
    CHECK(s.iterations <= (second_order ? 10 : 40));
  }
}

TEST_CASE("multigrid_cg: iteration counts stay bounded from 31x31 to 511x511", "[solvers][mg][slow]") {
  IterationOptions iteration;
  iteration.tolerance = 1e-10;
  iteration.max_iterations = 100;
  for (const NamedStencil& stencil : symmetric_stencils())
    for (int N : {31, 63, 127, 255, 511}) {
      const StencilOperator op = make_stencil_operator(N, N, stencil.weights);
      Multigrid mg;
      MultigridOptions options;  // as the backends: one sweep per side at radius 1, two at radius 2
      options.pre_smoothing = options.post_smoothing = op.radius;
      REQUIRE(mg.setup(op, options) == SolveStatus::kSuccess);
      const Eigen::VectorXd b = boundary_rhs(op).col(0);
      Eigen::VectorXd x_mg, x_cg;
      const IterationSummary v = mg.solve(b, x_mg, iteration), c = multigrid_cg(mg, b, x_cg, iteration);
      WARN(stencil.name << " N = " << N << ": mg " << v.iterations << " cycles (factor " << v.convergence_factor()
                        << "), mg-cg " << c.iterations << " iterations (factor " << c.convergence_factor() << ")");
      CHECK(c.ok());
      CHECK(c.iterations <= 40);
      if (stencil.name == "laplace" || stencil.name == "alpha -0.1") CHECK(v.iterations <= 10);
    }
}

TEST_CASE("Multigrid: a fixed margin around the free points changes neither the iterations nor the solution",
          "[solvers][mg]") {
  for (const NamedStencil& stencil : symmetric_stencils()) {
    const int N = 45, rings = stencil.weights.size() == 25 ? 2 : 1, R = N + 2 * rings;
    const StencilOperator bare = make_stencil_operator(N, N, stencil.weights);
    StencilOperator padded = make_stencil_operator(R, R, stencil.weights);
    padded.free.assign(std::size_t(R) * R, 0);
    for (int i = rings; i < R - rings; ++i)
      for (int j = rings; j < R - rings; ++j) padded.free[std::size_t(i) * R + j] = 1;
    REQUIRE(padded.size() == bare.size());
    const Eigen::VectorXd b = boundary_rhs(bare).col(0);
    Multigrid mg_bare, mg_padded;
    REQUIRE(mg_bare.setup(bare) == SolveStatus::kSuccess);
    REQUIRE(mg_padded.setup(padded) == SolveStatus::kSuccess);
    Eigen::VectorXd x_bare, x_padded;
    const IterationSummary s_bare = multigrid_cg(mg_bare, b, x_bare), s_padded = multigrid_cg(mg_padded, b, x_padded);
    INFO(stencil.name << ": " << s_bare.iterations << " / " << s_padded.iterations);
    REQUIRE(s_bare.ok());
    REQUIRE(s_padded.ok());
    CHECK(s_padded.iterations == s_bare.iterations);
    // Equal up to rounding (sums run in another order), amplified by the condition number.
    CHECK(max_relative_error(x_padded, x_bare) < (stencil.name == "c1-coons" ? 1e-6 : 1e-9));
  }
}

TEST_CASE("Multigrid::solve: stops with not_converged when the residual stalls", "[solvers][mg]") {
  // c1-coons with rough data on the outer ring: the rounding floor of the residual lies near 1e-9
  // at this size (a sparse Cholesky solve ends there too), far above the tolerance asked for.
  const StencilOperator op = make_stencil_operator(63, 63, c1_coons());
  Eigen::VectorXd b = Eigen::VectorXd::Zero(op.size());
  for (int i = 0; i < 63; ++i)
    for (int j = 0; j < 63; ++j)
      if (i == 0 || j == 0 || i == 62 || j == 62) b[i * 63 + j] = std::cos(0.1 * i + 0.2 * j);
  Multigrid mg;
  REQUIRE(mg.setup(op) == SolveStatus::kSuccess);
  IterationOptions options;
  options.tolerance = 1e-14;
  options.max_iterations = 400;
  Eigen::VectorXd x;
  const IterationSummary s = mg.solve(b, x, options);
  INFO(s.message);
  CHECK(s.status == SolveStatus::kNotConverged);
  CHECK_THAT(s.message, Catch::Contains("rounding floor"));
  CHECK(s.iterations < 400);
  CHECK(x.allFinite());
  CHECK(s.relative_residual < 1e-6);
}

TEST_CASE("multigrid_cg: stops at the rounding floor with its best iterate when the tolerance is below it",
          "[solvers][mg]") {
  // α = −1/4 with data from a smooth function: b holds second differences of it, so the floor
  // ε(Σ|w| ‖x‖ + ‖b‖)/‖b‖ lies far above 1e-16. Continued CG let the true residual grow again
  // (2e-12 to 7e-11 at 1023x1023); restarting from the true residual ends at the floor instead.
  const StencilOperator op = make_stencil_operator(127, 127, nine_point(1, -0.5, 0.25));
  const Eigen::VectorXd b = boundary_rhs(op).col(2);
  Multigrid mg;
  REQUIRE(mg.setup(op) == SolveStatus::kSuccess);
  IterationOptions options;
  options.tolerance = 1e-17;
  options.max_iterations = 200;
  Eigen::VectorXd x;
  const IterationSummary s = multigrid_cg(mg, b, x, options);
  INFO(s.message);
  CHECK(s.status == SolveStatus::kNotConverged);
  CHECK_THAT(s.message, Catch::Contains("rounding floor"));
  CHECK(s.iterations < 40);
  CHECK(x.allFinite());
  CHECK(s.relative_residual < 1e-11);
  // The same system to 1e-10 succeeds well before.
  options.tolerance = 1e-10;
  Eigen::VectorXd y;
  const IterationSummary ok = multigrid_cg(mg, b, y, options);
  CHECK(ok.ok());
  CHECK(ok.iterations < s.iterations);
}

TEST_CASE("gmres: solves a nonsymmetric convection-diffusion stencil like a dense LU", "[solvers][mg]") {
  // −Δu + c·∇u with upwinded convection: w(0,0) = 4 + c_i + c_j, w(−1,0) = −1 − c_i, w(0,−1) = −1 − c_j.
  const double ci = 1.5, cj = 0.8;
  for (Shape shape : {Shape::kFull, Shape::kHole}) {
    StencilOperator op = make_stencil_operator(26, 19, {0, -1 - ci, 0, -1 - cj, 4 + ci + cj, -1, 0, -1, 0});
    op.free = shape_mask(shape, 26, 19);
    REQUIRE(!op.symmetric());
    const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
    const Eigen::MatrixXd B = Eigen::MatrixXd::Random(A.rows(), 3);
    const Eigen::MatrixXd reference = Eigen::MatrixXd(A).fullPivLu().solve(B);
    GmresOptions options;
    options.restart = 20;
    options.iteration.tolerance = 1e-12;
    std::string message;
    const VectorMap ilu = ilut_preconditioner(A, &message);
    REQUIRE(ilu);
    Multigrid mg;
    REQUIRE(mg.setup(op) == SolveStatus::kSuccess);
    const VectorMap apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = A * in; };
    const VectorMap cycle = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { mg.precondition(in, out); };
    int plain_iterations = 0;
    for (int c = 0; c < 3; ++c) {
      Eigen::VectorXd x_plain, x_ilu, x_mg;
      const IterationSummary plain = gmres(apply, {}, B.col(c), x_plain, options);
      const IterationSummary with_ilu = gmres(apply, ilu, B.col(c), x_ilu, options);
      const IterationSummary with_mg = gmres(apply, cycle, B.col(c), x_mg, options);
      INFO("shape " << int(shape) << ", column " << c << ": " << plain.iterations << " / " << with_ilu.iterations
                    << " / " << with_mg.iterations << " iterations");
      REQUIRE(plain.ok());
      REQUIRE(with_ilu.ok());
      REQUIRE(with_mg.ok());
      for (const Eigen::VectorXd* x : {&x_plain, &x_ilu, &x_mg}) {
        CHECK((*x - reference.col(c)).cwiseAbs().maxCoeff() < 1e-9 * reference.col(c).cwiseAbs().maxCoeff());
        CHECK((A * *x - B.col(c)).norm() <= 1.01e-12 * B.col(c).norm());
      }
      CHECK(with_ilu.iterations < plain.iterations);
      CHECK(with_mg.iterations < plain.iterations);
      plain_iterations = std::max(plain_iterations, plain.iterations);
    }
    CHECK(plain_iterations > options.restart);  // the restarts were exercised
    // The backend: ILUT on the matrix, given or assembled from the (nonsymmetric) grid.
    LinearOperator with_grid, matrix_only;
    with_grid.grid = &op;
    matrix_only.matrix = &A;
    SolverOptions so;
    so.tolerance = 1e-12;
    for (const LinearOperator* lop : {&with_grid, &matrix_only}) {
      Eigen::MatrixX3d X;
      const SolveSummary s = make_solver("gmres", so)->compute_and_solve(*lop, B, X);
      INFO(s.brief_report());
      REQUIRE(s.ok());
      CHECK(max_relative_error(X, reference) < 1e-9);
    }
  }
}

TEST_CASE("gmres: an Arnoldi direction made of rounding is a breakdown, not a basis vector", "[solvers][mg]") {
  // [[1, 1], [1, 1 + 1e-10]], b = (1, −1): x = (2e10, −2e10). The Krylov space of A M⁻¹ is the whole
  // plane after two steps; what the third step orthogonalises is rounding of A z. Taken as a
  // direction, it made the least-squares problem ill-posed: ten more steps near 1e-6, then a residual
  // of 1e25 and `diverged`, with ILUT and without.
  Eigen::SparseMatrix<double> A(2, 2);
  A.insert(0, 0) = 1;
  A.insert(0, 1) = 1;
  A.insert(1, 0) = 1;
  A.insert(1, 1) = 1 + 1e-10;
  A.makeCompressed();
  const Eigen::Vector2d b(1, -1);
  const Eigen::Vector2d exact = Eigen::Matrix2d(A).fullPivLu().solve(b);
  const VectorMap apply = [&](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = A * in; };
  std::string message;
  const VectorMap ilu = ilut_preconditioner(A, &message);
  REQUIRE(ilu);
  for (const VectorMap* precondition : {&ilu, static_cast<const VectorMap*>(nullptr)}) {
    Eigen::VectorXd x;
    const IterationSummary s = gmres(apply, precondition ? *precondition : VectorMap{}, b, x);
    INFO(s.message);
    CHECK(s.ok());
    CHECK(s.iterations <= 2);
    // κ∞ = 4e10: the forward error may be κε relative, the residual is at rounding.
    CHECK((x - exact).cwiseAbs().maxCoeff() <= 1e-5 * exact.cwiseAbs().maxCoeff());
    CHECK((b - A * x).norm() <= 1e-10 * b.norm());
  }
}

TEST_CASE("gmres: unusable options are a failure that says why, before any iteration", "[solvers][mg]") {
  // GmresOptions::is_valid was never called: a restart of 0, which it rejects, was used as given
  const Eigen::Vector2d b(1, 2);
  const VectorMap identity = [](const Eigen::VectorXd& in, Eigen::VectorXd& out) { out = in; };
  for (const int restart : {0, -3}) {
    GmresOptions options;
    options.restart = restart;
    Eigen::VectorXd x = Eigen::VectorXd::Ones(2);  // an initial guess of the right size
    const IterationSummary s = gmres(identity, VectorMap{}, b, x, options);
    INFO(s.message);
    CHECK(s.status == SolveStatus::kFailure);
    CHECK(s.message == "invalid options: restart must be >= 1");
    CHECK(s.iterations == 0);
    CHECK(x.isZero(0));               // x = 0 is returned,
    CHECK(s.relative_residual == 1);  // with its residual
  }
  GmresOptions usable;
  Eigen::VectorXd x;
  CHECK(gmres(identity, VectorMap{}, b, x, usable).ok());
  CHECK(x.isApprox(Eigen::VectorXd(b)));
}

TEST_CASE("multigrid backends: report not_applicable instead of a wrong answer", "[solvers][mg]") {
  const StencilOperator laplace = make_stencil_operator(12, 9, nine_point(1, -0.25, 0));
  const Eigen::SparseMatrix<double> A = stencil_operator_matrix(laplace);
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(A.rows(), 3);
  Eigen::MatrixX3d X;
  LinearOperator matrix_only;
  matrix_only.matrix = &A;
  for (const char* name : {"mg", "mg-cg"}) {
    const SolveSummary s = make_solver(name)->compute_and_solve(matrix_only, B, X);
    INFO(s.brief_report());
    CHECK(s.status == SolveStatus::kNotApplicable);
    CHECK_THAT(s.message, Catch::Contains("grid stencil"));
  }
  CHECK(make_solver("gmres")->compute_and_solve(LinearOperator{}, B, X).status == SolveStatus::kNotApplicable);
  // CG needs symmetry.
  const StencilOperator convection = make_stencil_operator(12, 9, {0, -2, 0, -1, 5, -1, 0, -1, 0});
  LinearOperator nonsymmetric;
  nonsymmetric.grid = &convection;
  for (const char* name : {"mg", "mg-cg"}) {
    const SolveSummary s = make_solver(name)->compute_and_solve(nonsymmetric, B, X);
    CHECK(s.status == SolveStatus::kNotApplicable);
    CHECK_THAT(s.message, Catch::Contains("symmetric"));
  }
  // A matrix and a grid that disagree in size.
  const StencilOperator other = make_stencil_operator(12, 8, nine_point(1, -0.25, 0));
  LinearOperator mismatch;
  mismatch.matrix = &A;
  mismatch.grid = &other;
  CHECK(make_solver("mg")->compute_and_solve(mismatch, B, X).status == SolveStatus::kNotApplicable);
  // An indefinite operator: CG says so; the stationary iteration does not claim success.
  StencilOperator indefinite = make_stencil_operator(40, 40, nine_point(1, -0.65, 0.4));
  LinearOperator lop;
  lop.grid = &indefinite;
  const Eigen::MatrixX3d Bi = boundary_rhs(indefinite);
  const SolveSummary icg = make_solver("mg-cg")->compute_and_solve(lop, Bi, X);
  INFO(icg.brief_report());
  CHECK(icg.status == SolveStatus::kNotPositiveDefinite);
  const SolveSummary img = make_solver("mg")->compute_and_solve(lop, Bi, X);
  INFO(img.brief_report());
  if (img.ok()) CHECK(img.relative_residual < 1e-10);
  CHECK(std::isfinite(img.relative_residual));
}

TEST_CASE("multigrid backends: solve tiny and thin grids and a grid without free points", "[solvers][mg]") {
  SolverOptions options;
  options.tolerance = 1e-12;
  for (const NamedStencil& stencil : symmetric_stencils())
    for (auto [rows, cols] : {std::pair{1, 1}, {1, 9}, {2, 2}, {3, 200}, {150, 4}}) {
      const StencilOperator op = make_stencil_operator(rows, cols, stencil.weights);
      const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
      const Eigen::MatrixX3d B = boundary_rhs(op);
      const Eigen::MatrixX3d reference = Eigen::SparseLU<Eigen::SparseMatrix<double>>(A).solve(B);
      LinearOperator lop;
      lop.grid = &op;
      for (const char* name : {"mg", "mg-cg", "gmres"}) {
        Eigen::MatrixX3d X;
        const SolveSummary s = make_solver(name, options)->compute_and_solve(lop, B, X);
        INFO(name << " on " << stencil.name << ", " << rows << "x" << cols << ": " << s.brief_report());
        REQUIRE(s.ok());
        CHECK(max_relative_error(X, reference) < 1e-6);
      }
    }
  StencilOperator none = make_stencil_operator(4, 5, nine_point(1, -0.25, 0));
  none.free.assign(20, 0);
  LinearOperator lop;
  lop.grid = &none;
  for (const char* name : {"mg", "mg-cg", "gmres"}) {
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(name)->compute_and_solve(lop, Eigen::MatrixX3d(0, 3), X);
    INFO(name << ": " << s.brief_report());
    CHECK(s.status != SolveStatus::kSuccess);  // nothing to solve: reported, not crashed
    CHECK(X.rows() == 0);
  }
}

TEST_CASE("Multigrid::setup: a line block with a zero pivot is not_applicable, not singular", "[solvers][mg]") {
  // (1, −2, 1) ⊗ (1, 1, 1) on 11 × 6: the row lines are toeplitz(−2, −2), whose elimination
  // without pivoting meets a zero pivot, though A is regular (it was reported singular).
  const StencilOperator op = make_stencil_operator(11, 6, {1, 1, 1, -2, -2, -2, 1, 1, 1});
  REQUIRE(op.is_valid(nullptr));
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(stencil_operator_matrix(op));
  REQUIRE(lu.info() == Eigen::Success);
  Multigrid mg;
  std::string message;
  CHECK(mg.setup(op, {}, &message) == SolveStatus::kNotApplicable);
  CHECK(message.find("zero pivot") != std::string::npos);
  LinearOperator lin;
  lin.grid = &op;
  Eigen::MatrixX3d X;
  const SolveSummary s = make_solver("mg")->compute_and_solve(lin, Eigen::MatrixX3d::Ones(op.size(), 3), X);
  INFO(s.brief_report());
  CHECK(s.status == SolveStatus::kNotApplicable);
}

TEST_CASE("mg_detail::residual: the common-stencil stretches give the point-by-point values on Galerkin levels",
          "[solvers][mg]") {
  // A hole and a 5×5 stencil: the Galerkin levels have many distinct stencils near the hole and the
  // boundary; the rows' stretches of the common one must leave every value as the bounds-checked
  // kernel computes it (same products, same order: equal bit for bit).
  for (const bool cubic : {false, true}) {
    const StencilOperator op =
        cubic ? make_stencil_operator(93, 90, biharmonic()) : make_stencil_operator(93, 90, nine_point(1, -0.2, -0.05));
    mg_detail::Level fine;
    fine.rows = op.rows;
    fine.cols = op.cols;
    fine.radius = op.radius;
    fine.constant = true;
    fine.coef = op.weights;
    fine.free = shape_mask(Shape::kHole, op.rows, op.cols);
    fine.unknowns = std::count(fine.free.begin(), fine.free.end(), 1);
    std::vector<mg_detail::Level> levels;
    levels.push_back(std::move(fine));
    for (int l = 0; l < 2; ++l) levels.push_back(mg_detail::galerkin_coarse(levels.back(), cubic ? 3 : 1));
    for (std::size_t l = 0; l < levels.size(); ++l) {
      mg_detail::Level& L = levels[l];
      mg_detail::find_common_stencil(L);
      REQUIRE(mg_detail::factor_lines(L));
      INFO("level " << L.rows << " x " << L.cols << ", radius " << L.radius);
      int stretched = 0;
      for (int i = 0; i < L.rows; ++i) stretched += L.common_hi[std::size_t(i)] - L.common_lo[std::size_t(i)];
      if (l < 2) CHECK(stretched > L.points() / 4);                // the fast path is taken (not only at the coarsest)
      CHECK(L.row_lu.inv_pivot.size() < std::size_t(L.points()));  // some rows share their factors
      Eigen::VectorXd b = Eigen::VectorXd::Random(L.points()), x = Eigen::VectorXd::Random(L.points()), r;
      for (Eigen::Index p = 0; p < L.points(); ++p)
        if (!L.free[std::size_t(p)]) x[p] = 0;  // the invariant of the cycle
      mg_detail::residual(L, b, x, r);
      int differ = 0;
      for (int i = 0; i < L.rows; ++i)
        for (int j = 0; j < L.cols; ++j) {
          const Eigen::Index p = Eigen::Index(i) * L.cols + j;
          const double expected = L.free[std::size_t(p)] ? b[p] - mg_detail::apply_at_edge(L, x.data(), i, j) : 0.0;
          differ += r[p] != expected;
        }
      CHECK(differ == 0);
    }
  }
}

namespace {

// Fixtures of the fast-path tests: a fine level (3×3 or 5×5 stencil, on a rectangle or around a
// central hole, constant or with the centre weight raised at every 9th point of every 16th row so
// that the runs of equal stencils break there and, on the Galerkin levels, on the rows near them) and two Galerkin
// levels under it, each with its common stencil and line factors as Multigrid::setup makes them.
std::vector<mg_detail::Level> fast_path_levels(bool cubic, Shape shape, bool varying, int rows = 61, int cols = 58) {
  const StencilOperator op = cubic ? make_stencil_operator(rows, cols, biharmonic())
                                   : make_stencil_operator(rows, cols, nine_point(1, -0.2, -0.05));
  mg_detail::Level fine;
  fine.rows = op.rows;
  fine.cols = op.cols;
  fine.radius = op.radius;
  fine.free = shape_mask(shape, op.rows, op.cols);
  if (fine.free.empty()) fine.free.assign(std::size_t(fine.points()), 1);
  fine.unknowns = std::count(fine.free.begin(), fine.free.end(), 1);
  const std::size_t ww = op.weights.size();
  fine.constant = !varying;
  fine.coef = op.weights;
  if (varying) {
    fine.coef.clear();
    for (Eigen::Index p = 0; p < fine.points(); ++p) {
      fine.coef.insert(fine.coef.end(), op.weights.begin(), op.weights.end());
      if (p / op.cols % 16 == 5 && p % op.cols % 9 == 4)
        fine.coef[std::size_t(p) * ww + ww / 2] *= 1.0 + double(p % 7 + 1) / 64;
    }
  }
  std::vector<mg_detail::Level> levels;
  levels.push_back(std::move(fine));
  for (int l = 0; l < 2; ++l) {  // (as Multigrid::setup: the common stencil before the next level)
    mg_detail::find_common_stencil(levels.back());
    levels.push_back(mg_detail::galerkin_coarse(levels.back(), cubic ? 3 : 1));
  }
  mg_detail::find_common_stencil(levels.back());
  for (mg_detail::Level& L : levels) REQUIRE(mg_detail::factor_lines(L));
  return levels;
}

// A copy of a level's grid, stencils and free mask, without its common stencil (galerkin_coarse
// then takes no shortcut) and without line factors.
mg_detail::Level bare_copy(const mg_detail::Level& L) {
  mg_detail::Level out;
  out.rows = L.rows;
  out.cols = L.cols;
  out.radius = L.radius;
  out.offset_i = L.offset_i;
  out.offset_j = L.offset_j;
  out.reach = L.reach;
  out.constant = L.constant;
  out.coef = L.coef;
  out.free = L.free;
  out.unknowns = L.unknowns;
  return out;
}

// A grid vector of values in [−1, 1] at the free points, 0 at fixed ones (the invariant of the cycle).
Eigen::VectorXd random_on_free(const mg_detail::Level& L) {
  Eigen::VectorXd v = Eigen::VectorXd::Random(L.points());
  for (Eigen::Index p = 0; p < L.points(); ++p)
    if (!L.free[std::size_t(p)]) v[p] = 0;
  return v;
}

// The dense LU (no pivoting, Doolittle, eliminations in the order t, then k, then s) of one line
// block of L: row i (column = false) or column j; fixed points are identity rows, and a free point
// couples only to free points of the line. Entry (t, s) at lu[t·n + s]; the pivots on the diagonal.
std::vector<double> reference_line_lu(const mg_detail::Level& L, bool column, int m) {
  const int r = L.radius, w = L.width(), n = column ? L.rows : L.cols;
  auto point = [&](int t) { return column ? Eigen::Index(t) * L.cols + m : Eigen::Index(m) * L.cols + t; };
  std::vector<double> lu(std::size_t(n) * std::size_t(n), 0.0);
  auto at = [&](int t, int s) -> double& { return lu[std::size_t(t) * std::size_t(n) + std::size_t(s)]; };
  for (int t = 0; t < n; ++t) {
    if (!L.free[std::size_t(point(t))]) {
      at(t, t) = 1;
      continue;
    }
    const double* centre = L.at(point(t)) + r * w + r;
    for (int k = -r; k <= r; ++k)
      if (t + k >= 0 && t + k < n && L.free[std::size_t(point(t + k))]) at(t, t + k) = centre[column ? k * w : k];
  }
  for (int t = 0; t < n; ++t)
    for (int k = 1; k <= r && t + k < n; ++k) {
      at(t + k, t) /= at(t, t);
      for (int s = 1; s <= r && t + s < n; ++s) at(t + k, t + s) -= at(t + k, t) * at(t, t + s);
    }
  return lu;
}

// One colour step of the line smoother, written out: the residual b − A x at the free points of
// the lines of that colour (point by point, with bounds checks), the solve of each line with its
// own LU, then x += the correction on those lines.
void reference_colour_step(const mg_detail::Level& L, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool column,
                           int colour) {
  const int r = L.radius, colours = r + 1, n = column ? L.rows : L.cols, lines = column ? L.cols : L.rows;
  int first_free = lines;
  for (int i = 0; i < L.rows; ++i)
    for (int j = 0; j < L.cols; ++j)
      if (L.free[std::size_t(i) * std::size_t(L.cols) + std::size_t(j)])
        first_free = std::min(first_free, column ? j : i);
  const Eigen::VectorXd before = x;
  for (int m = (first_free + 1 + colour) % colours; m < lines; m += colours) {
    auto point = [&](int t) { return column ? Eigen::Index(t) * L.cols + m : Eigen::Index(m) * L.cols + t; };
    const std::vector<double> lu = reference_line_lu(L, column, m);
    auto at = [&](int t, int s) { return lu[std::size_t(t) * std::size_t(n) + std::size_t(s)]; };
    Eigen::VectorXd d = Eigen::VectorXd::Zero(n);
    for (int t = 0; t < n; ++t) {
      const Eigen::Index p = point(t);
      const int i = column ? t : m, j = column ? m : t;
      if (L.free[std::size_t(p)]) d[t] = b[p] - mg_detail::apply_at_edge(L, before.data(), i, j);
    }
    for (int t = 0; t < n; ++t) {
      double y = d[t];
      for (int k = 1; k <= std::min(r, t); ++k) y -= at(t, t - k) * d[t - k];
      d[t] = y;
    }
    for (int t = n - 1; t >= 0; --t) {
      double y = d[t];
      for (int k = 1; k <= std::min(r, n - 1 - t); ++k) y -= at(t, t + k) * d[t + k];
      d[t] = y * (1.0 / at(t, t));
    }
    for (int t = 0; t < n; ++t) x[point(t)] += d[t];
  }
}

// The fixtures of the fast-path tests, with a name for INFO.
struct FastPathCase {
  bool cubic;
  Shape shape;
  bool varying;
};
const FastPathCase kFastPathCases[] = {{false, Shape::kFull, false}, {false, Shape::kHole, false},
                                       {false, Shape::kHole, true},  {true, Shape::kFull, false},
                                       {true, Shape::kHole, false},  {true, Shape::kHole, true}};
std::string name_of(const FastPathCase& c) {
  return std::string(c.cubic ? "5x5" : "3x3") + (c.shape == Shape::kHole ? " hole" : " rectangle") +
         (c.varying ? " varying stencils" : " one fine stencil");
}

}  // namespace

TEST_CASE("mg_detail::factor_lines: the shared line factors equal each line's own LU bit for bit", "[solvers][mg]") {
  for (const FastPathCase& c : kFastPathCases) {
    const std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying);
    for (const mg_detail::Level& L : levels) {
      INFO(name_of(c) << ": level " << L.rows << " x " << L.cols << ", radius " << L.radius);
      const int r = L.radius;
      for (const bool column : {false, true}) {
        const mg_detail::Level::LineLU& lu = column ? L.col_lu : L.row_lu;
        const int n = column ? L.rows : L.cols, lines = column ? L.cols : L.rows;
        if (!c.varying && L.rows > 20) CHECK(lu.inv_pivot.size() < std::size_t(n) * std::size_t(lines));  // shared
        int differ = 0;
        for (int m = 0; m < lines; ++m) {
          const std::vector<double> own = reference_line_lu(L, column, m);
          const std::size_t u = std::size_t(lu.line[std::size_t(m)]);
          for (int t = 0; t < n; ++t) {
            const std::size_t nn = std::size_t(n), tt = std::size_t(t);
            differ += lu.inv_pivot[u * nn + tt] != 1.0 / own[tt * nn + tt];
            for (int k = 1; k <= r; ++k) {
              const std::size_t at = (u * std::size_t(r) + std::size_t(k - 1)) * nn + tt;
              if (t - k >= 0) differ += lu.lower[at] != own[tt * nn + tt - std::size_t(k)];
              if (t + k < n) differ += lu.upper[at] != own[tt * nn + tt + std::size_t(k)];
            }
          }
        }
        CHECK(differ == 0);
      }
    }
  }
}

TEST_CASE("mg_detail::smooth: both sweep directions equal a written-out line Gauss-Seidel bit for bit",
          "[solvers][mg]") {
  // The column steps evaluate the residual of every colours-th point of a row (step > 1), through
  // the common-stencil stretch; the row steps with step 1. Both must give the values of the
  // point-by-point kernel and each line's own factors.
  for (const FastPathCase& c : kFastPathCases) {
    const std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying);
    for (const mg_detail::Level& L : levels) {
      INFO(name_of(c) << ": level " << L.rows << " x " << L.cols << ", radius " << L.radius);
      int stretched = 0, broken = 0;  // points on the stretches; rows whose stretch stops short
      for (int i = 0; i < L.rows; ++i) {
        const int length = L.common_hi[std::size_t(i)] - L.common_lo[std::size_t(i)];
        stretched += length;
        broken += length > 0 && length < L.cols - 2 * L.radius;
      }
      if (L.rows > 20) CHECK(stretched > L.points() / 8);             // the fast path is taken
      if (L.rows > 20 && c.shape == Shape::kHole) CHECK(broken > 0);  // and left for the point-by-point one
      const Eigen::VectorXd b = random_on_free(L);
      for (const bool forward : {true, false}) {
        INFO((forward ? "forward" : "backward"));
        Eigen::VectorXd x = random_on_free(L), expected = x, work;
        mg_detail::smooth(L, b, x, work, forward);
        const int colours = L.radius + 1;
        for (int k = 0; k < 2 * colours; ++k) {
          // forward: rows of colour 0 … radius, then columns; backward: the reverse sequence
          const int step = forward ? k : 2 * colours - 1 - k;
          reference_colour_step(L, b, expected, step >= colours, step % colours);
        }
        int differ = 0;
        for (Eigen::Index p = 0; p < L.points(); ++p) differ += x[p] != expected[p];
        CHECK(differ == 0);
      }
    }
  }
}

TEST_CASE(
    "mg_detail::smooth: column blocks side by side on one to three threads equal the written-out sweep bit for bit",
    "[solvers][mg]") {
  // 203 columns: each colour's columns split into two or three blocks (one per thread, at least
  // 32 columns each), whose residuals lie side by side in slices of the work vector.
  for (const FastPathCase& c : kFastPathCases) {
    std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying, 61, 203);
    mg_detail::Level& L = levels.front();
    REQUIRE(L.cols / (L.radius + 1) / 32 >= 2);  // two blocks at least from two threads on
    const Eigen::VectorXd b = random_on_free(L), start = random_on_free(L);
    Eigen::VectorXd expected = start;
    for (int k = 0; k < 2 * (L.radius + 1); ++k)
      reference_colour_step(L, b, expected, k > L.radius, k % (L.radius + 1));
    for (const int threads : {1, 2, 3}) {
      INFO(name_of(c) << ", " << threads << " thread(s)");
      L.threads = threads;
      Eigen::VectorXd x = start, work;
      mg_detail::smooth(L, b, x, work, true);
      int differ = 0;
      for (Eigen::Index p = 0; p < L.points(); ++p) differ += x[p] != expected[p];
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("mg_detail::galerkin_coarse: the deep interior's copied stencil equals the point-by-point sums bit for bit",
          "[solvers][mg]") {
  for (const FastPathCase& c : kFastPathCases) {
    const std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying);
    for (std::size_t l = 0; l + 1 < levels.size(); ++l) {
      const mg_detail::Level& Cl = levels[l + 1];
      INFO(name_of(c) << ": coarse level " << Cl.rows << " x " << Cl.cols << ", radius " << Cl.radius);
      REQUIRE_FALSE(levels[l].common.empty());  // the copy was possible
      const mg_detail::Level generic = mg_detail::galerkin_coarse(bare_copy(levels[l]), Cl.reach);
      REQUIRE(generic.rows == Cl.rows);
      REQUIRE(generic.cols == Cl.cols);
      REQUIRE(generic.radius == Cl.radius);
      CHECK(generic.free == Cl.free);
      REQUIRE(generic.coef.size() == Cl.coef.size());
      std::size_t differ = 0;
      for (std::size_t k = 0; k < Cl.coef.size(); ++k) differ += generic.coef[k] != Cl.coef[k];
      CHECK(differ == 0);
      // and the interior is uniform: the common stencil covers most points of the level's rows
      std::size_t stretched = 0;
      for (int i = 0; i < Cl.rows; ++i)
        stretched += std::size_t(Cl.common_hi[std::size_t(i)] - Cl.common_lo[std::size_t(i)]);
      if (Cl.rows > 20) CHECK(stretched > std::size_t(Cl.points()) / 8);
    }
  }
}

TEST_CASE("mg_detail::restrict_to: the weight table gives the bounds-checked sums bit for bit", "[solvers][mg]") {
  for (const FastPathCase& c : kFastPathCases) {
    const std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying);
    for (std::size_t l = 0; l + 1 < levels.size(); ++l) {
      const mg_detail::Level &F = levels[l], &Cl = levels[l + 1];
      INFO(name_of(c) << ": fine level " << F.rows << " x " << F.cols << ", reach " << Cl.reach);
      const int h = Cl.reach;
      auto weight = [h](int a) {  // linear (1/2, 1, 1/2) or cubic (−1/16, 0, 9/16, 1, 9/16, 0, −1/16)
        a = std::abs(a);
        if (h == 1) return a == 0 ? 1.0 : a == 1 ? 0.5 : 0.0;
        return a == 0 ? 1.0 : a == 1 ? 9.0 / 16 : a == 3 ? -1.0 / 16 : 0.0;
      };
      const Eigen::VectorXd r = random_on_free(F);
      Eigen::VectorXd rc;
      mg_detail::restrict_to(F, Cl, r, rc);
      REQUIRE(rc.size() == Cl.points());
      int differ = 0;
      for (int I = 0; I < Cl.rows; ++I)
        for (int J = 0; J < Cl.cols; ++J) {
          const Eigen::Index q = Eigen::Index(I) * Cl.cols + J;
          double sum = 0;
          for (int a = -h; a <= h && Cl.free[std::size_t(q)]; ++a) {
            const int i = 2 * I + Cl.offset_i + a;
            if (i < 0 || i >= F.rows || weight(a) == 0) continue;
            for (int b = -h; b <= h; ++b) {
              const int j = 2 * J + Cl.offset_j + b;
              if (j >= 0 && j < F.cols) sum += weight(a) * weight(b) * r[Eigen::Index(i) * F.cols + j];
            }
          }
          differ += rc[q] != sum;
        }
      CHECK(differ == 0);
    }
  }
}

TEST_CASE("mg_detail::apply_level: the common-stencil stretches give the point-by-point products bit for bit",
          "[solvers][mg]") {
  for (const FastPathCase& c : kFastPathCases) {
    const std::vector<mg_detail::Level> levels = fast_path_levels(c.cubic, c.shape, c.varying);
    for (const mg_detail::Level& L : levels) {
      INFO(name_of(c) << ": level " << L.rows << " x " << L.cols << ", radius " << L.radius);
      const Eigen::VectorXd x = random_on_free(L);
      Eigen::VectorXd y;
      mg_detail::apply_level(L, x, y);
      REQUIRE(y.size() == L.points());
      int differ = 0;
      for (int i = 0; i < L.rows; ++i)
        for (int j = 0; j < L.cols; ++j) {
          const Eigen::Index p = Eigen::Index(i) * L.cols + j;
          differ += y[p] != (L.free[std::size_t(p)] ? mg_detail::apply_at_edge(L, x.data(), i, j) : 0.0);
        }
      CHECK(differ == 0);
    }
  }
}
