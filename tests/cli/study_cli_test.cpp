// `coons study` at its input edge and exit status, through the real binary: the base file of
// --family perturbed: is read as every boundary input (corner tolerance, B-spline refusal), a
// backend the triangles cannot take and an option that does nothing in the mode are refused, and
// a failed solve anywhere in the study exits 3 with the report written.
#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_support.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Bad input: one `error:` line, exit 2, nothing on stdout, nothing written.
void check_refused(const CommandResult& r, const std::string& out, const std::string& start) {
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind(start, 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(out));
}

// The dome with its bottom-left corner moved by `gap` in x (the left side keeps the old corner).
std::string dome_with_corner_gap(const TempDir& dir, double gap) {
  json dome = json::parse(read_text(kData + "/boundaries/dome.json"));
  dome["bottom"][0][0] = dome["bottom"][0][0].get<double>() + gap;
  return dir.write("gap.json", dome.dump());
}

}  // namespace

TEST_CASE("coons study --family perturbed:FILE: read as any boundary input, a B-spline file refused", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string wave = kData + "/boundaries/bspline_wave.json";
  check_refused(run_coons("study --family perturbed:" + quoted(wave) + " --count 2 --degrees 8 --out " + quoted(out)),
                out, "error: " + wave + ": knots_u: ");
  // a corner gap of 1e-5 (relative ~3.5e-6 of the dome's diagonal): refused at the default 1e-9,
  // studied with --corner-tolerance 1e-3 as `solve` and `view` read it
  const std::string gap = dome_with_corner_gap(dir, 1e-5);
  const std::string family = "study --family perturbed:" + quoted(gap) + " --count 2 --degrees 3 ";
  check_refused(run_coons(family + "--out " + quoted(out)), out, "error: " + gap + ": bottom-left corner: ");
  const CommandResult loose = run_coons(family + "--corner-tolerance 1e-3 --out " + quoted(out));
  INFO(loose.err);
  CHECK(loose.status == 0);
  CHECK(json::parse(read_text(out + "/results.json"))["count"] == 2);
}

TEST_CASE("coons study --solver: a backend the triangular systems cannot take is refused at the input edge", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string triangle = kData + "/triangles/planar_bulge.json";
  // cholmod is for definite systems only: every triangle row used to say "failed", with exit 0
  const CommandResult r = run_coons("study " + quoted(triangle) + " " + quoted(kData + "/boundaries/pillow.json") +
                                    " --solver cholmod --degrees 3 --out " + quoted(out));
  check_refused(r, out, "error: command line: --solver: cholmod ");
  CHECK(r.err.find(triangle) != std::string::npos);
  // a backend that takes them is not refused
  const CommandResult lu =
      run_coons("study " + quoted(triangle) + " --solver eigen-lu --degrees 3 --out " + quoted(dir.file("lu")));
  INFO(lu.err);
  CHECK(lu.status == 0);
}

TEST_CASE("coons study: a failed solve anywhere in the study exits 3, the report written, one error line", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string file = kData + "/boundaries/oscillating.json";
  // Jacobi diverges at α = −1/4 on the oscillating shape, and μ* rests on failed solves
  const CommandResult r = run_coons("study " + quoted(file) + " --degrees 6 --solver jacobi --out " + quoted(out));
  INFO(r.err);
  CHECK(r.status == 3);
  CHECK(r.err.rfind("error: " + file + ": solver: oscillating: ", 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(fs::exists(out + "/report.md"));
  const json results = json::parse(read_text(out + "/results.json"));
  REQUIRE(results[0]["kind"] == "shape");
  CHECK(results[0]["thin_plate"]["coons"].is_null());
  const json& solver = results[0]["solver"];
  CHECK(solver["status"] == "failure");
  CHECK(solver["message"].get<std::string>().find("the solve at α = −1/4 failed") != std::string::npos);
  // the same shape with a direct backend: every solve succeeds, exit 0
  const CommandResult ok =
      run_coons("study " + quoted(file) + " --degrees 6 --solver eigen-ldlt --out " + quoted(dir.file("ok")));
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.find("error:") == std::string::npos);
  CHECK(json::parse(read_text(dir.file("ok") + "/results.json"))[0]["solver"]["status"] == "success");
}

TEST_CASE("coons study: an option that does nothing in the study's mode is refused, naming it", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string dome = quoted(kData + "/boundaries/dome.json");
  const std::string family = "study --family random-smooth --count 2 --degrees 3";
  const std::string merge = "study --merge " + quoted(dir.file("shards"));
  const std::pair<std::string, std::string> cases[] = {
      {"study " + dome + " --count 3", "--count"},
      {"study " + dome + " --seed 3", "--seed"},
      {"study " + dome + " --amplitude 0.2", "--amplitude"},
      {family + " --html", "--html"},
      {family + " --corner-tolerance 1e-3", "--corner-tolerance"},
      {family + " --amplitude 0.3", "--amplitude"},
      {"study --family perturbed:" + dome + " --count 2 --degrees 3 --html", "--html"},
      {merge + " --degrees 3", "--degrees"},
      {merge + " --html", "--html"},
      {merge + " --count 3", "--count"},
      {merge + " --solver fast", "--solver"},
      {merge + " --corner-tolerance 1e-3", "--corner-tolerance"},
      {merge + " --max-memory 1GB", "--max-memory"},
      // a seed out of [0, 2^64 - 1] was wrapped or clamped to 2^64 - 1, silently
      {family + " --seed -1", "--seed"},
      {family + " --seed 18446744073709551616", "--seed"},
      {family + " --seed 1e23", "--seed"},
  };
  for (const auto& [args, option] : cases) {
    INFO(args);
    check_refused(run_coons(args + " --out " + quoted(out)), out, "error: command line: " + option + ": ");
  }
}

TEST_CASE("coons study --family: a failed search exits 3 with the report written, and so does the merge of its shards",
          "[cli]") {
  TempDir dir;
  // Jacobi diverges for α < 0 on these nets: the α* searches rest on failed solves
  const std::string family = "study --family random-smooth --count 2 --degrees 6 --solver jacobi";
  const std::string start = "error: study: solver: random-smooth: thin_plate at degree 6: ";
  const CommandResult r = run_coons(family + " --out " + quoted(dir.file("whole")));
  INFO(r.err);
  CHECK(r.status == 3);
  CHECK(r.err.rfind(start, 0) == 0);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(fs::exists(dir.file("whole") + "/report.md"));
  const json results = json::parse(read_text(dir.file("whole") + "/results.json"));
  CHECK(results["cells"][0]["failed"].get<int>() > 0);
  // the shard writes records, not the report: exit 0; the merge writes the report: exit 3
  const CommandResult shard = run_coons(family + " --shard 0/1 --out " + quoted(dir.file("shards")));
  INFO(shard.err);
  CHECK(shard.status == 0);
  const CommandResult merged =
      run_coons("study --merge " + quoted(dir.file("shards")) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 3);
  CHECK(merged.err == r.err);
  CHECK(read_text(dir.file("merged") + "/results.json") == read_text(dir.file("whole") + "/results.json"));
  // the same family with a direct backend: every search succeeds, exit 0
  const CommandResult ok = run_coons("study --family random-smooth --count 2 --degrees 6 --solver eigen-ldlt --out " +
                                     quoted(dir.file("ok")));
  INFO(ok.err);
  CHECK(ok.status == 0);
  CHECK(ok.err.find("error:") == std::string::npos);
}
