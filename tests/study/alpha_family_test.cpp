#include "coons/study/alpha_family.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "coons/alpha/mask_objective.h"
#include "coons/mask/mask_families.h"
#include "coons/net/degree_elevation.h"
#include "solvers/registry.h"

using namespace coons;

TEST_CASE("quantile: interpolates between order statistics") {
  CHECK(*quantile({3, 1, 2, 4}, 0) == 1);
  CHECK(*quantile({3, 1, 2, 4}, 1) == 4);
  CHECK(*quantile({3, 1, 2, 4}, 0.5) == Approx(2.5));
  CHECK_FALSE(quantile({}, 0.5));
  const auto d = distribution_of({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});
  REQUIRE(d);
  CHECK(d->q10 == Approx(2));
  CHECK(d->median == Approx(6));
}

TEST_CASE("best_single_alpha: the minimiser of a known mean relative loss") {
  // f_b(α) = 1 + (α − c_b)²: relative loss (α − c_b)², mean minimised at the mean of c_b.
  const std::vector<double> c = {-0.2, -0.1, -0.15};
  const auto best = best_single_alpha(
      3, {1, 1, 1}, [&](int b, double alpha) { return 1 + (alpha - c[b]) * (alpha - c[b]); }, 81);
  REQUIRE(best);
  // f_b is tabulated on the logit grid and interpolated between nodes: the mean loss at the α found,
  // 1 + (α + 0.15)² + const, is within 1e-6 of its least value, so α is within 1e-3 of −0.15
  CHECK(*best == Approx(-0.15).epsilon(0).margin(1e-3));
  CHECK_FALSE(best_single_alpha(
      0, {}, [](int, double) { return 0.0; }, 81));
}

TEST_CASE("run_alpha_family: every boundary is counted once, losses are not negative") {
  AlphaFamilyOptions options;
  options.degrees = {3, 6};
  options.count = 6;
  options.seed = 5;
  std::string why;
  Objective thin_plate = *parse_objective("thin_plate", &why);
  options.objectives = {thin_plate};
  REQUIRE(options.is_valid(&why));
  const AlphaFamilyResult r = run_alpha_family(options);
  REQUIRE(r.cells.size() == 2);
  for (const AlphaFamilyCell& c : r.cells) {
    CHECK(c.interior + c.flat + c.at_bound + c.failed == options.count);
    for (const auto& a : c.alpha_star)
      if (a) CHECK((*a >= -0.25 && *a <= 0.25));
    REQUIRE(c.best_alpha);
    REQUIRE(c.losses);
    CHECK(c.losses->min >= 0);
    CHECK(*c.loss_mean <= c.losses->max);
  }
  const auto json = alpha_family_json(r);
  CHECK(json["cells"][0]["alpha_star"].size() == 6);
  CHECK(json["family"] == "random-smooth");
}

namespace {

// f_b(α) by a factorisation and a solve (MaskObjective): not the sine basis the study evaluates in
double exact_value(const Boundary& b, const Objective& objective, double alpha) {
  MaskObjective f(
      b, objective, [](double a) { return alpha_family(a); }, *solvers::find_solver("eigen-ldlt"));
  const auto e = f.evaluate(alpha, false);
  REQUIRE(e.ok());
  return e.value;
}

// every boundary's reported loss against (f_b(best α) − f_b*)/f_b* with f_b(best α) solved for
void check_losses_exact(const AlphaFamilyOptions& options, const AlphaFamilyResult& r, double tolerance) {
  for (const AlphaFamilyCell& c : r.cells) {
    REQUIRE(c.best_alpha);
    const Objective objective = *parse_objective(c.objective, nullptr);
    for (int k = 0; k < options.count; ++k) {
      REQUIRE(c.loss[k]);
      const Boundary b = elevate_boundary(family_boundary(options, k), c.degree, c.degree);
      const double at_best = exact_value(b, objective, *c.best_alpha);
      const double own = std::min(exact_value(b, objective, *c.alpha_star[k]), at_best);
      INFO(c.objective << " n = " << c.degree << " boundary " << k << ", best alpha " << *c.best_alpha);
      CHECK(*c.loss[k] == Approx((at_best - own) / own).epsilon(0).margin(tolerance));
    }
  }
}

}  // namespace

TEST_CASE("run_alpha_family: each boundary's loss is its exact relative excess at the best alpha, to 1e-6") {
  // the losses come from f_b interpolated on the grid, so that a merge of shards gets the same;
  // here each is checked against f_b at the best α from a solve
  AlphaFamilyOptions options;
  options.degrees = {3, 8, 20};
  options.count = 4;
  options.seed = 7;
  options.objectives = {*parse_objective("thin_plate", nullptr), *parse_objective("e3", nullptr)};
  const AlphaFamilyResult r = run_alpha_family(options);
  REQUIRE(r.cells.size() == 6);
  check_losses_exact(options, r, 1e-6);
}

TEST_CASE("run_alpha_family: a family of one boundary repeated loses nothing at its best alpha") {
  // the perturbed family at amplitude 0: every member is the base, so the best single α is its
  // own optimum and every loss is zero up to the grid's interpolation (the dome, repeated, lost
  // 6.6e-6 at n = 5 on the log grid of α + 1/4 with cubics used before)
  AlphaFamilyOptions options;
  options.degrees = {5, 12};
  options.count = 3;
  options.base_name = "saddle";
  options.base = elevate_boundary(random_smooth_boundary(11, 0), 3, 3);
  options.amplitude = 0;
  options.objectives = {*parse_objective("thin_plate", nullptr), *parse_objective("e3", nullptr)};
  const AlphaFamilyResult r = run_alpha_family(options);
  for (const AlphaFamilyCell& c : r.cells) {
    REQUIRE(c.best_alpha);
    REQUIRE(c.losses);
    INFO(c.objective << " n = " << c.degree);
    CHECK(c.losses->max <= 1e-6);
    CHECK(*c.best_alpha == Approx(*c.alpha_star[0]).epsilon(0).margin(1e-3));
  }
  check_losses_exact(options, r, 1e-7);
}

TEST_CASE("alpha_family_conclusions: 'no single α' only when some boundary loses more than 1 %") {
  AlphaFamilyResult r;
  r.options.count = 2;
  r.objectives = {"thin_plate"};
  AlphaFamilyCell c;
  c.degree = 3;
  c.objective = "thin_plate";
  c.best_alpha = -0.1;
  c.loss = {0.001, 0.002};
  c.losses = distribution_of({0.001, 0.002});
  c.loss_mean = 0.0015;
  c.interior = 2;
  r.cells = {c};
  CHECK(alpha_family_conclusions(r).find("within 1 %") != std::string::npos);
  CHECK(alpha_family_conclusions(r).find("No single") == std::string::npos);
  r.cells[0].losses = distribution_of({0.001, 0.2});
  r.cells[0].loss_mean = 0.1005;
  CHECK(alpha_family_conclusions(r).find("No single α is best") != std::string::npos);
}

TEST_CASE("AlphaFamilyOptions: degrees below the sides' degree are refused") {
  AlphaFamilyOptions options;
  options.degrees = {2, 4};
  std::string why;
  CHECK_FALSE(options.is_valid(&why));
  CHECK(why.find("degree 2") != std::string::npos);
}

TEST_CASE("best_single_alpha_on_grid: a mean loss falling to the grid's end gives its last alpha, flagged") {
  // two boundaries whose values fall all the way along the grid: the last node is the best
  std::vector<std::vector<double>> values(2, std::vector<double>(81));
  for (int k = 0; k < 81; ++k) {
    values[0][k] = 2 + (80 - k) * 0.01;
    values[1][k] = 3 + (80 - k) * (80 - k) * 1e-3;
  }
  const auto best = best_single_alpha_on_grid(values, {2, 3});
  REQUIRE(best);
  CHECK(best->alpha == family_alpha_grid(81).back());
  CHECK(best->alpha == Approx(0.25 - kFamilyGridEnd).epsilon(1e-12));
  CHECK(best->at_grid_end);
  // a minimum inside the grid is not flagged
  for (int k = 0; k < 81; ++k) values[0][k] = values[1][k] = 1 + (k - 40) * (k - 40) * 1e-3;
  const auto inside = best_single_alpha_on_grid(values, {1, 1});
  REQUIRE(inside);
  CHECK_FALSE(inside->at_grid_end);
}

TEST_CASE("best_single_alpha_on_grid: curves of unequal or too few values give no alpha") {
  // curves read back from shard files: every one must have the same grid, and one optimum each
  std::vector<std::vector<double>> values(2, std::vector<double>(9));
  for (int k = 0; k < 9; ++k) values[0][k] = values[1][k] = 1 + (k - 4) * (k - 4) * 1e-2;
  REQUIRE(best_single_alpha_on_grid(values, {1, 1}));
  CHECK_FALSE(best_single_alpha_on_grid({{}, {}}, {1, 1}));
  CHECK_FALSE(best_single_alpha_on_grid({{1}, {1}}, {1, 1}));
  CHECK_FALSE(best_single_alpha_on_grid(values, {1}));
  std::vector<std::vector<double>> shorter = values;
  shorter[1].resize(3);
  CHECK_FALSE(best_single_alpha_on_grid(shorter, {1, 1}));
  std::vector<std::vector<double>> longer = values;
  longer[1].push_back(1);
  CHECK_FALSE(best_single_alpha_on_grid(longer, {1, 1}));
}

TEST_CASE("alpha_family_conclusions: a best single α at the grid's end is said to be there") {
  AlphaFamilyResult r;
  r.options.count = 2;
  r.objectives = {"thin_plate"};
  AlphaFamilyCell c;
  c.degree = 3;
  c.objective = "thin_plate";
  c.best_alpha = 0.25;
  c.best_at_grid_end = true;
  c.loss = {0.001, 0.002};
  c.losses = distribution_of({0.001, 0.002});
  c.loss_mean = 0.0015;
  c.interior = 2;
  r.cells = {c};
  const std::string text = alpha_family_conclusions(r);
  INFO(text);
  CHECK(text.find("The best single α is at the end of its grid at 0.25 (n = 3)") != std::string::npos);
  CHECK(alpha_family_json(r)["cells"][0]["best_alpha_at_grid_end"] == true);
  CHECK(alpha_family_markdown(r, {}).find("| 3 | 0.25 (grid end) |") != std::string::npos);
}

TEST_CASE("alpha_family_conclusions: medians on the bound, medians that do not move, a spread of one mu") {
  // Every α* at −1/4 found from inside by 1e-9: "moves towards −1/4 as n grows (-0.25, -0.25, -0.25)";
  // equal medians: "not monotone towards −1/4"; one μ* of 200: "μ*'s 90th over 10th percentile: 1".
  AlphaFamilyResult r;
  r.options.count = 3;
  r.objectives = {"e3"};
  for (int n : {3, 5, 8}) {
    AlphaFamilyCell c;
    c.degree = n;
    c.objective = "e3";
    c.alpha = distribution_of({-0.25 + 3e-9 / n, -0.25 + 2e-9 / n, -0.25 + 1e-9 / n});
    c.at_bound = 3;
    c.mu = distribution_of({7.0});
    r.cells.push_back(c);
  }
  std::string text = alpha_family_conclusions(r);
  INFO(text);
  CHECK(text.find("The median α* is −1/4, the bound, at every degree") != std::string::npos);
  CHECK(text.find("moves towards") == std::string::npos);
  CHECK(text.find("90th over 10th") == std::string::npos);
  for (AlphaFamilyCell& c : r.cells) c.alpha = distribution_of({-0.1, -0.1, -0.1});
  text = alpha_family_conclusions(r);
  CHECK(text.find("The median α* does not move with n") != std::string::npos);
  CHECK(text.find("not monotone") == std::string::npos);
}
