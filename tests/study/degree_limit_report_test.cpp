// The generated conclusions of the degree-law report (coons/study/degree_limit_report.h): a claim
// is printed only when the table supports it, otherwise the measured value takes its place.
#include "coons/study/degree_limit_report.h"

#include <catch2/catch.hpp>
#include <cmath>

#include "support/fixtures.h"

using namespace coons;
using coons::test::contains;
using coons::test::joined_lines;

namespace {

//! A synthetic entry: μ*(n) = limit + a/n at the given degrees, with the limit fitted as the
//! report's generator sees it, and a continuum optimum mu_c.
DegreeLimitEntry synthetic(double limit, double a, std::optional<double> mu_c) {
  DegreeLimitEntry e;
  e.boundary = "synthetic";
  e.objective = "thin_plate";
  std::vector<std::pair<int, double>> mus;
  for (int n : {4, 8, 12, 16, 24, 32, 48, 64}) {
    DegreeLimitCell c;
    c.degree = n;
    c.mu = limit + a / n;
    c.alpha.parameter = -double(n) * n / (4 * (double(n) * n + *c.mu));
    mus.emplace_back(n, *c.mu);
    e.cells.push_back(c);
  }
  e.limit = fit_degree_limit(mus);
  double lo = HUGE_VAL, hi = 0;
  for (auto [n, mu] : mus)
    if (n <= 32) {
      lo = std::min(lo, mu);
      hi = std::max(hi, mu);
    }
  e.mu_spread.ratio = hi / lo;
  e.mu_spread.points = 6;
  e.mu_spread.from = 4;
  e.mu_spread.to = 32;
  if (mu_c) {
    ContinuumOptimum o;
    o.degree = 40;
    o.mu = mu_c;
    e.continuum.push_back(o);
  }
  return e;
}

}  // namespace

TEST_CASE("degree_limit_conclusions: a drifting mu* is never called degree-independent", "[study]") {
  const std::string text = joined_lines(degree_limit_conclusions(synthetic(5, 40, 5)));
  INFO(text);
  CHECK_FALSE(contains(text, "does not depend on the degree"));
  CHECK(contains(text, "μ* drifts with the degree"));
  CHECK(contains(text, "μ*(4) = 15"));  // the measured drift is printed instead
}

TEST_CASE("degree_limit_conclusions: a small spread over degrees close together is not called constant", "[study]") {
  // the dome's e3 at n = 30, 31, 32 has max/min 1.003, over 4 … 32 1.57: the report said "μ* does
  // not depend on the degree: max/min = 1.003 over n = 4 … 32", a range it had not measured
  DegreeLimitEntry e = synthetic(5, 0.4, std::nullopt);
  e.mu_spread.from = 30;
  const std::string text = joined_lines(degree_limit_conclusions(e));
  INFO(text);
  CHECK_FALSE(contains(text, "does not depend on the degree"));
  CHECK(contains(text, "over n = 30 … 32, too narrow a range of degrees"));
  const std::string headline = degree_limit_headline({e}, "thin_plate");
  CHECK_FALSE(contains(headline, "does not depend"));
  CHECK(contains(headline, "n = 30 … 32"));
}

TEST_CASE("degree_limit_conclusions: a nearly constant mu* is called degree-independent", "[study]") {
  const std::string text = joined_lines(degree_limit_conclusions(synthetic(5, 0.4, std::nullopt)));
  INFO(text);
  CHECK(contains(text, "does not depend on the degree"));
  CHECK_FALSE(contains(text, "drifts"));
}

TEST_CASE("degree_limit_conclusions: agreement with the continuum only when the numbers agree", "[study]") {
  const std::string agree = joined_lines(degree_limit_conclusions(synthetic(5, 40, 5.01)));
  INFO(agree);
  CHECK(contains(agree, "tends to the continuum optimum"));
  // the same table against a continuum optimum 30 % away: the claim is replaced by the gap
  const std::string apart = joined_lines(degree_limit_conclusions(synthetic(5, 40, 6.5)));
  INFO(apart);
  CHECK_FALSE(contains(apart, "tends to the continuum optimum"));
  CHECK(contains(apart, "differ by 23.1 %"));
}

TEST_CASE("degree_limit_conclusions: no convergence claimed when the tail turns", "[study]") {
  DegreeLimitEntry e = synthetic(5, 40, 5);
  e.cells.back().mu = 9.0;  // the last point turns upwards
  std::vector<std::pair<int, double>> mus;
  for (const auto& c : e.cells) mus.emplace_back(c.degree, *c.mu);
  e.limit = fit_degree_limit(mus);
  const std::string text = joined_lines(degree_limit_conclusions(e));
  INFO(text);
  CHECK_FALSE(contains(text, "converges"));
  CHECK_FALSE(contains(text, "tends to the continuum"));
  CHECK(contains(text, "no limit claimed"));
}

TEST_CASE("degree_limit_headline: claims only what every shape of the table supports", "[study]") {
  const std::vector<DegreeLimitEntry> agreeing = {synthetic(5, 40, 5), synthetic(7, 30, 7)};
  const std::string all = degree_limit_headline(agreeing, "thin_plate");
  INFO(all);
  CHECK(contains(all, "drifts with the degree"));
  CHECK(contains(all, "converges"));
  CHECK(contains(all, "to the optimum of the continuous problem"));
  // one shape whose limit misses its continuum optimum: the headline no longer says it
  const std::vector<DegreeLimitEntry> one_off = {synthetic(5, 40, 5), synthetic(7, 30, 9)};
  const std::string some = degree_limit_headline(one_off, "thin_plate");
  INFO(some);
  CHECK_FALSE(contains(some, "to the optimum of the continuous problem"));
  CHECK(contains(some, "converges, as n^−p"));
  // constant sequences give the constant headline, drifting ones never do
  const std::string constant = degree_limit_headline({synthetic(5, 0.3, std::nullopt)}, "thin_plate");
  CHECK(contains(constant, "does not depend on the degree"));
  CHECK_FALSE(contains(all, "does not depend on the degree"));
}

TEST_CASE("degree_limit_conclusions: without an established limit, that is the reason no agreement is claimed",
          "[study]") {
  // a limit whose error exceeds the threshold: the sentence used to blame a gap of 4 % that the
  // 5 % rule would have accepted
  DegreeLimitEntry e = synthetic(76.4, 30, 73.46);
  REQUIRE(e.limit.limit);
  e.limit.limit_error = 20;  // far above the allowed relative error
  const std::string text = joined_lines(degree_limit_conclusions(e));
  CHECK(contains(text, "is not established (error ± 20)"));
  CHECK_FALSE(contains(text, "tends to the continuum optimum"));
  CHECK_FALSE(contains(text, "not claimed to agree"));
}

TEST_CASE("degree_limit_report_markdown: an entry fitted with fewer than two tolerances has none made up", "[study]") {
  // DegreeLimitOptions::is_valid allows any number of tolerances; the report used to read the first
  // two of every entry
  for (const std::vector<double>& tolerances : {std::vector<double>{}, std::vector<double>{0.05}}) {
    DegreeLimitEntry e = synthetic(5, 40, 5);
    DegreeLimitOptions options;
    options.tolerances = tolerances;
    REQUIRE(options.is_valid(nullptr));
    std::vector<std::pair<int, double>> mus;
    for (const auto& c : e.cells) mus.emplace_back(c.degree, *c.mu);
    e.limit = fit_degree_limit(mus, options);
    REQUIRE(e.limit.within_from.size() == tolerances.size());
    const std::string text = joined_lines(degree_limit_conclusions(e));
    INFO(text);
    CHECK(contains(text, "converges"));
    CHECK(contains(text, "within 5 %") == !tolerances.empty());
    CHECK_FALSE(contains(text, "within 1 %"));
    const std::string md = degree_limit_report_markdown({e}, DegreeLimitStudyOptions{}, Provenance{}, {});
    INFO(md);
    CHECK(contains(md, "| synthetic | thin_plate |"));
  }
}

TEST_CASE("degree_limit_report_markdown: the within labels are the tolerances' values", "[study]") {
  // the conclusions and the table used to say "within 5 %" and "within 1 %" whatever the tolerances
  DegreeLimitEntry e = synthetic(5, 40, 5);
  DegreeLimitStudyOptions options;
  options.limit.tolerances = {0.1, 0.02, 0.005};
  REQUIRE(options.limit.is_valid(nullptr));
  std::vector<std::pair<int, double>> mus;
  for (const auto& c : e.cells) mus.emplace_back(c.degree, *c.mu);
  e.limit = fit_degree_limit(mus, options.limit);
  const std::string text = joined_lines(degree_limit_conclusions(e));
  INFO(text);
  CHECK(contains(text, "; within 10 % "));
  CHECK(contains(text, ", within 2 % "));
  CHECK(contains(text, ", within 0.5 % "));
  CHECK_FALSE(contains(text, "within 5 %"));
  CHECK_FALSE(contains(text, "within 1 %"));
  const std::string md = degree_limit_report_markdown({e}, options, Provenance{}, {});
  INFO(md);
  CHECK(contains(md, "| within 10 % from | within 2 % from | within 0.5 % from | μ_c (Ritz) |"));
  CHECK_FALSE(contains(md, "within 5 % from"));
  // the default tolerances keep the labels they had
  const std::string defaults = degree_limit_report_markdown({synthetic(5, 40, 5)}, {}, Provenance{}, {});
  CHECK(contains(defaults, "| within 5 % from | within 1 % from | μ_c (Ritz) |"));
}

TEST_CASE("degree_limit_conclusions: skipped degrees are named with the reason", "[study]") {
  DegreeLimitEntry e = synthetic(5, 40, 5);
  CHECK_FALSE(contains(joined_lines(degree_limit_conclusions(e)), "not measured"));
  e.skipped_degrees = {2, 3};
  e.skipped_continuum_degrees = {2};
  e.skipped_reason = "below the boundary's degree 4x4";
  const std::string text = joined_lines(degree_limit_conclusions(e));
  INFO(text);
  CHECK(contains(text, "Degrees not measured: 2 3 (search); 2 (continuum), below the boundary's degree 4x4."));
}

TEST_CASE("degree_limit_conclusions: no form fits best where each passes through its points", "[study]") {
  // Two points at n >= 8: both two-parameter forms interpolate them, and "mu_inf + a/n fits best"
  // was decided by residuals of 0 and 1.8e-16 (their limits 5.25 and 7.26).
  DegreeLimitEntry e = synthetic(5, 40, std::nullopt);
  const auto fit = [](const char* form, std::vector<std::pair<std::string, double>> parameters, double residual,
                      int points) {
    LimitFit f;
    f.form = form;
    f.parameters = std::move(parameters);
    f.residual = residual;
    f.points = points;
    return f;
  };
  e.limit.fits = {fit("mu_inf + a/n", {{"mu_inf", 5.25}, {"a", 1}}, 0, 2),
                  fit("mu_inf + a/n^2", {{"mu_inf", 7.26}, {"a", 1}}, 1.8e-16, 2)};
  std::string text = joined_lines(degree_limit_conclusions(e));
  INFO(text);
  CHECK_FALSE(contains(text, "fits best"));
  CHECK(contains(text, "No candidate form is preferred"));
  for (LimitFit& f : e.limit.fits) f.points = 3;  // one point more than parameters: compared
  text = joined_lines(degree_limit_conclusions(e));
  CHECK(contains(text, "mu_inf + a/n fits best"));
}
