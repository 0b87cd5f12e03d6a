// The Eigen direct backends (solvers/eigen_direct.cpp).
#include <catch2/catch.hpp>
#include <string>

#include "solvers/registry.h"

using namespace coons::solvers;

TEST_CASE("eigen-lu: a matrix with empty columns is singular without entering SparseLU", "[solvers]") {
  // SparseLU sizes its U from fillratio·(nnz + 1)/n, which is 0 when nnz + 1 < n/20, and then
  // never returns from factorize (Eigen 3.4: n = 50 with one entry spun for over 15 minutes in
  // `coons bench-matrix`). Such a matrix has empty columns: singular, said before SparseLU runs.
  for (const int n : {3, 50, 2000}) {
    Eigen::SparseMatrix<double> A(n, n);
    A.insert(0, 0) = 1;
    A.makeCompressed();
    LinearOperator op;
    op.matrix = &A;
    const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(n, 3);
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver("eigen-lu")->compute_and_solve(op, B, X);
    INFO(n << ": " << s.brief_report());
    CHECK(s.status == SolveStatus::kSingular);
    CHECK_THAT(s.message, Catch::Contains("row 1 (counting from 0) is empty"));
  }
}

TEST_CASE("eigen-lu: a regular matrix is still factorised and solved", "[solvers]") {
  Eigen::SparseMatrix<double> A(3, 3);
  A.insert(0, 1) = 2;  // a permutation times a diagonal: no entry on the diagonal, regular
  A.insert(1, 2) = 3;
  A.insert(2, 0) = 4;
  A.makeCompressed();
  LinearOperator op;
  op.matrix = &A;
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(3, 3);
  Eigen::MatrixX3d X;
  const SolveSummary s = make_solver("eigen-lu")->compute_and_solve(op, B, X);
  INFO(s.brief_report());
  REQUIRE(s.status == SolveStatus::kSuccess);
  CHECK((A * X - B).cwiseAbs().maxCoeff() < 1e-15);
}

TEST_CASE("LinearSolver::factorize: a failed factorisation reports the residual of X = 0, not 0", "[solvers]") {
  // The searches copy the summary of a failed factorize(): it read "singular, 0 iterations,
  // residual 0" although nothing was solved (solve() then returns X = 0, residual 1).
  Eigen::SparseMatrix<double> A(2, 2);
  A.insert(0, 0) = 1;
  A.insert(0, 1) = 1;
  A.insert(1, 0) = 1;
  A.insert(1, 1) = 1;
  A.makeCompressed();
  LinearOperator op;
  op.matrix = &A;
  for (const char* name : {"eigen-lu", "eigen-ldlt"}) {
    auto solver = make_solver(name);
    INFO(name);
    REQUIRE(solver->factorize(op) != SolveStatus::kSuccess);
    CHECK(solver->summary().relative_residual == 1);
    Eigen::MatrixX3d X;
    const SolveSummary s = solver->solve(Eigen::MatrixX3d::Ones(2, 3), X);
    CHECK(s.relative_residual == 1);
    CHECK(X.isZero(0));
  }
}
