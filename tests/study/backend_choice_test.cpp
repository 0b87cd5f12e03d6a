// The backend of a search (study/backend_choice.h): the one asked for as given, auto's pick, and
// the check that says whether a requested one can serve.
#include "coons/study/backend_choice.h"

#include <catch2/catch.hpp>
#include <stdexcept>
#include <string>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;

TEST_CASE(
    "search_backend: auto is the registry's pick on the alpha family, never a definite-only one where "
    "indefinite",
    "[study]") {
  const Boundary b = test::make_random_boundary(9, 7, 1);
  const std::string pick = solvers::choose_auto_solver(mask_stencil(alpha_mask(-0.1), 8, 6));
  CHECK(search_backend(nullptr, b, false).name == pick);
  CHECK_FALSE(search_backend(nullptr, b, true).definite_only);
  CHECK(check_search_backend(search_backend(nullptr, b, true), b, true).applicable);
  // a requested backend is used as given when the check accepts it ...
  const solvers::SolverInfo* lu = solvers::find_solver("eigen-lu");
  CHECK(&search_backend(lu, b, true) == lu);
  // ... and one it refuses is the caller's error, not a search answered by another evaluator
  const solvers::SolverInfo* banded = solvers::find_solver("separable-banded");
  CHECK_THROWS_AS(search_backend(banded, b, false), std::invalid_argument);
  CHECK_THROWS_AS(search_backend(solvers::find_solver("eigen-ldlt"), b, true), std::invalid_argument);
}

TEST_CASE("check_search_backend: refuses what cannot solve the alpha family, and definite-only where indefinite",
          "[study]") {
  const Boundary b = test::make_random_boundary(9, 7, 1);
  // separable-banded takes alpha = -1/4 only, fast5 (FFTW builds) 5x5 stencils only
  for (const char* name : {"separable-banded", "fast5"}) {
    const solvers::SolverInfo* info = solvers::find_solver(name);
    if (!info) continue;
    INFO(name);
    const SearchBackendCheck refused = check_search_backend(*info, b, false);
    CHECK_FALSE(refused.applicable);
    CHECK(refused.reason.rfind(std::string(name) + " does not solve the 3x3 alpha family (", 0) == 0);
  }
  const SearchBackendCheck ldlt = check_search_backend(*solvers::find_solver("eigen-ldlt"), b, true);
  CHECK_FALSE(ldlt.applicable);
  CHECK(ldlt.reason.find("needs a positive definite system") != std::string::npos);
  for (const char* name : {"eigen-ldlt", "eigen-lu", "cg", "fast", "dst", "mg", "mg-cg"}) {
    const solvers::SolverInfo* info = solvers::find_solver(name);
    if (!info) continue;  // (fast and dst: FFTW builds)
    INFO(name);
    const SearchBackendCheck ok = check_search_backend(*info, b, false);
    CHECK(ok.applicable);
    CHECK(ok.reason.empty());
  }
}

TEST_CASE("weight_search_backend: a backend that works from the matrix, else cholmod or eigen-ldlt", "[study]") {
  const std::string fallback = solvers::find_solver("cholmod") ? "cholmod" : "eigen-ldlt";
  const solvers::SolverInfo* mg = solvers::find_solver("mg");  // a grid-stencil backend in every build
  CHECK(weight_search_backend(nullptr).name == fallback);
  CHECK(weight_search_backend(mg).name == fallback);
  CHECK(weight_search_backend(solvers::find_solver("eigen-lu")).name == "eigen-lu");
  CHECK_FALSE(check_weight_search_backend(*mg).applicable);
  CHECK(check_weight_search_backend(*mg).reason.rfind("mg works from the grid stencil only", 0) == 0);
  CHECK(check_weight_search_backend(*solvers::find_solver("eigen-ldlt")).applicable);
}
