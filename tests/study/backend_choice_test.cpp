// The backend of a search (study/backend_choice.h): the one asked for as given, auto's pick, and
// the check that says whether a requested one can serve.
#include "coons/study/backend_choice.h"

#include <catch2/catch.hpp>
#include <string>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/registry.h"

using namespace coons;

namespace {

Boundary sized(int m, int n) {
  Boundary b;
  b.m = m;
  b.n = n;
  return b;
}

}  // namespace

TEST_CASE("search_backend: auto is the registry's pick on the alpha family, a general LU where indefinite", "[study]") {
  const Boundary b = sized(9, 7);
  const std::string pick = solvers::choose_auto_solver(mask_stencil(alpha_mask(-0.1), 8, 6));
  CHECK(search_backend(nullptr, b, false).name == pick);
  const solvers::SolverInfo* picked = solvers::find_solver(pick);
  REQUIRE(picked != nullptr);
  CHECK(search_backend(nullptr, b, true).name == (picked->definite_only ? std::string("eigen-lu") : pick));
  // a requested backend is used as given, even one the check refuses (its solves then say why)
  const solvers::SolverInfo* fast5 = solvers::find_solver("fast5");
  CHECK(&search_backend(fast5, b, false) == fast5);
}

TEST_CASE("check_search_backend: refuses what cannot solve the alpha family, and definite-only where indefinite",
          "[study]") {
  const Boundary b = sized(9, 7);
  const SearchBackendCheck fast5 = check_search_backend(*solvers::find_solver("fast5"), b, false);
  CHECK_FALSE(fast5.applicable);
  CHECK(fast5.reason.rfind("fast5 does not solve the 3x3 alpha family (", 0) == 0);
  CHECK_FALSE(check_search_backend(*solvers::find_solver("separable-banded"), b, false).applicable);
  const SearchBackendCheck ldlt = check_search_backend(*solvers::find_solver("eigen-ldlt"), b, true);
  CHECK_FALSE(ldlt.applicable);
  CHECK(ldlt.reason.find("needs a positive definite system") != std::string::npos);
  for (const char* name : {"eigen-ldlt", "eigen-lu", "cg", "fast", "dst", "mg", "mg-cg"}) {
    INFO(name);
    const SearchBackendCheck ok = check_search_backend(*solvers::find_solver(name), b, false);
    CHECK(ok.applicable);
    CHECK(ok.reason.empty());
  }
}

TEST_CASE("weight_search_backend: a backend that works from the matrix, else cholmod or eigen-ldlt", "[study]") {
  const std::string fallback = solvers::find_solver("cholmod") ? "cholmod" : "eigen-ldlt";
  CHECK(weight_search_backend(nullptr).name == fallback);
  CHECK(weight_search_backend(solvers::find_solver("fast")).name == fallback);
  CHECK(weight_search_backend(solvers::find_solver("gmres")).name == "gmres");
  CHECK_FALSE(check_weight_search_backend(*solvers::find_solver("fast")).applicable);
  CHECK(check_weight_search_backend(*solvers::find_solver("fast"))
            .reason.rfind("fast works from the grid stencil only", 0) == 0);
  CHECK(check_weight_search_backend(*solvers::find_solver("umfpack")).applicable);
}
