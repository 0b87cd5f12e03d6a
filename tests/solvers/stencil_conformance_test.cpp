// Every registered backend on the problem classes of the 5×5 masks and of free sets, built as
// StencilOperators in code: the C1 family a·C + b·T on full rectangles (rows ≠ cols), and free
// sets with a hole, an L-shape and a fixed interior line (5×5 and 3×3 stencils). A backend either
// solves (and then agrees with a dense reference) or says honestly why not; the structured ones
// that claim a class (fast5, separable-banded, pcg-fast) must solve it.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "coons/config.h"
#include "solvers/fast5_solver.h"
#include "solvers/registry.h"
#include "solvers/separable_banded_solver.h"
#include "solvers/stencil_operator.h"

using namespace coons::solvers;

namespace {

// w·C + (1−w)·T, C = δ⁴⊗δ⁴, T = δ⁴⊗e + 2δ²⊗δ² + e⊗δ⁴, scaled by `scale`.
std::vector<double> c1_family(double w, double scale = 1) {
  const double d4[5] = {1, -4, 6, -4, 1}, d2[5] = {0, 1, -2, 1, 0}, e[5] = {0, 0, 1, 0, 0};
  std::vector<double> out(25);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      out[std::size_t(i) * 5 + std::size_t(j)] =
          scale * (w * d4[i] * d4[j] + (1 - w) * (d4[i] * e[j] + 2 * d2[i] * d2[j] + e[i] * d4[j]));
  return out;
}

std::vector<double> alpha_stencil(double alpha) {  // centre 1, edges −(1/4 − α), diagonals −α
  const double e = -(0.25 - alpha), d = -alpha;
  return {d, e, d, e, 1, e, d, e, d};
}

enum class Region { kFull, kHole, kLShape, kLine };
const char* region_name(Region s) {
  switch (s) {
    case Region::kFull:
      return "full";
    case Region::kHole:
      return "hole";
    case Region::kLShape:
      return "L-shape";
    case Region::kLine:
      return "interior line";
  }
  return "";
}

StencilOperator make_problem(int rows, int cols, const std::vector<double>& weights, Region shape) {
  StencilOperator op = make_stencil_operator(rows, cols, weights);
  if (shape == Region::kFull) return op;
  op.free.assign(std::size_t(rows) * std::size_t(cols), 1);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j) {
      bool fixed = false;
      if (shape == Region::kHole) fixed = i >= rows / 3 && i < rows / 3 + 4 && j >= cols / 3 && j < cols / 3 + 3;
      if (shape == Region::kLShape) fixed = i >= rows / 2 && j >= cols / 2;
      if (shape == Region::kLine) fixed = i == rows / 2 && j >= 2 && j < cols - 3;  // a fixed curve inside
      if (fixed) op.free[std::size_t(i) * std::size_t(cols) + std::size_t(j)] = 0;
    }
  return op;
}

Eigen::MatrixX3d random_rhs(Eigen::Index n, unsigned seed) {
  std::srand(seed);
  return Eigen::MatrixX3d::Random(n, 3);
}

// Whether `name` promises to solve this problem (it must then succeed).
bool claims(const std::string& name, const StencilOperator& op) {
  const bool full = op.free.empty();
  if (name == "fast5") return full && c1_family_weights(op).has_value();
  if (name == "separable-banded") return full && separable_operator(op).has_value();
  if (name == "pcg-fast") return true;  // every stencil here is symmetric definite, covered by a box solver
  const SolverInfo* info = find_solver(name);
  return info && info->family == SolverFamily::kDirect;
}

void check_backends(const StencilOperator& op, const std::string& what) {
  const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
  const Eigen::MatrixX3d B = random_rhs(A.rows(), 7);
  const Eigen::MatrixX3d reference = Eigen::MatrixXd(A).ldlt().solve(Eigen::MatrixXd(B));
  LinearOperator lop;
  lop.matrix = &A;
  lop.grid = &op;
  for (const SolverInfo& info : available_solvers()) {
    Eigen::MatrixX3d X;
    // the iterative backends to 1e-9: c1-coons (κ ≈ 1e9 at 20 × 20) ends near 1e-10 here, and a true
    // residual above the tolerance is (rightly) not_converged
    SolverOptions options;
    options.tolerance = 1e-9;
    const SolveSummary s = make_solver(info.name, options)->compute_and_solve(lop, B, X);
    INFO(what << ": " << s.brief_report());
    if (claims(info.name, op)) REQUIRE(s.ok());
    if (s.ok()) {
      // κ of the 5×5 systems grows like N⁸ (c1-coons): compare in the residual and loosely in X.
      // Eigen's Krylov backends stop on their recursive residual, which drifts from the true one
      // (reported in the summary) by up to ~5e-9 here at κ ≈ 1e9.
      CHECK(s.relative_residual < (info.family == SolverFamily::kIterative && info.needs_matrix ? 1e-7 : 1e-9));
      CHECK((X - reference).cwiseAbs().maxCoeff() < 1e-6 * reference.cwiseAbs().maxCoeff());
    } else {
      const bool honest = s.status == SolveStatus::kNotApplicable ||
                          (info.family == SolverFamily::kIterative &&
                           (s.status == SolveStatus::kNotConverged || s.status == SolveStatus::kDiverged));
      CHECK(honest);
      CHECK(!s.message.empty());
    }
  }
}

}  // namespace

TEST_CASE("every solver: the c1 family on full rectangles agrees with a dense reference or declines", "[solvers]") {
  for (double w : {0.0, 0.5, 1.0})
    for (auto [rows, cols] : {std::pair{9, 14}, {13, 6}, {20, 20}})
      check_backends(make_problem(rows, cols, c1_family(w, 1 / (20 + 16 * w)), Region::kFull),
                     "w = " + std::to_string(w) + ", " + std::to_string(rows) + " x " + std::to_string(cols));
}

TEST_CASE("every solver: free sets with a hole, an L-shape and a fixed line agree or decline", "[solvers]") {
  for (Region shape : {Region::kHole, Region::kLShape, Region::kLine}) {
    check_backends(make_problem(16, 21, c1_family(0.5), shape), std::string("c1-family 0.5, ") + region_name(shape));
    check_backends(make_problem(17, 12, c1_family(0.0), shape), std::string("biharmonic, ") + region_name(shape));
    check_backends(make_problem(19, 23, alpha_stencil(-0.1), shape), std::string("alpha -0.1, ") + region_name(shape));
  }
}

#if COONS_HAVE_FFTW
TEST_CASE("fast5: exact on a*C + b*T for any positive scale, one row or one column too", "[solvers]") {
  for (auto [rows, cols] : {std::pair{1, 7}, {6, 1}, {2, 3}, {11, 8}})
    for (double w : {0.0, 0.25, 0.9, 1.0}) {
      const StencilOperator op = make_problem(rows, cols, c1_family(w, 3.5), Region::kFull);
      const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
      const Eigen::MatrixX3d B = random_rhs(A.rows(), 3);
      LinearOperator lop;
      lop.grid = &op;
      Eigen::MatrixX3d X;
      const SolveSummary s = make_solver("fast5")->compute_and_solve(lop, B, X);
      INFO(rows << " x " << cols << ", w = " << w << ": " << s.brief_report());
      REQUIRE(s.ok());
      CHECK((A * X - B).norm() <= 1e-11 * B.norm());
    }
}

TEST_CASE("fast5: the same solution bit for bit on 1 and 2 threads, dense and mask-like right-hand sides",
          "[solvers]") {
  // 300 and 301 columns: three chunks of modes in the threaded sweeps, an even and an odd number
  // of modes; mask-like: non-zero on the two rows and columns next to the frame only (those rows
  // skip the forward transform)
  const int rows = 40;
  for (const int cols : {300, 301})
    for (double w : {0.0, 0.5}) {
      const StencilOperator op = make_problem(rows, cols, c1_family(w), Region::kFull);
      const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
      const Eigen::MatrixX3d dense = random_rhs(A.rows(), 5);
      Eigen::MatrixX3d mask = dense;
      for (int i = 2; i < rows - 2; ++i)
        for (int j = 2; j < cols - 2; ++j) mask.row(Eigen::Index(i) * cols + j).setZero();
      const Eigen::MatrixX3d& mask_like = mask;
      for (const Eigen::MatrixX3d* B : {&dense, &mask_like}) {
        LinearOperator lop;
        lop.grid = &op;
        Eigen::MatrixX3d X1, X2;
        SolverOptions options;
        const SolveSummary s1 = make_solver("fast5", options)->compute_and_solve(lop, *B, X1);
        options.threads = 2;
        const SolveSummary s2 = make_solver("fast5", options)->compute_and_solve(lop, *B, X2);
        INFO(cols << " columns, w = " << w << (B == &dense ? ", dense" : ", mask-like") << ": " << s1.brief_report());
        REQUIRE(s1.ok());
        REQUIRE(s2.ok());
        // random data excites the lowest modes (κ ∝ cols⁴): 2e-11 at w = 0.5 here, with one thread too
        CHECK((A * X1 - *B).norm() <= 1e-10 * B->norm());
        CHECK((X1 - X2).cwiseAbs().maxCoeff() == 0);
      }
    }
}

TEST_CASE("fast5: a zero right-hand-side column gives a zero solution and leaves the others as accurate", "[solvers]") {
  // A zero column once made the boundary ratio 0/0 = NaN, which turned off the boundary corrections
  // of every column (success with the first pass's accuracy).
  const int rows = 40, cols = 300;
  for (double w : {0.0, 0.5}) {
    const StencilOperator op = make_problem(rows, cols, c1_family(w), Region::kFull);
    const Eigen::SparseMatrix<double> A = stencil_operator_matrix(op);
    Eigen::MatrixX3d with_zero = random_rhs(A.rows(), 9);
    Eigen::MatrixX3d without = with_zero;
    with_zero.col(0).setZero();
    without.col(0) = without.col(1);
    LinearOperator lop;
    lop.grid = &op;
    Eigen::MatrixX3d X0, X1;
    const SolveSummary s0 = make_solver("fast5", SolverOptions{})->compute_and_solve(lop, with_zero, X0);
    const SolveSummary s1 = make_solver("fast5", SolverOptions{})->compute_and_solve(lop, without, X1);
    INFO("w = " << w << ": " << s0.brief_report());
    REQUIRE(s0.ok());
    REQUIRE(s1.ok());
    CHECK(X0.col(0).cwiseAbs().maxCoeff() == 0);
    for (int c = 1; c < 3; ++c) {
      const double r0 = (A * X0.col(c) - with_zero.col(c)).norm() / with_zero.col(c).norm();
      const double r1 = (A * X1.col(c) - without.col(c)).norm() / without.col(c).norm();
      INFO("column " << c << ": residual " << r0 << " with a zero column, " << r1 << " without");
      CHECK(r0 <= std::max(2 * r1, 1e-12));
    }
  }
}

TEST_CASE("fast5: declines 3x3 stencils, free masks, negative weights and other 5x5 stencils", "[solvers]") {
  std::vector<StencilOperator> declined = {make_problem(8, 8, alpha_stencil(-0.1), Region::kFull),
                                           make_problem(12, 12, c1_family(0.5), Region::kHole),
                                           make_problem(8, 8, c1_family(1.5), Region::kFull)};  // b < 0
  std::vector<double> other = c1_family(0.5);
  other[0] += 0.01;  // a corner weight off the family
  declined.push_back(make_problem(8, 8, other, Region::kFull));
  for (const StencilOperator& op : declined) {
    LinearOperator lop;
    lop.grid = &op;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver("fast5")->compute_and_solve(lop, random_rhs(op.size(), 1), X);
    INFO(s.brief_report());
    CHECK(s.status == SolveStatus::kNotApplicable);
    CHECK(!s.message.empty());
  }
  CHECK(!c1_family_weights(make_problem(5, 5, c1_family(1.5), Region::kFull)));
  const auto w = c1_family_weights(make_problem(5, 5, c1_family(0.25, 2), Region::kFull));
  REQUIRE(w);
  CHECK(w->a == Approx(0.5));
  CHECK(w->b == Approx(1.5));
}

TEST_CASE("pcg-fast: a hole needs more iterations than the full rectangle, which needs one", "[solvers]") {
  const StencilOperator full = make_problem(24, 24, c1_family(0.5), Region::kFull);
  const StencilOperator hole = make_problem(24, 24, c1_family(0.5), Region::kHole);
  int iterations[2] = {0, 0};
  int k = 0;
  for (const StencilOperator* op : {&full, &hole}) {
    LinearOperator lop;
    lop.grid = op;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver("pcg-fast")->compute_and_solve(lop, random_rhs(op->size(), 2), X);
    INFO(s.brief_report());
    REQUIRE(s.ok());
    iterations[k++] = s.iterations;
  }
  CHECK(iterations[0] <= 2);
  CHECK(iterations[1] > iterations[0]);
}

TEST_CASE("pcg-fast: indefinite 3x3 boxes and stencils without a structured solver are declined", "[solvers]") {
  const StencilOperator indefinite = make_problem(20, 20, alpha_stencil(-0.4), Region::kHole);
  std::vector<double> other = c1_family(0.5);
  other[0] += 0.01;
  const StencilOperator uncovered = make_problem(12, 12, other, Region::kHole);
  for (const auto& [op, expected] :
       {std::pair{&indefinite, SolveStatus::kNotPositiveDefinite}, {&uncovered, SolveStatus::kNotApplicable}}) {
    LinearOperator lop;
    lop.grid = op;
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver("pcg-fast")->compute_and_solve(lop, random_rhs(op->size(), 4), X);
    INFO(s.brief_report());
    CHECK(s.status == expected);
  }
}
#endif

TEST_CASE("separable_operator: finds P x Q for c1-coons and alpha = -1/4, not for the biharmonic", "[solvers]") {
  const auto c1 = separable_operator(make_problem(6, 9, c1_family(1.0, 2), Region::kFull));
  REQUIRE(c1);
  const Eigen::SparseMatrix<double> A = separable_banded_matrix(*c1);
  CHECK((Eigen::MatrixXd(A) -
         Eigen::MatrixXd(stencil_operator_matrix(make_problem(6, 9, c1_family(1.0, 2), Region::kFull))))
            .cwiseAbs()
            .maxCoeff() < 1e-12);
  CHECK(separable_operator(make_problem(6, 9, alpha_stencil(-0.25), Region::kFull)));
  CHECK(!separable_operator(make_problem(6, 9, c1_family(0.0), Region::kFull)));
  CHECK(!separable_operator(make_problem(6, 9, c1_family(1.0), Region::kHole)));
}

TEST_CASE("fast5, separable-banded, pcg-fast: analyze once, factorize many equals fresh solves", "[solvers]") {
  for (const char* name : {"fast5", "separable-banded", "pcg-fast"}) {
    if (!find_solver(name)) {
      WARN("skipped: " << name << " is not built into this binary (FFTW)");
      continue;
    }
    const bool separable_only = std::string(name) == "separable-banded";
    const Region shape = std::string(name) == "pcg-fast" ? Region::kLShape : Region::kFull;
    auto reused = make_solver(name);
    const StencilOperator first = make_problem(10, 13, c1_family(1.0), shape);
    LinearOperator lop;
    lop.grid = &first;
    REQUIRE(reused->analyze(lop) == SolveStatus::kSuccess);
    // separable-banded takes c1-coons (w = 1) only: it gets that stencil at four scales instead
    const std::vector<std::pair<double, double>> members =
        separable_only ? std::vector<std::pair<double, double>>{{1.0, 2.0}, {1.0, 0.5}, {1.0, 3.0}, {1.0, 1.0}}
                       : std::vector<std::pair<double, double>>{{1.0, 2.0}, {0.7, 1.7}, {0.3, 1.3}, {0.0, 1.0}};
    int compared = 0;
    for (const auto& [w, scale] : members) {
      const StencilOperator op = make_problem(10, 13, c1_family(w, scale), shape);
      LinearOperator next;
      next.grid = &op;
      INFO(name << ", w = " << w << ", scale = " << scale);
      REQUIRE(reused->factorize(next) == SolveStatus::kSuccess);
      const Eigen::MatrixX3d B = random_rhs(op.size(), 5);
      Eigen::MatrixX3d X_reused, X_fresh;
      const SolveSummary reused_summary = reused->solve(B, X_reused);
      const SolveSummary fresh_summary = make_solver(name)->compute_and_solve(next, B, X_fresh);
      INFO(reused_summary.brief_report() << " / " << fresh_summary.brief_report());
      REQUIRE(reused_summary.ok());
      REQUIRE(fresh_summary.ok());
      CHECK((X_reused - X_fresh).cwiseAbs().maxCoeff() <= 1e-12 * X_fresh.cwiseAbs().maxCoeff());
      ++compared;
    }
    CHECK(compared == 4);
  }
}

TEST_CASE("dst, fast, jacobi, gauss-seidel: a grid stencil they cannot take is declined naming what it is",
          "[solvers]") {
  // They said "needs the grid stencil (matrix-free)" of a system given as just that.
  const StencilOperator five = make_problem(9, 8, c1_family(0.5), Region::kFull);
  const StencilOperator holed = make_problem(9, 8, alpha_stencil(-0.1), Region::kHole);
  // point-symmetric (so a symmetric matrix) but not mirrored: they said "with one fixed ring only"
  const StencilOperator skew = make_problem(9, 8, {-0.3, -0.2, -0.05, -0.2, 1, -0.2, -0.05, -0.2, -0.3}, Region::kFull);
  int checked = 0;
  for (const char* name : {"dst", "fast", "jacobi", "gauss-seidel"}) {
    if (!find_solver(name)) continue;  // dst and fast need FFTW
    for (const auto* op : {&five, &holed, &skew}) {
      const Eigen::SparseMatrix<double> A = stencil_operator_matrix(*op);
      LinearOperator lop;
      lop.matrix = &A;
      lop.grid = op;
      Eigen::MatrixX3d X;
      const SolveSummary s = make_solver(name)->compute_and_solve(lop, random_rhs(A.rows(), 3), X);
      INFO(name << ": " << s.brief_report());
      CHECK(s.status == SolveStatus::kNotApplicable);
      CHECK_THAT(s.message, Catch::StartsWith("works on a 3x3 stencil with one weight per pair of neighbours along i, "
                                              "one along j and one for the four diagonals, on a full rectangle; "));
      CHECK_THAT(s.message, !Catch::Contains("ring"));
      if (op == &five) CHECK_THAT(s.message, Catch::EndsWith("this system is a 5x5 stencil"));
      if (op == &holed)
        CHECK_THAT(s.message,
                   Catch::EndsWith("this system is a 3x3 stencil on a free set (some interior points fixed)"));
      if (op == &skew)
        CHECK_THAT(s.message, Catch::EndsWith(
                                  "this system is a 3x3 stencil that is not symmetric under reflection in i and in j"));
      ++checked;
    }
  }
  CHECK(checked >= 6);  // jacobi and gauss-seidel are always built
}
