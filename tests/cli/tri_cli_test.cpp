// The triangular side of the command line (docs/formats.md, "Triangular boundaries"), through the binary.
#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coons/io/tri_boundary_io.h"
#include "coons/tri/tri_solve.h"
#include "solvers/registry.h"
#include "support/cli_support.h"
#include "tri/tri_fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kTriangles = std::string(COONS_DATA_DIR) + "/triangles/";

int count_lines_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  int count = 0;
  for (std::string line; std::getline(in, line);) count += line.rfind(prefix, 0) == 0 ? 1 : 0;
  return count;
}

}  // namespace

TEST_CASE("coons solve: a triangular file gives the triangle report, net in the contract's row order", "[cli][tri]") {
  const std::string file = kTriangles + "sphere_octant.json";
  const CommandResult r = run_coons("solve '" + file + "' --alpha -0.1 --solver eigen-lu");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["type"] == "triangle");
  CHECK(report["degree"] == 6);
  CHECK(report["method"] == "alpha");
  CHECK(report["alpha"] == -0.1);
  CHECK(report["a"].get<double>() == Approx((1 + 0.3) / 6));
  CHECK(report["solver"]["name"] == "eigen-lu");
  CHECK(report["solver"]["status"] == "success");
  for (const char* key :
       {"dirichlet_energy", "thin_plate_energy", "twist_energy", "e3_energy", "discrete_dirichlet_energy",
        "discrete_thin_plate_energy", "discrete_twist_energy", "mask_residual"})
    CHECK(report["metrics"][key].is_number());
  // the net equals the library's solve, row by row: net[k][j] = b[n-k-j][j][k]
  tri::TriSolveOptions options;
  options.mask.c = -0.1;
  options.solver = solvers::find_solver("eigen-lu");
  const tri::TriNet expected = tri::solve_tri_net(read_tri_boundary_file(file), options).net;
  CHECK(report["net"] == tri_net_to_json(expected));
  CHECK(report["metrics"]["mask_residual"].get<double>() < 1e-14);
  // one point [x, y, z] per line, as in the rectangle's report (each coordinate had a line)
  int point_lines = 0;
  std::istringstream text(r.out);
  for (std::string line; std::getline(text, line);) {
    const auto first = line.find_first_not_of(' ');
    if (first != std::string::npos && line.size() > first + 1 && line[first] == '[' && line[first + 1] != '\n' &&
        line.find(']') != std::string::npos && std::count(line.begin(), line.end(), ',') >= 2)
      ++point_lines;
  }
  CHECK(point_lines == 28);  // (n + 1)(n + 2)/2 points of degree 6
  CHECK(count_lines_starting(r.out, "        1.0") == 0);
}

TEST_CASE("coons solve: --solver auto on a triangle picks an LU backend, c defaults to -1/6", "[cli][tri]") {
  const CommandResult r = run_coons("solve '" + kTriangles + "monkey_saddle.json'");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["alpha"].get<double>() == -1.0 / 6);
  CHECK(report["solver"]["picked_by"] == "auto");
  CHECK((report["solver"]["name"] == "umfpack" || report["solver"]["name"] == "eigen-lu"));
}

TEST_CASE("coons solve: a triangle's c that a named Cholesky or CG backend does not accept is bad input",
          "[cli][tri]") {
  // docs/formats.md, Errors: "an α outside what the chosen solver accepts" is bad input (exit 2,
  // one line, nothing on standard output), as a rectangle's --alpha 0.4 with eigen-llt is. These
  // backends accept c = 0 only (the system is symmetric there alone), at the default c = -1/6 too.
  const std::string file = kTriangles + "dome_half.json";
  for (const std::string& args : {std::string(" --alpha -0.1 --solver eigen-ldlt"), std::string(" --solver eigen-llt"),
                                  std::string(" --alpha 0.2 --solver cg")}) {
    const CommandResult r = run_coons("solve " + quoted(file) + args);
    INFO(args << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(count_lines_starting(r.err, "error: command line: --alpha: c = ") == 1);
    CHECK_THAT(r.err, Catch::Contains("the triangular mask system is not symmetric for c != 0"));
  }
  // a backend that never applies to a triangle (grid stencils only) reports not_applicable, exit 3
  if (solvers::find_solver("fast")) {
    const CommandResult r = run_coons("solve '" + file + "' --solver fast");
    REQUIRE(r.status == 3);
    const json report = json::parse(r.out);
    CHECK(report["solver"]["status"] == "not_applicable");
    CHECK(report["net"].is_null());
    CHECK(report["metrics"].is_null());
    CHECK(count_lines_starting(r.err, "error: " + file + ": solver: fast not_applicable") == 1);
  }
  // c = 0 is symmetric positive definite: there it applies and agrees with LU
  const CommandResult zero = run_coons("solve '" + file + "' --alpha 0 --solver eigen-ldlt");
  const CommandResult zero_lu = run_coons("solve '" + file + "' --alpha 0 --solver eigen-lu");
  REQUIRE(zero.status == 0);
  REQUIRE(zero_lu.status == 0);
  const json a = json::parse(zero.out)["net"], b = json::parse(zero_lu.out)["net"];
  for (size_t k = 0; k < a.size(); ++k)
    for (size_t j = 0; j < a[k].size(); ++j)
      for (int c = 0; c < 3; ++c) CHECK(a[k][j][c].get<double>() == Approx(b[k][j][c].get<double>()).margin(1e-12));
}

TEST_CASE("coons solve: bad triangular inputs exit 2 naming the side and point", "[cli][tri]") {
  TempDir dir;
  json doc = tri_boundary_to_json(tri::boundary_of(tri_test::random_tri_net(4, 5), "bad"));
  json gap = doc;
  gap["sides"][1][0][0] = gap["sides"][1][0][0].get<double>() + 0.1;
  json short_side = doc;
  short_side["sides"][2].erase(3);
  json bad_point = doc;
  bad_point["sides"][0][2] = json::array({1, 2});
  const std::pair<json, std::string> cases[] = {{gap, "sides[1][0]: corner (0,4,0) differs from sides[0][4] by 0.1"},
                                                {short_side, "sides[2]: has 4 points, sides[0] has 5"},
                                                {bad_point, "sides[0][2]: a point must have 3 coordinates, not 2"}};
  int k = 0;
  for (const auto& [bad, expected] : cases) {
    const std::string file = dir.write("bad" + std::to_string(k++) + ".json", bad.dump());
    const std::vector<std::string> commands = {"solve", "export --out '" + dir.file("out") + "'",
                                               "search-alpha --objective thin_plate",
                                               "sweep --out '" + dir.file("out") + "'"};
    for (const std::string& command : commands) {
      const std::string verb = command.substr(0, command.find(' '));
      const CommandResult r = run_command(fmt::format("{} {} '{}'{}", kCoons, verb, file, command.substr(verb.size())));
      INFO(command << ": " << r.err);
      CHECK(r.status == 2);
      CHECK(r.out.empty());
      CHECK(r.err.rfind(fmt::format("error: {}: {}", file, expected), 0) == 0);
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    }
  }
  CHECK_FALSE(fs::exists(dir.file("out")));
  // options that mean nothing for a triangle
  const std::string file = kTriangles + "sphere_octant.json";
  for (const std::string option : {"--mu 2", "--method coons", "--allow-indefinite"}) {
    const CommandResult r = run_command(fmt::format("{} solve '{}' {}", kCoons, file, option));
    INFO(option);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(count_lines_starting(r.err, "error: command line: --") == 1);
  }
}

TEST_CASE("coons export: a triangle as OBJ (surface and net), PLY and VTU", "[cli][tri]") {
  TempDir dir;
  const std::string file = kTriangles + "sphere_octant.json";
  const CommandResult r = run_coons("export '" + file + "' --samples 5 --out '" + dir.file("x") + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["written"].size() == 6);
  const std::string prefix = dir.file("x/sphere_octant");
  const std::string surface = read_text(prefix + ".surface.obj");
  CHECK(count_lines_starting(surface, "v ") == 15);
  CHECK(count_lines_starting(surface, "vn ") == 15);
  CHECK(count_lines_starting(surface, "f ") == 16);
  const std::string net = read_text(prefix + ".net.obj");
  CHECK(count_lines_starting(net, "v ") == 28);
  CHECK(count_lines_starting(net, "f ") == 36);
  const std::string ply = read_text(prefix + ".surface.ply");
  CHECK(ply.find("element vertex 15\n") != std::string::npos);
  CHECK(ply.find("element face 16\n") != std::string::npos);
  CHECK(count_lines_starting(ply, "3 ") == 16);
  const std::string vtu = read_text(prefix + ".surface.vtu");
  CHECK(vtu.find("<Piece NumberOfPoints=\"15\" NumberOfCells=\"16\">") != std::string::npos);
  CHECK(vtu.find("Name=\"types\"") != std::string::npos);
  CHECK(fs::exists(prefix + ".A.mtx"));
  // every surface vertex of the octant lies near the unit sphere (the c = -1/6 net is not on it:
  // 8% inside at the centre)
  std::istringstream in(surface);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("v ", 0) == 0) {
      std::istringstream p(line.substr(2));
      double x = 0, y = 0, z = 0;
      p >> x >> y >> z;
      const double radius = std::sqrt(x * x + y * y + z * z);
      CHECK(radius > 0.9);
      CHECK(radius < 1 + 1e-5);
    }
  // without --force the files are not replaced
  const CommandResult again = run_coons("export '" + file + "' --vtu --out '" + dir.file("x") + "'");
  CHECK(again.status == 2);
  CHECK(count_lines_starting(again.err, "error: ") == 1);
  // --ply and --vtu are for triangles
  const CommandResult rect = run_coons("export '" + std::string(COONS_DATA_DIR) +
                                       "/boundaries/dome.json' --vtu --out '" + dir.file("y") + "'");
  CHECK(rect.status == 2);
  CHECK_FALSE(fs::exists(dir.file("y")));
}

TEST_CASE("coons search-alpha: the best c of a triangle, with bounds that avoid the singular member", "[cli][tri]") {
  const std::string file = kTriangles + "sphere_octant.json";
  const CommandResult r = run_coons("search-alpha '" + file + "' --objective target");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["type"] == "triangle");
  CHECK(report["status"] == "success");
  CHECK(report["flat"] == false);
  CHECK(report["at_bound"] == false);
  CHECK(report.at("mu").is_null());  // a field of every search report; the triangular family has no μ
  const double c = report["alpha"].get<double>();
  CHECK(c > report["bounds"][0].get<double>());
  CHECK(c < report["bounds"][1].get<double>());
  CHECK(report["bounds"][0].get<double>() == Approx(-1.0 / 6 - 1.0 / 12));
  // the target value is the mean squared distance to the sphere: small for the octant
  CHECK(report["value"].get<double>() < 1e-4);
  const CommandResult e3 = run_coons("search-alpha '" + file + "' --objective e3");
  CHECK(e3.status == 0);
  CHECK(json::parse(e3.out)["objective"] == "e3");
  const CommandResult rejected = run_coons("search-alpha '" + file + "' --objective e4");
  CHECK(rejected.status == 2);
  CHECK(count_lines_starting(rejected.err, "error: command line: --objective: unknown objective 'e4'") == 1);
}

TEST_CASE("coons sweep: a triangle gives NAME.sweep-c.jsonl, one line per c", "[cli][tri]") {
  TempDir dir;
  const std::string file = kTriangles + "dome_half.json";
  const CommandResult r = run_coons("sweep '" + file + "' --count 5 --out '" + dir.path.string() + "'");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json summary = json::parse(r.out);
  CHECK(summary["parameter"] == "c");
  std::istringstream lines(read_text(dir.file("dome_half.sweep-c.jsonl")));
  int count = 0;
  for (std::string line; std::getline(lines, line); ++count) {
    const json row = json::parse(line);
    CHECK(row["status"] == "success");
    CHECK(row["metrics"]["thin_plate_energy"].is_number());
    CHECK(row["rms_target"].get<double>() > 0);
    CHECK(row["rms_target"].get<double>() < 0.2);
  }
  CHECK(count == 5);
}

TEST_CASE("coons sweep: on a triangle --threads and values of c beyond 1e60 are refused as solve refuses them",
          "[cli][tri]") {
  // --threads was ignored with exit 0, and c = 1e200 gave "singular" lines for regular systems
  // (the weights overflow), c = 1.7e308 a null c
  TempDir dir;
  const std::string file = kTriangles + "dome_half.json";
  const std::string threads = "error: command line: --threads: does not apply to a triangular boundary";
  const std::string range = "error: command line: --from/--to: values must lie in [-1e+60, 1e+60]";
  for (const auto& [options, reason] : {std::pair{"--threads 2", threads}, std::pair{"--from 1e200 --to 1e300", range},
                                        std::pair{"--from -1.7e308 --to 1.7e308", range}}) {
    const CommandResult r =
        run_coons("sweep '" + file + "' --count 2 " + options + " --out '" + dir.path.string() + "'");
    INFO(options << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::StartsWith(reason));
  }
  CHECK_FALSE(fs::exists(dir.file("dome_half.sweep-c.jsonl")));
  CHECK(run_coons("sweep '" + file + "' --count 2 --from -1e60 --to 1e60 --out '" + dir.path.string() + "'").status !=
        2);
}

TEST_CASE("coons study: a triangular file among the inputs gets its rows in results.json and report.md", "[cli][tri]") {
  const TempDir dir;
  const fs::path out = dir.path / "study";
  const CommandResult r =
      run_coons("study " + quoted(kTriangles + "sphere_octant.json") + " --degrees 6 8 --out " + quoted(out.string()));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json results = json::parse(read_text((out / "results.json").string()));
  const auto it = std::find_if(results.begin(), results.end(), [](const json& e) { return e["kind"] == "triangle"; });
  REQUIRE(it != results.end());
  CHECK((*it)["boundary"] == "sphere_octant");
  const json& target = (*it)["objectives"]["target"];
  REQUIRE(target.size() == 2);  // its own degree 6, then 8
  CHECK(target[1]["degree"] == 8);
  CHECK(target[0]["flat"] == false);
  CHECK(target[0]["c"].get<double>() < 0);
  const std::string report = read_text((out / "report.md").string());
  CHECK(report.find("## 6. Triangular boundaries") != std::string::npos);
  CHECK(report.find("### sphere_octant (triangle, degree 6)") != std::string::npos);
}

TEST_CASE("coons solve and export: the singular member c*_n of a triangle is refused by every backend", "[cli][tri]") {
  // A flat degree-4 triangle: its right-hand side is consistent at c*_4 = -2/3, so gmres used to
  // return one of many nets as a success (a flat triangle must stay flat) while LU said singular.
  TempDir dir;
  const std::string file = dir.write("tflat4.json",
                                     R"json({"name": "tflat4", "type": "triangle", "degree": 4, "sides": [
        [[1, 0, 0], [0.75, 0.25, 0], [0.5, 0.5, 0], [0.25, 0.75, 0], [0, 1, 0]],
        [[0, 1, 0], [0, 0.75, 0], [0, 0.5, 0], [0, 0.25, 0], [0, 0, 0]],
        [[0, 0, 0], [0.25, 0, 0], [0.5, 0, 0], [0.75, 0, 0], [1, 0, 0]]]})json");
  for (const std::string solver : {"gmres", "bicgstab", "eigen-lu"}) {
    for (const std::string& command : {std::string("solve"), "export --out " + quoted(dir.file("e-" + solver))}) {
      const CommandResult r =
          run_coons(fmt::format("{} {} --alpha -0.6666666666666666 --solver {}", command, quoted(file), solver));
      INFO(command << " " << solver << ": " << r.err);
      CHECK(r.status == 2);
      CHECK(r.out.empty());
      CHECK(count_lines_starting(r.err, "error: " + file + ": --alpha: the mask system is singular: c = ") == 1);
    }
  }
  // a regular member nearby solves, and the flat triangle stays flat
  const CommandResult near = run_coons("solve " + quoted(file) + " --alpha -0.6 --solver gmres");
  REQUIRE(near.status == 0);
  const json report = json::parse(near.out);  // named: a range-for over a temporary's member dangles
  for (const auto& row : report.at("net"))
    for (const auto& p : row) CHECK(std::abs(p[2].get<double>()) < 1e-12);
}
