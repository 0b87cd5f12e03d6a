// The SuiteSparse backends (solvers/suitesparse_direct.cpp; built with SuiteSparse only).
#include <catch2/catch.hpp>
#include <string>

#include "coons/config.h"
#include "coons/mask/assemble_mask_system.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

#if COONS_HAVE_SUITESPARSE

using namespace coons;
using namespace coons::solvers;
using namespace coons::test;

namespace {

// The SPD mask matrix of a random net with one negative diagonal entry at `column`: a Cholesky
// factorisation fails at that column, wherever AMD has put it (a principal submatrix without it
// is still definite). The summary of `backend` on it.
SolveSummary negative_entry_summary(const std::string& backend, const MaskSystem& s, int column) {
  Eigen::SparseMatrix<double> A = s.A;
  A.coeffRef(column, column) = -1;
  LinearOperator op;
  op.matrix = &A;
  Eigen::MatrixX3d X;
  return make_solver(backend)->compute_and_solve(op, s.B, X);
}

}  // namespace

TEST_CASE("cholmod: not positive definite names the column of the matrix not the pivot", "[solvers]") {
  const MaskSystem s = assemble_mask_system(make_random_net(11, 13, 43), alpha_mask(0.1));
  for (const int column : {0, 37, 71, int(s.A.rows()) - 1}) {
    const SolveSummary summary = negative_entry_summary("cholmod", s, column);
    INFO(summary.brief_report());
    CHECK(summary.status == SolveStatus::kNotPositiveDefinite);
    CHECK_THAT(summary.message, Catch::StartsWith("not positive definite at column " + std::to_string(column) + " ("));
    CHECK_THAT(summary.message, Catch::Contains("of the amd ordering)"));
  }
}

TEST_CASE("cholmod-simplicial: not positive definite names the column of its first negative pivot", "[solvers]") {
  // The LDLᵀ goes on through a negative pivot; the first one is where the supernodal LLᵀ stops,
  // at the column with the negative diagonal entry (the leading block before it is definite).
  const MaskSystem s = assemble_mask_system(make_random_net(11, 13, 43), alpha_mask(0.1));
  for (const int column : {0, 37, 71, int(s.A.rows()) - 1}) {
    const SolveSummary summary = negative_entry_summary("cholmod-simplicial", s, column);
    INFO(summary.brief_report());
    CHECK(summary.status == SolveStatus::kNotPositiveDefinite);
    CHECK_THAT(summary.message, Catch::StartsWith("not positive definite at column " + std::to_string(column) + " ("));
    CHECK_THAT(summary.message, Catch::Contains("of the amd ordering); 1 negative pivot(s) in D"));
  }
}

TEST_CASE("cholmod, umfpack: a matrix with no entries is singular, naming the empty row", "[solvers]") {
  // A 3 by 3 Matrix Market file of no entries: cholmod_analyze (status -4) and umfpack_di_symbolic
  // (status -5) fail on it, which was reported as a bare `failure` with SuiteSparse's status code.
  Eigen::SparseMatrix<double> A(3, 3);
  A.makeCompressed();
  LinearOperator op;
  op.matrix = &A;
  const Eigen::MatrixX3d B = Eigen::MatrixX3d::Ones(3, 3);
  for (const char* name : {"cholmod", "cholmod-simplicial", "umfpack"}) {
    Eigen::MatrixX3d X;
    const SolveSummary s = make_solver(name)->compute_and_solve(op, B, X);
    INFO(name << ": " << s.brief_report());
    CHECK(s.status == SolveStatus::kSingular);
    CHECK_THAT(s.message, Catch::Contains("is empty"));
  }
}

#endif  // COONS_HAVE_SUITESPARSE
