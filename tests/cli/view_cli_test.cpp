// `coons view` through the real binary: the page, its summary and the input edge.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "coons/config.h"
#include "support/cli_support.h"

using namespace coons::test;
namespace fs = std::filesystem;

namespace {

// A page needs three.js, found at configure time; without it each test says "skipped" and returns.
bool three_js_missing() {
  if (COONS_HAVE_THREE_JS) return false;
  WARN("skipped: three.js not found at configure time (apt-get install libjs-three)");
  return true;
}

}  // namespace

TEST_CASE("coons view: one page with the optima, refused without --force when it exists", "[cli][view]") {
  if (three_js_missing()) return;
  const TempDir dir;
  const std::string page = dir.file("dome.html");
  const std::string command =
      "view " + quoted(kData + "/boundaries/dome.json") + " --out " + quoted(page) + " --alphas 21 --samples 9";
  const CommandResult r = run_coons(command);
  REQUIRE(r.status == 0);
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  CHECK(summary["boundary"] == "dome");
  CHECK(summary["page"] == page);
  CHECK(summary["frames"].get<int>() >= 21);
  CHECK(summary["optima"]["thin_plate"].get<double>() == Approx(summary["initial_alpha"].get<double>()));
  const std::string text = read_text(page);
  CHECK(text.size() == summary["bytes"].get<size_t>());
  CHECK(text.find("REVISION") != std::string::npos);  // three.js is inlined
  CHECK(text.find("window.coonsView") != std::string::npos);

  const CommandResult again = run_coons(command);
  CHECK(again.status == 2);
  CHECK(again.out.empty());
  CHECK(again.err == "error: " + page + ": --force: exists; give --force to overwrite it\n");
}

TEST_CASE("coons view: without --alpha the page opens inside its slider's range", "[cli][view]") {
  // the dome over [0, 0.1] (its thin-plate optimum, about -0.1, outside) opened at alpha = -0.25
  if (three_js_missing()) return;
  const TempDir dir;
  const CommandResult r = run_coons("view " + quoted(kData + "/boundaries/dome.json") + " --from 0 --to 0.1 --out " +
                                    quoted(dir.file("dome.html")) + " --alphas 5 --samples 5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const double initial = nlohmann::json::parse(r.out)["initial_alpha"].get<double>();
  CHECK(initial >= 0);
  CHECK(initial <= 0.1);
}

TEST_CASE("coons view: a missing three.js is bad input naming libjs-three, nothing written", "[cli][view]") {
  const TempDir dir;
  const std::string page = dir.file("p.html");
  const CommandResult r = run_coons("view " + quoted(kData + "/boundaries/dome.json") + " --out " + quoted(page) +
                                    " --three-js " + quoted(dir.file("missing.js")));
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("libjs-three") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(page));
  const CommandResult bad =
      run_coons("view " + quoted(kData + "/boundaries/dome.json") + " --out " + quoted(page) + " --alphas 1");
  CHECK(bad.status == 2);
  CHECK_FALSE(fs::exists(page));
}

TEST_CASE("coons study --html: a page per shape in pages/, linked from the report", "[cli][view]") {
  if (three_js_missing()) return;
  const TempDir dir;
  const CommandResult r = run_coons(
      "study " + quoted(kData + "/boundaries/dome.json") + " " + quoted(kData + "/triangles/dome_half.json") + " " +
      quoted(kData + "/boundaries/bspline_wave.json") + " --degrees 3 4 --html --out " + quoted(dir.file("out")));
  REQUIRE(r.status == 0);
  const std::string report = read_text(dir.file("out/report.md"));
  CHECK(report.find("## Pages") != std::string::npos);
  // (the B-spline boundary's page: view takes B-spline boundaries since 2026-12-01, review r63a)
  for (const char* page : {"pages/dome.html", "pages/dome_half.html", "pages/bspline_wave.html"}) {
    CHECK(report.find(std::string("(") + page + ")") != std::string::npos);
    CHECK(fs::file_size(dir.path / "out" / page) > 100000);
  }
}

TEST_CASE("coons view: on a triangle --from/--to and an --alpha outside the c range are bad input", "[cli][view]") {
  // --from/--to used to be ignored for triangles and --alpha taken unchecked as the first c
  const TempDir dir;
  const std::string page = dir.file("t.html");
  for (const auto& [args, field] : {std::pair{std::string(" --from -0.1"), std::string("--from")},
                                    std::pair{std::string(" --to 0.1"), std::string("--to")},
                                    std::pair{std::string(" --alpha 5"), std::string("--alpha")}}) {
    std::string command = "view " + quoted(kData + "/triangles/dome_half.json");
    command.append(" --out ").append(quoted(page)).append(args);
    const CommandResult r = run_coons(command);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: command line: " + field + ": ", 0) == 0);
    CHECK_FALSE(fs::exists(page));
  }
}

TEST_CASE("coons view: a triangle without interior points has flat optima, as search-alpha says", "[cli][view]") {
  // degree 1 and 2: no interior point, so no energy depends on c. The page said not_applicable
  // where search-alpha says flat.
  const TempDir dir;
  const std::string degree1 =
      dir.write("d1.json", R"({"type": "triangle", "sides": [[[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [0, 1, 0]],
                                                             [[0, 1, 0], [0, 0, 0]]]})");
  const std::string degree2 =
      dir.write("d2.json", R"({"type": "triangle", "sides": [[[0, 0, 0], [0.5, 0, 0.2], [1, 0, 0]],
                    [[1, 0, 0], [0.5, 0.5, 0.3], [0, 1, 0]], [[0, 1, 0], [0, 0.5, 0.1], [0, 0, 0]]]})");
  for (const std::string& file : {degree1, degree2}) {
    const CommandResult r = run_coons("view " + quoted(file) + " --out " + quoted(dir.file("v.html")) + " --force");
    INFO(file << "\n" << r.err);
    REQUIRE(r.status == 0);
    const nlohmann::json optima = nlohmann::json::parse(r.out)["optima"];
    for (const char* name : {"thin_plate", "e3", "dirichlet", "twist"}) {
      CHECK(optima[name] == "flat");
      const CommandResult s = run_coons("search-alpha " + quoted(file) + " --objective " + name);
      REQUIRE(s.status == 0);
      CHECK(nlohmann::json::parse(s.out)["status"] == "flat");
    }
  }
}

TEST_CASE("coons view: a B-spline boundary gets the slider of its non-uniform family, optima as search-alpha's",
          "[cli][view]") {
  // view refused B-spline boundaries ("read by solve, export, batch, search-alpha and study only"),
  // though the contract's `coons view B.json` takes any boundary file
  if (three_js_missing()) return;
  const TempDir dir;
  const std::string wave = quoted(kData + "/boundaries/bspline_wave.json");
  const CommandResult r =
      run_coons("view " + wave + " --out " + quoted(dir.file("wave.html")) + " --alphas 11 --samples 5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  const nlohmann::json solved = nlohmann::json::parse(run_coons("solve " + wave + " --method coons").out);
  CHECK(summary["degree"] == solved["degree"]);
  CHECK(summary["sliders"] == nlohmann::json::array({"alpha"}));
  CHECK(summary["frames"].get<int>() >= 11);
  for (const char* objective : {"thin_plate", "twist"}) {
    INFO(objective);
    const CommandResult searched = run_coons("search-alpha " + wave + " --objective " + objective);
    REQUIRE(searched.status == 0);
    const nlohmann::json s = nlohmann::json::parse(searched.out);
    CHECK(summary["optima"][objective].get<double>() == Approx(s["alpha"].get<double>()).margin(1e-9));
  }
  CHECK(summary["initial_alpha"] == summary["optima"]["thin_plate"]);
  const std::string text = read_text(dir.file("wave.html"));
  CHECK(text.size() == summary["bytes"].get<size_t>());

  // beyond the definite end of its family, and --degree, are bad input; nothing is written
  // (--from at or above the definite end named the contract's interval, not that end: review r63a)
  for (const std::string& options : {std::string(" --to 0.25"), std::string(" --degree 8 8"),
                                     std::string(" --from 0.2"), std::string(" --from 0.25")}) {
    INFO(options);
    const std::string page = dir.file("bad.html");
    std::string command = "view " + wave + " --out " + quoted(page);
    command += options;
    const CommandResult bad = run_coons(command);
    CHECK(bad.status == 2);
    CHECK(bad.out.empty());
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
    CHECK(bad.err.find(options.substr(1, options.find(' ', 1) - 1)) != std::string::npos);
    if (options != " --degree 8 8") CHECK(bad.err.find("definite for alpha in [-0.25, 0.116") != std::string::npos);
    CHECK_FALSE(fs::exists(page));
  }
}

TEST_CASE("coons view: searches whose solves fail are named on one line after the page, exit 3", "[cli][view]") {
  if (three_js_missing()) return;
  // jacobi diverges for alpha < 0: the page was written with "failed_region" optima and exit 0
  const TempDir dir;
  const std::string page = dir.file("j.html");
  const CommandResult r = run_coons("view " + quoted(kData + "/boundaries/dome.json") + " --out " + quoted(page) +
                                    " --alphas 11 --samples 5 --solver jacobi");
  CHECK(r.status == 3);
  CHECK(fs::exists(page));
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  CHECK(summary["optima"]["e3"] == "failed_region");
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::StartsWith("error: " + kData + "/boundaries/dome.json: solver: jacobi search failed for "));
  CHECK_THAT(r.err, Catch::Contains("e3 (failed_region)"));
}

TEST_CASE("coons view: a net without an interior point is flat, as search-alpha says, and --out under a file",
          "[cli][view]") {
  if (three_js_missing()) return;
  const TempDir dir;
  const std::string file =
      dir.write("deg1.json", R"({"name":"deg1","degree":[1,1],"bottom":[[0,0,0],[1,0,0]],"top":[[0,1,0],[1,1,1]],)"
                             R"("left":[[0,0,0],[0,1,0]],"right":[[1,0,0],[1,1,1]]})");
  const CommandResult r = run_coons("view " + quoted(file) + " --out " + quoted(dir.file("p.html")));
  REQUIRE(r.status == 0);
  const nlohmann::json optima = nlohmann::json::parse(r.out)["optima"];
  const CommandResult search = run_coons("search-alpha " + quoted(file) + " --objective thin_plate");
  REQUIRE(search.status == 0);
  CHECK(nlohmann::json::parse(search.out)["status"] == "flat");
  for (const char* name : {"thin_plate", "e3", "dirichlet", "twist"}) CHECK(optima[name] == "flat");
  const std::string regular = dir.write("reg", "");
  const CommandResult under = run_coons("view " + quoted(file) + " --out " + quoted(regular + "/x.html"));
  CHECK(under.status == 2);
  CHECK(under.err == "error: command line: --out: '" + regular + "' exists and is not a folder\n");
}
