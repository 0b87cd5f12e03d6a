// `coons degree-limit` through the real binary, at small degrees: the docs/formats.md fields,
// μ* = −n²(1 + 4α*)/(4α*), null (not a number) where the optimum is flat, and the error contract.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "coons/study/degree_limit.h"
#include "support/cli_support.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

TEST_CASE("coons degree-limit: the fields of the degree law, mu* from alpha*", "[cli]") {
  const CommandResult r = run_coons("degree-limit '" + kData +
                                    "/boundaries/pillow.json' --objective thin_plate --degrees 4 5 6 8 10 12 "
                                    "--continuum-degrees 10 14");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json j = json::parse(r.out);
  CHECK(j["degrees"] == json({4, 5, 6, 8, 10, 12}));
  for (const char* key : {"alpha_star", "mu_star", "mu_limit", "mu_limit_error", "rate", "fits",
                          "within_5_percent_from", "within_1_percent_from", "mu_continuum", "spread"})
    CHECK(j.contains(key));
  for (size_t k = 0; k < 6; ++k) {
    const double n = j["degrees"][k], a = j["alpha_star"][k], mu = j["mu_star"][k];
    CHECK(mu == Approx(-n * n * (1 + 4 * a) / (4 * a)).epsilon(1e-12));
  }
  // μ* falls with the degree and stays above the continuum optimum, which is converged in N
  CHECK(j["mu_star"][5].get<double>() < j["mu_star"][0].get<double>());
  REQUIRE(j["continuum"].size() == 2);
  const double c10 = j["continuum"][0]["mu"], c14 = j["continuum"][1]["mu"];
  CHECK(std::abs(c10 - c14) < 1e-3 * c14);
  CHECK(j["mu_star"][5].get<double>() > c14);
  CHECK(j["fits"].size() == 3);  // three points from n = 8: the two-parameter forms and the a/n + b/n² form
}

TEST_CASE("coons degree-limit: the n^-p fit says whether p stopped at the end of its range", "[cli]") {
  // (p_at_bound was never written: the form has three parameters, mu_inf, a and p)
  const CommandResult r = run_coons("degree-limit '" + kData +
                                    "/boundaries/pillow.json' --objective thin_plate --degrees 8 10 12 14 "
                                    "--continuum-degrees 6");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json j = json::parse(r.out);
  int with_p = 0;
  for (const json& fit : j["fits"]) {
    INFO(fit.dump());
    const bool has_p = fit["parameters"].contains("p");
    CHECK(fit.contains("p_at_bound") == has_p);
    if (!has_p) continue;
    ++with_p;
    const double p = fit["parameters"]["p"];
    const coons::DegreeLimitOptions range;  // the search range of p, and fit_degree_limit's nearness to its ends
    const double near = 1e-6 * (range.max_rate - range.min_rate);
    CHECK(fit["p_at_bound"].get<bool>() == (range.max_rate - p <= near || p - range.min_rate <= near));
  }
  CHECK(with_p == 1);
}

TEST_CASE("coons degree-limit: a flat objective gives nulls, not numbers", "[cli]") {
  const CommandResult r = run_coons("degree-limit '" + kData +
                                    "/boundaries/saddle.json' --objective thin_plate --degrees 4 6 "
                                    "--continuum-degrees 6");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json j = json::parse(r.out);
  CHECK(j["optimum"] == json({"flat", "flat"}));
  CHECK(j["mu_star"] == json({nullptr, nullptr}));
  CHECK(j["mu_limit"].is_null());
  CHECK(j["within_5_percent_from"].is_null());
  CHECK(j["continuum"][0]["status"] == "flat");
}

TEST_CASE("coons degree-limit: bad input is one error line, exit 2, nothing written", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("report");
  const std::string pillow = "'" + kData + "/boundaries/pillow.json'";
  const std::string target_out = " --degrees 4 6 --objective target --out '" + out + "'";
  for (const std::string& options :
       {std::string(" --degrees 6 4"), std::string(" --objective no_such_energy"),
        std::string(" --objective thin_plate e3"), std::string(" --continuum-degrees 100"), target_out}) {
    std::string command = kCoons;
    command += " degree-limit ";
    const std::string args = pillow + options;
    command += args;
    const CommandResult r = run_command(command);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: command line: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("coons degree-limit: --out writes the report with its generated conclusions", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("report");
  const CommandResult r = run_coons("degree-limit '" + kData + "/boundaries/pillow.json' '" + kData +
                                    "/boundaries/saddle.json' --objective thin_plate e3 --degrees 4 6 8 "
                                    "--continuum-degrees 8 --out '" +
                                    out + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(fs::exists(out + "/report.md"));
  const json results = json::parse(std::ifstream(out + "/results.json"));
  CHECK(results.size() == 4);
  CHECK(r.out.find("## 2. Conclusions") != std::string::npos);
  CHECK(r.out.find("saddle, thin_plate.** flat at every degree") != std::string::npos);
}

TEST_CASE("coons degree-limit: a weighted sum written with spaces is the same objective", "[cli]") {
  // "thin_plate + 0.1*e3" was refused as "unknown objective 'thin_plate '" while search-alpha took it
  const std::string base = "degree-limit '" + kData + "/boundaries/dome.json' --degrees 3 4 5 --objective ";
  const CommandResult spaced = run_coons(base + "'thin_plate + 0.1*e3'");
  const CommandResult tight = run_coons(base + "thin_plate+0.1*e3");
  INFO(spaced.err);
  REQUIRE(spaced.status == 0);
  REQUIRE(tight.status == 0);
  const json a = json::parse(spaced.out), b = json::parse(tight.out);
  CHECK(a["objective"] == "thin_plate+0.1*e3");
  CHECK(a["alpha_star"] == b["alpha_star"]);
}

TEST_CASE("coons degree-limit: degrees below a boundary without curves are listed as skipped and all of them refused",
          "[cli]") {
  // pillow is a 3x3 boundary without "curves": degree 2 cannot be made from it. It used to vanish
  // from the result without a word, and --degrees 2 alone gave an empty result with exit 0.
  const std::string pillow = "'" + kData + "/boundaries/pillow.json'";
  const CommandResult some = run_coons("degree-limit " + pillow + " --degrees 2 4 --continuum-degrees 2");
  INFO(some.err);
  REQUIRE(some.status == 0);
  const json j = json::parse(some.out);
  CHECK(j["degrees"] == json({4}));
  CHECK(j["skipped_degrees"] == json({2}));
  CHECK(j["skipped_continuum_degrees"] == json({2}));
  CHECK(j["skipped_reason"].get<std::string>().find("below the boundary's degree 3x3") != std::string::npos);
  CHECK(j["continuum"].empty());
  CHECK(j["continuum_unavailable"].get<std::string>().rfind("every continuum degree asked for is below", 0) == 0);

  const CommandResult none = run_coons("degree-limit " + pillow + " --degrees 2");
  INFO(none.err);
  CHECK(none.status == 2);
  CHECK(none.out.empty());
  CHECK(none.err.find("pillow.json: --degrees: every degree asked for (2) is below") != std::string::npos);
  CHECK(std::count(none.err.begin(), none.err.end(), '\n') == 1);

  // a boundary with curves is refitted at any degree: nothing skipped, no field
  const CommandResult fitted =
      run_coons("degree-limit '" + kData + "/boundaries/dome.json' --degrees 2 4 --continuum-degrees 4");
  INFO(fitted.err);
  REQUIRE(fitted.status == 0);
  const json f = json::parse(fitted.out);
  CHECK(f["degrees"] == json({2, 4}));
  CHECK_FALSE(f.contains("skipped_degrees"));
}

TEST_CASE("coons search-alpha and degree-limit: an optimum at alpha = 0 found with rounding has no mu", "[cli]") {
  // The discrete Dirichlet energy is least at alpha = 0 exactly (its Euler-Lagrange equation is the
  // alpha = 0 mask). The search returns 0 up to rounding (-6.4e-17), and mu = -n^2(1+4a)/(4a) was
  // printed as 3.5e16, or null, by the sign of that rounding error.
  const std::string dome = "'" + kData + "/boundaries/dome.json'";
  const CommandResult s = run_coons("search-alpha " + dome + " --objective discrete_dirichlet");
  INFO(s.err);
  REQUIRE(s.status == 0);
  const json search = json::parse(s.out);
  CHECK(std::abs(search["alpha"].get<double>()) < 1e-12);
  CHECK(search["mu"].is_null());
  const CommandResult d = run_coons("degree-limit " + dome + " --objective discrete_dirichlet --degrees 3 4 5 6");
  INFO(d.err);
  REQUIRE(d.status == 0);
  const json law = json::parse(d.out);
  for (const json& a : law["alpha_star"]) CHECK(std::abs(a.get<double>()) < 1e-12);
  CHECK(law["mu_star"] == json({nullptr, nullptr, nullptr, nullptr}));
}

TEST_CASE("coons degree-limit: a rerun that draws no plot takes away the earlier run's plots of its names", "[cli]") {
  // docs/formats.md: "A plot that was not drawn also removes an earlier run's file of its name";
  // a rerun at one degree left mu_vs_degree_thin_plate.png beside a report without it
  TempDir dir;
  const std::string out = dir.file("r");
  const std::string base =
      "degree-limit '" + kData + "/boundaries/dome.json' --objective thin_plate --out '" + out + "'";
  const CommandResult first = run_coons(base + " --degrees 3 4");
  INFO(first.err);
  REQUIRE(first.status == 0);
  const std::string plot = out + "/figures/mu_vs_degree_thin_plate.png";
  REQUIRE(fs::exists(plot));
  const CommandResult second = run_coons(base + " --degrees 3");
  INFO(second.err);
  REQUIRE(second.status == 0);
  CHECK_FALSE(fs::exists(plot));
  CHECK_FALSE(fs::exists(out + "/figures/mu_gap_vs_degree_thin_plate.png"));
  CHECK(fs::exists(out + "/report.md"));
}
