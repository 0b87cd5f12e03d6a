// The memory estimates of memory_estimate.h against what the code allocates: upper bounds, but
// not far above (the old dense-Gram estimate of net_metrics_bytes was 2.0–2.5 times the peak).
#include "coons/study/memory_estimate.h"

#include <catch2/catch.hpp>

#include "coons/mask/assemble_mask_system.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/mask/stencil_system.h"
#include "coons/net/banded_gram.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {
double stored_entries(int k) { return BandedGram(k).stored_fraction() * (double(k) + 1) * (double(k) + 1); }
}  // namespace

TEST_CASE("banded_gram_entries: an upper bound on what BandedGram keeps, within 1.25 of it", "[study]") {
  for (int k : {0, 1, 10, 60, 100, 300, 1000}) {
    INFO("k = " << k);
    const double held = stored_entries(k);
    CHECK(banded_gram_entries(k) >= held);
    CHECK(banded_gram_entries(k) <= 1.25 * held);
  }
}

TEST_CASE("net_metrics_bytes: above what net_metrics holds at once, within 1.6 of it", "[study]") {
  // Held together for one coordinate: the net (3 doubles a point), its grid, the four products
  // Y Δ^bᵀ G^{n−b} and one G^{m−a} Δ^a X (6 grids), and the eight banded Gram matrices.
  for (auto [m, n] : {std::pair{40, 30}, std::pair{300, 200}, std::pair{1000, 700}}) {
    INFO("m = " << m << ", n = " << n);
    double grams = 0;
    for (int order = 0; order <= 3; ++order) grams += stored_entries(m - order) + stored_entries(n - order);
    const double held = (double(m) + 1) * (double(n) + 1) * 8 * (3 + 6) + 8 * grams;
    CHECK(net_metrics_bytes(m, n) >= held);
    CHECK(net_metrics_bytes(m, n) <= 1.6 * held);
  }
}

TEST_CASE("net_solve_bytes: a 5x5 stencil's matrix is counted with its 25 entries a row", "[study]") {
  const int m = 30, n = 26;
  const ControlNet net = make_random_net(m, n, 5);
  const double entries3 = double(assemble_mask_system(net, alpha_mask(-0.2)).A.nonZeros());
  const double entries5 = double(assemble_stencil_system(rings_problem(net, 2), c1_family_stencil(0.5)).A.nonZeros());
  REQUIRE(entries5 > 2 * entries3);
  const double extra = 12 * (entries5 - entries3);  // a value and a row index an entry
  for (const char* name : {"cg", "eigen-ldlt"}) {
    INFO(name);
    const solvers::SolverInfo& solver = backend(name);
    const double added = net_solve_bytes(m, n, &solver, kStencil5Nonzeros) - net_solve_bytes(m, n, &solver);
    CHECK(added >= extra);
    CHECK(net_solve_bytes(m, n, &solver, kStencil5Nonzeros) <= 4 * net_solve_bytes(m, n, &solver));
  }
}
