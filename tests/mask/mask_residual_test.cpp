// mask_residual for a stencil over a free set: the classical residual for the alpha stencil on the
// interior, zero at a solution, and only the free points count.
#include "coons/mask/mask_residual.h"

#include <catch2/catch.hpp>

#include "coons/mask/mask9.h"
#include "coons/mask/solve_stencil_net.h"
#include "solvers/registry.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

TEST_CASE("mask_residual: the alpha stencil on the interior is the 3x3 residual", "[mask]") {
  const ControlNet net = make_random_net(6, 5, 21);
  const StencilProblem p = rings_problem(net, 1);
  for (double alpha : {-0.25, -0.1, 0.0, 0.2}) {
    const Mask9 mask = alpha_mask(alpha);
    CHECK(mask_residual(net, free_points(p), alpha_stencil(mask)) == Approx(mask_residual(net, mask)).epsilon(1e-14));
  }
}

TEST_CASE("mask_residual: zero at the stencil solve, and data points do not count", "[mask]") {
  const ControlNet net = make_random_net(8, 7, 22);
  StencilProblem p = rings_problem(net, 2);
  p.free = free_points(p);
  p.free(4, 3) = false;  // a fixed point inside: its equation is not part of the problem
  auto solver = solvers::make_solver("eigen-ldlt");
  const StencilSolveResult r = solve_stencil_net(p, biharmonic_stencil(), *solver);
  REQUIRE(r.summary.ok());
  CHECK(mask_residual(r.net, p.free, biharmonic_stencil()) < 1e-13);
  FreeGrid all = free_points(rings_problem(net, 2));
  CHECK(mask_residual(r.net, all, biharmonic_stencil()) > 1e-3);  // (4, 3) is random data
  CHECK(mask_residual(r.net, FreeGrid::Constant(9, 8, false), biharmonic_stencil()) == 0);
}
