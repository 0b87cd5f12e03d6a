// `coons view` through the real binary: the page, its summary and the input edge.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coons/config.h"
#include "support/fixtures.h"

using namespace coons::test;
namespace fs = std::filesystem;

namespace {

const std::string kCoons = COONS_BINARY;
const std::string kData = COONS_DATA_DIR;

std::string q(const std::string& s) { return "'" + s + "'"; }

fs::path fresh_folder(const std::string& name) {
  fs::path dir = fs::temp_directory_path() / ("coons-view-cli-" + name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST_CASE("coons view: one page with the optima, refused without --force when it exists", "[cli][view]") {
  if (!COONS_HAVE_THREE_JS) {
    WARN("skipped: three.js not found at configure time (apt-get install libjs-three)");
    return;
  }
  const fs::path dir = fresh_folder("page");
  const std::string page = (dir / "dome.html").string();
  const std::string command =
      kCoons + " view " + q(kData + "/boundaries/dome.json") + " --out " + q(page) + " --alphas 21 --samples 9";
  const CommandResult r = run_command(command);
  REQUIRE(r.status == 0);
  const nlohmann::json summary = nlohmann::json::parse(r.out);
  CHECK(summary["boundary"] == "dome");
  CHECK(summary["page"] == page);
  CHECK(summary["frames"].get<int>() >= 21);
  CHECK(summary["optima"]["thin_plate"].get<double>() == Approx(summary["initial_alpha"].get<double>()));
  std::ifstream in(page);
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str().size() == summary["bytes"].get<size_t>());
  CHECK(text.str().find("REVISION") != std::string::npos);  // three.js is inlined
  CHECK(text.str().find("window.coonsView") != std::string::npos);

  const CommandResult again = run_command(command);
  CHECK(again.status == 2);
  CHECK(again.out.empty());
  CHECK(again.err == "error: " + page + ": --force: exists; give --force to overwrite it\n");
  fs::remove_all(dir);
}

TEST_CASE("coons view: a missing three.js is bad input naming libjs-three, nothing written", "[cli][view]") {
  const fs::path dir = fresh_folder("nothree");
  const std::string page = (dir / "p.html").string();
  const CommandResult r = run_command(kCoons + " view " + q(kData + "/boundaries/dome.json") + " --out " + q(page) +
                                      " --three-js " + q((dir / "missing.js").string()));
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.find("libjs-three") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(page));
  const CommandResult bad =
      run_command(kCoons + " view " + q(kData + "/boundaries/dome.json") + " --out " + q(page) + " --alphas 1");
  CHECK(bad.status == 2);
  CHECK_FALSE(fs::exists(page));
  fs::remove_all(dir);
}

TEST_CASE("coons study --html: a page per shape in pages/, linked from the report", "[cli][view]") {
  if (!COONS_HAVE_THREE_JS) {
    WARN("skipped: three.js not found at configure time (apt-get install libjs-three)");
    return;
  }
  const fs::path dir = fresh_folder("study");
  const CommandResult r =
      run_command(kCoons + " study " + q(kData + "/boundaries/dome.json") + " " +
                  q(kData + "/triangles/dome_half.json") + " --degrees 3 4 --html --out " + q((dir / "out").string()));
  REQUIRE(r.status == 0);
  std::ifstream in(dir / "out" / "report.md");
  std::stringstream report;
  report << in.rdbuf();
  CHECK(report.str().find("## Pages") != std::string::npos);
  for (const char* page : {"pages/dome.html", "pages/dome_half.html"}) {
    CHECK(report.str().find(std::string("(") + page + ")") != std::string::npos);
    CHECK(fs::file_size(dir / "out" / page) > 100000);
  }
  fs::remove_all(dir);
}
