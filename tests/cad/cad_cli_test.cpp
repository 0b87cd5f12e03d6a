// `coons export --step/--iges` and `coons import-step` end to end (the built binary).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coons/cad/cad_surface.h"
#include "coons/io/boundary_io.h"
#include "coons/net/coons_net.h"
#include "support/fixtures.h"

using namespace coons;
using coons::test::CommandResult;
using coons::test::run_command;

namespace {
const std::string kCoons = COONS_BINARY;
const std::string kData = std::string(COONS_DATA_DIR) + "/";
}  // namespace

TEST_CASE("coons export --step --iges: the written surface is the solved net, exactly", "[cad][cli]") {
  const test::TempDir dir;
  const std::string step = dir.file("pillow.step"), iges = dir.file("pillow.iges");
  const CommandResult r = run_command(kCoons + " export " + kData + "boundaries/pillow.json --method coons --step " +
                                      step + " --iges " + iges);
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  const auto report = nlohmann::json::parse(r.out);
  CHECK(report["written"] == nlohmann::json::array({step, iges}));
  const ControlNet expected = discrete_coons_net(read_boundary_file(kData + "boundaries/pillow.json").boundary);
  for (const auto& back : {cad::read_step_surfaces(step), cad::read_iges_surfaces(iges)}) {
    REQUIRE(back.size() == 1);
    CHECK(back[0].net.points == expected.points);
    CHECK(back[0].knots_u == cad::bezier_as_bspline(expected).knots_u);
  }
  // import-step of that file gives back the boundary file's sides
  const std::string out = dir.file("back.json");
  const CommandResult imported = run_command(kCoons + " import-step " + step + " --face 0 --out " + out);
  INFO(imported.err);
  REQUIRE(imported.status == 0);
  const Boundary a = read_boundary_file(out).boundary;
  const Boundary b = read_boundary_file(kData + "boundaries/pillow.json").boundary;
  CHECK(a.bottom == b.bottom);
  CHECK(a.top == b.top);
  CHECK(a.left == b.left);
  CHECK(a.right == b.right);
  CHECK(nlohmann::json::parse(imported.out)["import"]["max_gap"] == 0.0);
}

TEST_CASE("coons import-step: the bundled B-spline patch gives a B-spline boundary file", "[cad][cli]") {
  const test::TempDir dir;
  const std::string out = dir.file("patch.json");
  const CommandResult r =
      run_command(kCoons + " import-step " + kData + "cad/bspline_patch.step --face 0 --out " + out);
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::ifstream in(out);
  const auto doc = nlohmann::json::parse(in);
  CHECK(doc["degree_spline"] == nlohmann::json::array({3, 2}));
  CHECK(doc["knots_u"] == nlohmann::json::array({0, 0, 0, 0, 0.3, 0.45, 1, 1, 1, 1}));
  CHECK(doc["knots_v"] == nlohmann::json::array({0, 0, 0, 0.6, 1, 1, 1}));
  CHECK(doc["import"]["form"] == "bspline");
  // export --step of that file (--method coons: the Greville net) reads back with the same knots
  const std::string step = dir.file("again.step");
  const CommandResult e = run_command(kCoons + " export " + out + " --method coons --step " + step);
  INFO(e.err);
  REQUIRE(e.status == 0);
  const auto again = cad::read_step_surfaces(step);
  const auto original = cad::read_step_surfaces(kData + "cad/bspline_patch.step");
  REQUIRE(again.size() == 1);
  CHECK(again[0].knots_u == original[0].knots_u);
  CHECK(again[0].knots_v == original[0].knots_v);
  CHECK(again[0].net.points == original[0].net.points);
}

TEST_CASE("coons import-step, export --step: bad input exits 2 with one line, nothing written", "[cad][cli]") {
  const test::TempDir dir;
  const std::string out = dir.file("x.json");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"import-step " + dir.file("none.step") + " --face 0 --out " + out, "none.step: (document): cannot be read"},
      {"import-step " + kData + "cad/bspline_patch.step --face 4 --out " + out,
       "bspline_patch.step: face 4: out of range"},
      {"import-step " + kData + "cad/four_edges.step --edges 0,1,2,9 --out " + out,
       "four_edges.step: edge 9: out of range"},
      // a folder that does not exist: the option and the folder (it named the file, "cannot create")
      {"export " + kData + "boundaries/pillow.json --method alpha --step " + dir.file("cad/x.step"),
       "command line: --step: the folder '" + dir.file("cad") + "' does not exist"},
  };
  // four_edges.step edited: a control point that is not there (OpenCASCADE's transfer dereferenced
  // it: a segfault), and poles that are not a number or beyond |x| <= 1e60 (written out as null)
  const test::TempDir edited;
  std::ifstream in(kData + "cad/four_edges.step");
  const std::string step((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string pole = "#49 = CARTESIAN_POINT('',(3.2500000000000000E+00,";
  REQUIRE(step.find("(#48,#49,#50,#51)") != std::string::npos);
  REQUIRE(step.find(pole) != std::string::npos);
  const auto write_edited = [&](const std::string& name, const std::string& from, const std::string& to) {
    std::string text = step;
    text.replace(text.find(from), from.size(), to);
    std::ofstream(edited.file(name)) << text;
    return edited.file(name);
  };
  std::vector<Case> more = cases;
  more.push_back({"import-step " + write_edited("dangling.step", "(#48,#49,#50,#51)", "(#48,#49,#50,#999)") +
                      " --edges 0,1,2,3 --out " + out,
                  "dangling.step: entity #47: OpenCASCADE cannot load it"});
  // multiplicities (3, 2, 3) for 4 poles of degree 2: OpenCASCADE's transfer leaves the curve out,
  // and the edges after it were numbered one lower ("edge 3: out of range: the file has 3 edge(s)")
  REQUIRE(step.find(",.F.,(3,1,3),") != std::string::npos);
  more.push_back({"import-step " + write_edited("mismatch.step", ",.F.,(3,1,3),", ",.F.,(3,2,3),") +
                      " --edges 0,1,2,3 --out " + out,
                  "mismatch.step: entity #46: OpenCASCADE cannot translate it (left out of the shape"});
  more.push_back({"import-step " + write_edited("nan.step", pole, "#49 = CARTESIAN_POINT('',(NAN,") +
                      " --edges 0,1,2,3 --out " + out,
                  "nan.step: entity #49: OpenCASCADE cannot load it"});
  for (const char* value : {"1.0E+400", "3.25E+70"})
    more.push_back({"import-step " +
                        write_edited(std::string("pole") + value + ".step", pole,
                                     "#49 = CARTESIAN_POINT('',(" + std::string(value) + ",") +
                        " --edges 0,1,2,3 --out " + out,
                    "edge 0: control point 1: coordinate 0 is "});
  for (const auto& c : more) {
    const CommandResult r = run_command(kCoons + " " + c.args);
    INFO(c.args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(c.message) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(out));
  }
  CHECK(std::filesystem::is_empty(dir.path));
}

TEST_CASE("coons export --step: a B-spline boundary's alpha net is written with its knots, as solve gives it",
          "[cad][cli]") {
  const test::TempDir dir;
  const std::string patch = dir.file("patch.json"), step = dir.file("p.step");
  REQUIRE(run_command(kCoons + " import-step " + kData + "cad/bspline_patch.step --face 0 --out " + patch).status == 0);
  const std::string options = " --method alpha --alpha -0.1 --solver eigen-lu";
  const CommandResult e = run_command(kCoons + " export " + patch + options + " --step " + step);
  INFO(e.err);
  REQUIRE(e.status == 0);
  CHECK(nlohmann::json::parse(e.out)["written"] == nlohmann::json::array({step}));
  const CommandResult solved = run_command(kCoons + " solve " + patch + options);
  REQUIRE(solved.status == 0);
  const nlohmann::json net = nlohmann::json::parse(solved.out)["net"];
  const auto back = cad::read_step_surfaces(step);
  REQUIRE(back.size() == 1);
  const ControlNet& written = back[0].net;
  REQUIRE(net.size() == static_cast<std::size_t>(written.m + 1));
  double differs_from_greville = 0;
  const auto greville = cad::read_step_surfaces(kData + "cad/bspline_patch.step");
  for (int i = 0; i <= written.m; ++i)
    for (int j = 0; j <= written.n; ++j)
      for (int c = 0; c < 3; ++c) {
        CHECK(written.at(i, j)(c) == net[i][j][c].get<double>());
        differs_from_greville =
            std::max(differs_from_greville, std::abs(written.at(i, j)(c) - greville[0].net.at(i, j)(c)));
      }
  CHECK(differs_from_greville > 1e-6);  // alpha = -0.1 is not the Coons net the sample holds
  CHECK(back[0].knots_u == greville[0].knots_u);
  CHECK(back[0].knots_v == greville[0].knots_v);
}

TEST_CASE("coons export --step: a net above OpenCASCADE's degree limit is refused with the degree and the limit",
          "[cad][cli]") {
  // "OpenCASCADE refuses the surface: Geom_BSplineSurface: invalid degree" gave neither
  const coons::test::TempDir dir;
  const std::string boundary = dir.file("d26.json"), step = dir.file("d26.step");
  const CommandResult refit =
      run_command(kCoons + " refit '" + kData + "boundaries/dome.json' --degree 26 26 --out '" + boundary + "'");
  REQUIRE(refit.status == 0);
  const CommandResult r = run_command(kCoons + " export '" + boundary + "' --step '" + step + "'");
  CHECK(r.status == 2);
  CHECK(r.err == "error: " + step +
                     ": --step: the surface's degree (26, 26) exceeds OpenCASCADE's B-spline limit 25, so it cannot be "
                     "written as STEP or IGES\n");
  CHECK_FALSE(std::filesystem::exists(step));
}
