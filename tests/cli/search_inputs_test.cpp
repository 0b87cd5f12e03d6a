// What the search commands read from the command line (cli/search_inputs.h): the --target
// specification, number by number, and the --solver checks of the searches.
#include "cli/search_inputs.h"

#include <catch2/catch.hpp>
#include <string>

#include "coons/io/input_error.h"
#include "coons/net/control_net.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using coons::cli::resolve_target;

namespace {

// The message of the InputError that resolving `spec` throws ("" when it does not throw).
std::string spec_error(const std::string& spec) {
  try {
    (void)resolve_target(spec, "b.json", Boundary{}, 41);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The message of the InputError a check throws ("" when it does not throw).
template <class Check>
std::string error_of(Check check) {
  try {
    check();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("resolve_target: numbers beyond the coordinate bound are bad input naming --target", "[cli]") {
  for (const std::string spec :
       {"sphere:0,0,0,1e200", "sphere:1e61,0,0,1", "plane:0,0,0,0,0,1e200", "cylinder:0,0,0,0,0,1,-1e200"}) {
    INFO(spec);
    CHECK(spec_error(spec).rfind("command line: --target: '", 0) == 0);
    CHECK(spec_error(spec).find("beyond the bound |x| <= 1e+60") != std::string::npos);
  }
  CHECK(spec_error("sphere:0,0,0,1e60").empty());
}

TEST_CASE("resolve_target: a subnormal value is a finite number, one below the doubles is refused", "[cli]") {
  CHECK(spec_error("sphere:0,0,0,1e-320").empty());
  CHECK(resolve_target("sphere:0,0,0,1e-320", "b.json", Boundary{}, 41)->radius == 1e-320);
  // 1e-400 was read as 0, as every number of the command line was (the options now refuse it too)
  CHECK(spec_error("sphere:1e-400,0,0,1").find("'1e-400' is below the smallest double and would be read as 0") !=
        std::string::npos);
  CHECK(resolve_target("sphere:0.0e-5,-0,0,1", "b.json", Boundary{}, 41)->point.x() == 0);
  // what stod also refused stays refused
  for (const std::string spec : {"sphere:0,0,0,1e999", "sphere:0,0,0,x", "sphere:0,0,,1", "sphere:0,0,0,1 "})
    CHECK(spec_error(spec).find("is not a finite number") != std::string::npos);
}

TEST_CASE("resolve_target: a zero direction or radius is refused naming --target, a tiny direction is one", "[cli]") {
  CHECK(spec_error("plane:0,0,0,0,0,0") == "command line: --target: axis/normal must not be the zero vector");
  CHECK(spec_error("cylinder:0,0,0,0,0,0,1") == "command line: --target: axis/normal must not be the zero vector");
  CHECK(spec_error("cylinder:0,0,0,0,0,1,0") == "command line: --target: radius must be positive");
  CHECK(spec_error("sphere:0,0,0,-1") == "command line: --target: radius must be positive");
  // 1e-320 is a direction, held scaled by a power of two
  CHECK(resolve_target("cylinder:0,0,0,1e-320,0,0,1", "b.json", Boundary{}, 41)->direction.normalized() ==
        Eigen::RowVector3d(1, 0, 0));
  CHECK(resolve_target("plane:1,2,3,0,3,-6", "b.json", Boundary{}, 7)->direction == Eigen::RowVector3d(0, 0.75, -1.5));
  CHECK(resolve_target("plane:1,2,3,0,3,-6", "b.json", Boundary{}, 7)->samples == 7);
}

TEST_CASE("require_search_backend: a backend that cannot serve the alpha search is bad input naming --solver",
          "[cli]") {
  const Boundary b = test::make_random_boundary(6, 5, 1);
  // fast5 solves 5x5 stencils only, separable-banded alpha = -1/4 only: the search would fail at
  // every evaluation
  for (const char* name : {"fast5", "separable-banded"}) {
    if (!solvers::find_solver(name)) continue;  // (fast5: FFTW builds)
    INFO(name);
    const std::string message = error_of([&] { cli::require_search_backend(solvers::find_solver(name), b, false); });
    CHECK(message.rfind(std::string("command line: --solver: ") + name + " does not solve the 3x3 alpha family (", 0) ==
          0);
    CHECK(error_of([&] {
            cli::require_search_backend(solvers::find_solver(name), b, false, "shape.json");
          }).find(") (on shape.json)") != std::string::npos);
  }
  // a Cholesky-type backend where the range leaves the definite alpha in [-1/4, 1/4]
  CHECK(error_of([&] { cli::require_search_backend(solvers::find_solver("eigen-ldlt"), b, true); }) ==
        "command line: --solver: eigen-ldlt needs a positive definite system; bounds outside [-0.25, 0.25] need "
        "another solver");
  // what serves passes, auto (nullptr) always
  for (const char* name : {"eigen-ldlt", "eigen-lu", "fast", "mg"})
    if (const solvers::SolverInfo* info = solvers::find_solver(name))  // (fast: FFTW builds)
      CHECK(error_of([&] { cli::require_search_backend(info, b, false); }).empty());
  CHECK(error_of([&] { cli::require_search_backend(solvers::find_solver("eigen-lu"), b, true); }).empty());
  CHECK(error_of([&] { cli::require_search_backend(nullptr, b, true); }).empty());
}

TEST_CASE("require_weight_search_backend: a grid-stencil backend is bad input naming --solver", "[cli]") {
  CHECK(error_of([] {
          cli::require_weight_search_backend(solvers::find_solver("mg"));
        }).rfind("command line: --solver: mg works from the grid stencil only; ", 0) == 0);
  CHECK(error_of([] { cli::require_weight_search_backend(solvers::find_solver("eigen-ldlt")); }).empty());
  CHECK(error_of([] { cli::require_weight_search_backend(nullptr); }).empty());
}

TEST_CASE("require_matrix_backend: a grid-stencil backend is bad input naming --solver and what needs the matrix",
          "[cli]") {
  CHECK(error_of([] { cli::require_matrix_backend(solvers::find_solver("mg"), "this needs one"); }) ==
        "command line: --solver: mg works from the grid stencil only; this needs one");
  const solvers::SolverInfo* ldlt = solvers::find_solver("eigen-ldlt");
  const solvers::SolverInfo* taken = nullptr;
  CHECK(error_of([&] { taken = cli::require_matrix_backend(ldlt, "this needs one"); }).empty());
  CHECK(taken == ldlt);
  CHECK(error_of([&] { taken = cli::require_matrix_backend(nullptr, "this needs one"); }).empty());
  CHECK(taken == nullptr);
}
