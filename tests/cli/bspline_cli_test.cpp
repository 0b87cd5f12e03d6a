// `coons solve/export/search-alpha/study` on B-spline boundary files (docs/formats.md "B-spline
// boundaries"): the reports, the files, and bad knot vectors (exit 2, one error line naming the
// file, the field and the index, nothing on standard output).
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "coons/io/boundary_io.h"
#include "support/bspline_singular.h"
#include "support/cli_support.h"
#include "support/fixtures.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// (kCoons and kData are cli_support.h's: a second definition here clashed in the unity build's units.
// The path is a function, not a namespace-scope constant: kData lives in another translation unit and
// may not be initialised yet when this one's constants are, which gave an empty path on CI.)
std::string wave_path() { return kData + "/boundaries/bspline_wave.json"; }

std::string q(const std::string& s) { return "'" + s + "'"; }

json wave() { return json::parse(std::ifstream(wave_path())); }

}  // namespace

TEST_CASE("coons solve: a B-spline boundary gives its knots, degrees, compatibility notes and exact energies",
          "[cli][bspline]") {
  const CommandResult coons = run_command(kCoons + " solve " + q(wave_path()) + " --method coons");
  REQUIRE(coons.status == 0);
  const json c = json::parse(coons.out);
  CHECK(c["bspline"]["degree_spline"] == json({3, 2}));
  CHECK(c["bspline"]["compatibility"].size() == 2);  // left and right received each other's knots
  CHECK(c["degree"] == json({7, 6}));
  CHECK(c["net"].size() == 8);
  CHECK(c["metrics"]["mask_residual"].get<double>() < 1e-12);
  const CommandResult alpha = run_command(kCoons + " solve " + q(wave_path()) + " --alpha -0.25 --solver eigen-lu");
  REQUIRE(alpha.status == 0);
  const json a = json::parse(alpha.out);
  CHECK(a["solver"]["status"] == "success");
  CHECK(a["metrics"]["thin_plate_energy"].get<double>() ==
        Approx(c["metrics"]["thin_plate_energy"].get<double>()).epsilon(1e-9));
  const CommandResult laplace = run_command(kCoons + " solve " + q(wave_path()) + " --alpha 0");
  REQUIRE(laplace.status == 0);
  const json l = json::parse(laplace.out);
  CHECK(l["metrics"]["dirichlet_energy"].get<double>() < c["metrics"]["dirichlet_energy"].get<double>());
  CHECK(l["solver"]["picked_by"] == "auto");
  // gmres takes a bare matrix (ILUT), as coons solvers says: it was refused as a grid-stencil backend
  const CommandResult gmres = run_command(kCoons + " solve " + q(wave_path()) + " --alpha -0.25 --solver gmres");
  INFO(gmres.err);
  REQUIRE(gmres.status == 0);
  const json g = json::parse(gmres.out);
  CHECK(g["solver"]["status"] == "success");
  CHECK(g["metrics"]["thin_plate_energy"].get<double>() ==
        Approx(a["metrics"]["thin_plate_energy"].get<double>()).epsilon(1e-9));
}

TEST_CASE("coons solve: bad knot vectors and options are one error line naming the file, the field and the index",
          "[cli][bspline]") {
  TempDir dir;
  struct Case {
    std::string name, field;
    std::function<void(json&)> edit;
  };
  const std::vector<Case> cases = {
      {"decreasing", "knots_u[5]", [](json& d) { d["knots_u"][5] = 0.05; }},
      {"unclamped", "knots_u[3]", [](json& d) { d["knots_u"][3] = 0.05; }},
      {"too_long", "knots_u", [](json& d) { d["knots_u"].push_back(1); }},
      {"multiplicity", "knots_u[7]",
       [](json& d) {
         for (int k = 4; k < 8; ++k) d["knots_u"][k] = 0.5;
       }},
      {"right_decreasing", "knots_v.right[4]", [](json& d) { d["knots_v"]["right"][4] = 0.3; }},
      {"not_number", "knots_v.left[2]", [](json& d) { d["knots_v"]["left"][2] = "zero"; }},
      {"no_degree", "degree_spline", [](json& d) { d.erase("degree_spline"); }},
      {"bad_degree", "degree_spline[1]", [](json& d) { d["degree_spline"][1] = 0; }},
      {"side", "knots_v.middle", [](json& d) { d["knots_v"]["middle"] = json::array(); }},
      // every knot times 1e-309: valid by every other rule, but subnormal (the solve overflowed, exit 3)
      {"subnormal_span", "knots_u",
       [](json& d) {
         for (json& k : d["knots_u"]) k = k.get<double>() * 1e-309;
       }},
  };
  for (const Case& c : cases) {
    json doc = wave();
    c.edit(doc);
    const std::string path = dir.write(c.name + ".json", doc.dump());
    const CommandResult r = run_command(kCoons + " solve " + q(path));
    INFO(c.name << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: " + path + ": " + c.field + ": ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
  for (const auto& [options, field] :
       {std::pair{"--mu 3", "--mu"}, std::pair{"--mask c1-coons", "--mask"},
        std::pair{"--method hermite-coons", "--method"}, std::pair{"--solver dst", "--solver"}}) {
    const CommandResult r = run_command(kCoons + " solve " + q(wave_path()) + " " + options);
    INFO(options << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(std::string("command line: ") + field + ": ") != std::string::npos);
  }
  // a grid-stencil backend: one line, worded alike by every command that reads a B-spline boundary
  // (view and solve had said it three ways), nothing written
  TempDir out;
  std::string first;
  for (const std::string& command :
       {std::string("solve"), std::string("search-alpha --objective thin_plate"),
        "export --obj --out " + q(out.file("ex")), "view --out " + q(out.file("page.html"))}) {
    std::string line = kCoons;
    line.append(" ").append(command).append(" ").append(q(wave_path())).append(" --solver mg");
    const CommandResult r = run_command(line);
    INFO(command << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.rfind("error: command line: --solver: mg works from the grid stencil only; the non-uniform mask system "
                      "of a B-spline boundary is an assembled matrix",
                      0) == 0);
    if (first.empty()) first = r.err;
    CHECK(r.err == first);
  }
  CHECK_FALSE(fs::exists(out.file("ex")));
  CHECK_FALSE(fs::exists(out.file("page.html")));
  const CommandResult sweep = run_command(kCoons + " sweep " + q(wave_path()));
  CHECK(sweep.status == 2);
  CHECK(sweep.err.find("knots_u: ") != std::string::npos);
}

TEST_CASE("coons export: a B-spline boundary as sampled OBJ, PLY and VTS and its system as Matrix Market",
          "[cli][bspline]") {
  TempDir out;
  const CommandResult r =
      run_command(kCoons + " export " + q(wave_path()) + " --alpha -0.1 --samples 9 --obj --ply --vts --mtx --out " +
                  q(out.path.string()));
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["written"].size() == 6);
  for (const char* name : {"bspline_wave.surface.obj", "bspline_wave.net.obj", "bspline_wave.surface.ply",
                           "bspline_wave.surface.vts", "bspline_wave.A.mtx", "bspline_wave.B.mtx"})
    CHECK(fs::exists(out.path / name));
  std::ifstream obj(out.path / "bspline_wave.surface.obj");
  int vertices = 0;
  for (std::string line; std::getline(obj, line);) vertices += line.rfind("v ", 0) == 0 ? 1 : 0;
  CHECK(vertices == 81);
}

TEST_CASE("coons export: a B-spline system that is singular at the alpha asked for is refused, not written",
          "[cli][bspline]") {
  // The non-uniform system is solved for --mtx too (it was only for the sampled and CAD outputs),
  // so --mtx alone at a singular alpha fails as the other outputs do: exit 3, nothing written.
  const coons::BoundaryFile file = coons::read_boundary_file(wave_path());
  REQUIRE(file.bspline);
  const double star = bspline_singular_alpha(file.bspline->compatible);
  REQUIRE(star < 0.25);
  TempDir out;
  const std::string alpha = fmt::format("{}", star);  // shortest text that reads back as star
  const CommandResult r =
      run_command(kCoons + " export " + q(wave_path()) + " --alpha " + alpha + " --mtx --out " + q(out.path.string()));
  INFO("alpha " << alpha << ": " << r.err);
  CHECK(r.status == 3);
  CHECK_THAT(r.err, Catch::Contains("singular"));
  CHECK(fs::is_empty(out.path));
  // at a regular alpha the same command writes the system
  const CommandResult regular =
      run_command(kCoons + " export " + q(wave_path()) + " --alpha -0.1 --mtx --out " + q(out.path.string()));
  CHECK(regular.status == 0);
  CHECK(fs::exists(out.path / "bspline_wave.A.mtx"));
}

TEST_CASE("coons search-alpha and study: a B-spline boundary is searched over the non-uniform family",
          "[cli][bspline]") {
  const CommandResult r = run_command(kCoons + " search-alpha " + q(wave_path()) + " --objective thin_plate");
  REQUIRE(r.status == 0);
  const json s = json::parse(r.out);
  CHECK(s["status"] == "success");
  CHECK(s["alpha"].get<double>() > -0.25);
  CHECK(s["alpha"].get<double>() < 0.25);
  CHECK(s["beta"].is_null());
  CHECK(s["bspline"]["degree_spline"] == json({3, 2}));
  // the default bounds: [-1/4, U], U the end of the definite range (a singular alpha lies above it)
  const double upper = s["bounds"][1].get<double>();
  CHECK(s["bounds"][0] == -0.25);
  CHECK(upper > 0.1);
  CHECK(upper < 0.25);
  // the Dirichlet energy falls across [0, U]: its minimum against U is said to be the singular
  // alpha's (with the old bounds [-1/4, 0] it read alpha = 0 "at a bound")
  const CommandResult dirichlet = run_command(kCoons + " search-alpha " + q(wave_path()) + " --objective dirichlet");
  REQUIRE(dirichlet.status == 0);
  const json d = json::parse(dirichlet.out);
  CHECK(d["alpha"].get<double>() > 0.1);
  CHECK_THAT(d["message"].get<std::string>(), Catch::Contains("so this minimum is made by it"));
  CHECK(json::parse(run_command(kCoons + " search-alpha " + q(wave_path()) + " --objective e3").out)
            .value("message", "") == "");
  // beyond U: bad input naming U
  const CommandResult beyond = run_command(kCoons + " search-alpha " + q(wave_path()) + " --objective e3 --upper " +
                                           fmt::format("{}", upper + 0.01));
  CHECK(beyond.status == 2);
  CHECK_THAT(beyond.err, Catch::Contains(fmt::format("definite for alpha in [-0.25, {}] only", upper)));
  const CommandResult target =
      run_command(kCoons + " search-alpha " + q(wave_path()) + " --objective target --target coons");
  CHECK(target.status == 2);
  CHECK(target.out.empty());
  TempDir out;
  const CommandResult study =
      run_command(kCoons + " study " + q(wave_path()) + " --degrees 3 --out " + q(out.path.string()));
  REQUIRE(study.status == 0);
  CHECK(study.out.find("## B-spline boundaries") != std::string::npos);
  CHECK(study.out.find("| bspline_wave |") != std::string::npos);
  const json rows = json::parse(std::ifstream(out.path / "bspline.json"));
  REQUIRE(rows.size() == 1);
  CHECK(rows[0]["best_alpha"]["thin_plate"]["status"] == "success");
}

TEST_CASE("coons export: a B-spline boundary without an interior point writes no system, --mtx is refused",
          "[cli][bspline]") {
  // its "0 0 0" Matrix Market files were written (exit 0), as a Bézier 2 by 2 net's are not
  TempDir dir;
  const std::string file = dir.write(
      "bsp11.json", R"({"degree_spline":[1,1],"knots_u":[0,0,1,1],"knots_v":[0,0,1,1],"bottom":[[0,0,0],[1,0,0]],)"
                    R"("top":[[0,1,0],[1,1,1]],"left":[[0,0,0],[0,1,0]],"right":[[1,0,0],[1,1,1]]})");
  const std::string out = dir.file("e");
  const CommandResult asked = run_command(kCoons + " export " + q(file) + " --out " + q(out) + " --mtx");
  CHECK(asked.status == 2);
  CHECK(asked.err ==
        "error: " + file + ": --mtx: the 2 by 2 net has no point to solve for: there is no system to write\n");
  CHECK_FALSE(fs::exists(out));
  const CommandResult defaults = run_command(kCoons + " export " + q(file) + " --out " + q(out));
  INFO(defaults.err);
  CHECK(defaults.status == 0);
  CHECK(fs::exists(out + "/bsp11.net.obj"));
  CHECK_FALSE(fs::exists(out + "/bsp11.A.mtx"));
  CHECK_FALSE(fs::exists(out + "/bsp11.B.mtx"));
}

TEST_CASE(
    "coons solve: a Cholesky-type backend on a B-spline boundary takes alpha up to the end U of its definite range",
    "[cli][bspline]") {
  // bspline_wave's system stops being definite at U = 0.1164 (docs/formats.md): 0.2 was accepted by
  // the Bézier family's range [-0.25, 0.25] and failed with exit 3, and 0.3 was refused naming that range
  for (const std::string alpha : {"0.2", "0.3", "-0.3"}) {
    std::string command = kCoons + " solve " + q(wave_path()) + " --solver eigen-llt --alpha ";
    command += alpha;
    const CommandResult r = run_command(command);
    INFO(alpha << ": " << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.rfind("error: command line: --alpha: " + alpha + " is outside [-0.25, 0.116", 0) == 0);
    CHECK(r.err.find("where the non-uniform mask system of " + wave_path() + " is positive definite") !=
          std::string::npos);
  }
  const CommandResult inside = run_command(kCoons + " solve " + q(wave_path()) + " --solver eigen-llt --alpha 0.1");
  INFO(inside.err);
  CHECK(inside.status == 0);
  CHECK(json::parse(inside.out)["solver"]["status"] == "success");
}
