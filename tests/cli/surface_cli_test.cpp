// `coons surface` through the real binary: the docs/formats.md report, the files it writes, and the
// error contract for bad descriptions (exit 2, one `error:` line naming the field, nothing written).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coons/io/boundary_io.h"
#include "coons/net/coons_net.h"
#include "support/cli_support.h"
#include "support/surface_fixtures.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// Runs `coons surface SPEC` with every output option; checks the error contract.
void check_rejected(const std::string& spec_text, const std::string& field, const std::string& reason_part) {
  TempDir dir;
  const std::string spec = dir.write("bad.json", spec_text);
  const std::string outputs[] = {dir.file("s.obj"), dir.file("s.ply"), dir.file("s.vts"), dir.file("s.png"),
                                 dir.file("net.json")};
  const CommandResult r =
      run_coons("surface " + quoted(spec) + " --sample 5 --obj " + quoted(outputs[0]) + " --ply " + quoted(outputs[1]) +
                " --vts " + quoted(outputs[2]) + " --png " + quoted(outputs[3]) + " --net-out " + quoted(outputs[4]));
  INFO(spec_text << "\nstderr: " << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("error: " + spec + ": " + field + ": ", 0) == 0);
  CHECK(r.err.find(reason_part) != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  for (const auto& o : outputs) CHECK_FALSE(fs::exists(o));
  // Nothing else either (no temporary files left behind).
  CHECK(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()) == 1);
}

}  // namespace

TEST_CASE("coons surface: points[a][b] = r(a/(K-1), b/(K-1)), type, and the exact net of seed example 1",
          "[cli][surfaces]") {
  const CommandResult r =
      run_coons("surface " + quoted(surface_data("seed000_bilinear_coons_1.json")) + " --sample 5 --fit-degree 2");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["type"] == "bilinear-coons");
  REQUIRE(report["points"].size() == 5);
  for (int a = 0; a < 5; ++a) {
    REQUIRE(report["points"][a].size() == 5);
    for (int b = 0; b < 5; ++b) {
      const double u = a / 4.0, v = b / 4.0;
      const auto p = report["points"][a][b];
      CHECK(p[0].get<double>() == Approx(u + v).margin(1e-15));
      CHECK(p[1].get<double>() == Approx(u * u - v * v).margin(1e-15));
      CHECK(p[2].get<double>() == Approx(1 - u + v).margin(1e-15));
    }
  }
  // Expressions are not known to be polynomial: the net is over fits, which are exact here.
  CHECK(report["polynomial"] == false);
  CHECK(report["net"]["exact"] == false);
  CHECK(report["net"]["degree"] == json::array({2, 2}));
  CHECK(report["net"]["max_surface_deviation"].get<double>() < 1e-14);
  const auto interior = report["net"]["net"][1][1];
  CHECK(interior[0].get<double>() == Approx(1).margin(1e-14));
  CHECK(interior[1].get<double>() == Approx(0).margin(1e-14));
  CHECK(interior[2].get<double>() == Approx(1).margin(1e-14));
  // docs/math.md §5: the Coons net of example 1 has twist 0, Dirichlet 20/3, thin plate 8.
  CHECK(report["metrics"]["twist_energy"].get<double>() == Approx(0).margin(1e-12));
  CHECK(report["metrics"]["dirichlet_energy"].get<double>() == Approx(20.0 / 3).epsilon(1e-12));
  CHECK(report["metrics"]["thin_plate_energy"].get<double>() == Approx(8).epsilon(1e-12));
  CHECK(report["discrete_nets"]["coons"]["max_difference"].get<double>() < 1e-14);
  CHECK(report["compatibility"]["max_corner_gap"].get<double>() == 0);
}

TEST_CASE(
    "coons surface: max_surface_deviation does not depend on a coarse --samples and is at least that of the sides",
    "[cli][surfaces]") {
  // It was measured on the --samples grid only: 2 x 2 saw the corners and printed 0 beside a
  // side that deviates by 8.9e-4 (the sides are part of the surface).
  TempDir dir;
  const std::string file = dir.write("s.json", R"json({"name": "s", "type": "bilinear-coons",
    "bottom": {"expr": ["t", "0", "sin(pi*t)"]}, "top": {"expr": ["t", "1", "0"]},
    "left": {"expr": ["0", "t", "0"]}, "right": {"expr": ["1", "t", "exp(t)-1-t*(e-1)"]}})json");
  auto net_of = [&](int samples) {
    const CommandResult r = run_coons("surface " + quoted(file) + " --samples " + std::to_string(samples));
    INFO(r.err);
    REQUIRE(r.status == 0);
    return json::parse(r.out)["net"];
  };
  const json coarse = net_of(2), five = net_of(5), fine = net_of(129);
  const double d2 = coarse["max_surface_deviation"], d5 = five["max_surface_deviation"],
               d129 = fine["max_surface_deviation"];
  CHECK(d2 > 0);
  CHECK(d2 == d5);  // both on the 65 x 65 grid
  CHECK(d2 >= coarse["max_curve_deviation"].get<double>());
  CHECK(d129 >= d2);         // 129 x 129 contains the 65 x 65 grid...
  CHECK(d129 <= 1.05 * d2);  // ...and finds little more
}

TEST_CASE("coons surface: a polynomial surface prints its exact net, twists and energies", "[cli][surfaces]") {
  const CommandResult r = run_coons("surface " + quoted(surface_data("seed000_hermite16_T10.json")) + " --sample 3");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["type"] == "hermite16");
  CHECK(report["polynomial"] == true);
  CHECK(report["net"]["exact"] == true);
  CHECK(report["net"]["degree"] == json::array({3, 3}));
  CHECK(report["net"]["net"][1][1][2].get<double>() == Approx(10.0 / 9));
  CHECK(report["corner_twists"][0][2].get<double>() == Approx(10));
  CHECK(report["corner_twists"][3][2].get<double>() == Approx(0).margin(1e-13));
  // The boundary is planar: the discrete nets are flat, the surface is not.
  CHECK(report["discrete_nets"]["coons"]["max_difference"].get<double>() == Approx(10.0 / 9));
  CHECK(report["metrics"]["thin_plate_energy"].get<double>() > 0);
  CHECK(report["points"][1][1][2].get<double>() == Approx(10 * 0.125 * 0.125));  // T H13(½)²
}

TEST_CASE("coons surface: meshes, PNG and a net file that coons solve reads", "[cli][surfaces]") {
  TempDir dir;
  const std::string obj = dir.file("s.obj"), ply = dir.file("s.ply"), vts = dir.file("s.vts"), png = dir.file("s.png"),
                    net = dir.file("net.json");
  const std::string plane =
      dir.write("plane.json", R"({"type": "bilinear", "corners": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]})");
  const CommandResult r =
      run_coons("surface " + quoted(surface_data("seed000_hermite_coons_1.json")) + " --sample 9 --obj " + quoted(obj) +
                " --ply " + quoted(ply) + " --vts " + quoted(vts) + " --png " + quoted(png) + " --net-out " +
                quoted(net) + " --reference " + quoted(plane));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["written"].size() == 5);
  CHECK(read_text(obj).find("\nf ") != std::string::npos);
  CHECK(read_text(ply).find("property double distance") != std::string::npos);
  CHECK(read_text(vts).find("Name=\"twist\"") != std::string::npos);
  CHECK(read_text(png).substr(1, 3) == "PNG");
  CHECK(report["reference"]["max_distance"].get<double>() == Approx(2).margin(1e-9));  // z at (1, 1)
  // The net file is a boundary file: its hermite-coons closed form is this net.
  const CommandResult solved = run_coons("solve " + quoted(net) + " --method hermite-coons");
  REQUIRE(solved.status == 0);
  const json s = json::parse(solved.out);
  const BoundaryFile written = read_boundary_file(net);
  CHECK(max_difference(*written.net, net_of(s)) < 1e-14);
  // A file with "net" (here the solve report) is a reference too: the surface is its own net's.
  const std::string report_file = dir.write("solve.json", solved.out);
  const CommandResult again = run_coons("surface " + quoted(surface_data("seed000_hermite_coons_1.json")) +
                                        " --sample 7 --reference " + quoted(report_file));
  REQUIRE(again.status == 0);
  const json compared = json::parse(again.out);
  CHECK(compared["reference"]["type"] == "bezier");
  CHECK(compared["reference"]["max_distance"].get<double>() < 1e-12);
  CHECK(compared["reference"]["max_parametric_distance"].get<double>() < 1e-14);
}

TEST_CASE("coons surface: every data/surfaces file runs", "[cli][surfaces]") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(std::string(COONS_DATA_DIR) + "/surfaces")) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    INFO(entry.path());
    const CommandResult r = run_coons("surface " + quoted(entry.path().string()) + " --sample 4");
    CHECK(r.status == 0);
    CHECK(r.err.empty());
  }
  CHECK(files >= 15);  // as surfaces/seed_examples_test.cpp: the bundled examples are all there
}

TEST_CASE("coons surface: bad descriptions exit 2 with one error line naming the field, nothing written",
          "[cli][surfaces]") {
  // Wrong counts.
  check_rejected(R"({"type": "bilinear", "corners": [[0,0,0],[1,0,0],[0,1,0]]})", "corners", "exactly 4");
  check_rejected(R"({"type": "ruled", "curves": [{"bezier": [[0,0,0],[1,0,0]]}]})", "curves", "exactly 2");
  check_rejected(R"({"type": "ferguson", "corners": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]],
                     "du": [[1,0,0],[1,0,0],[1,0,0],[1,0,0]], "dv": [[0,1,0],[0,1,0],[0,1,0],[0,1,0],[0,1,0]]})",
                 "dv", "exactly 4");
  // Unknown type.
  check_rejected(R"({"type": "nurbs"})", "type", "unknown type 'nurbs'");
  // An expression that does not parse.
  check_rejected(R"({"type": "ruled", "curves": [{"expr": ["t", "sin(pi*t", "0"]}, {"bezier": [[0,1,0],[1,1,0]]}]})",
                 "curves[0].expr[1]", "does not parse");
  // Incompatible data: corners, then a general-Coons twist.
  check_rejected(
      R"({"type": "bilinear-coons", "bottom": {"bezier": [[0,0,0],[1,0,0]]}, "top": {"bezier": [[0,1,0],[1,1,0]]},
                     "left": {"bezier": [[0,0,0],[0,1,0]]}, "right": {"bezier": [[1,0,0.5],[1,1,0]]}})",
      "right", "bottom-right (u = 1, v = 0)");
  check_rejected(R"({"type": "general-coons",
                     "bottom": {"bezier": [[0,0,0],[1,0,0]]}, "top": {"bezier": [[0,1,0],[1,1,0]]},
                     "left": {"bezier": [[0,0,0],[0,1,0]]}, "right": {"bezier": [[1,0,0],[1,1,0]]},
                     "du_left": {"point": [1,0,0]}, "du_right": {"point": [1,0,0]},
                     "dv_bottom": {"point": [0,1,0]}, "dv_top": {"point": [0,1,0]},
                     "twist": [[0,0,0],[0,0,0],[0,0,0],[0,0,3]]})",
                 "twist[3]", "top-right (u = 1, v = 1): twist[3] = du_right'(1) fails by 3");
  // Missing and misspelt fields, malformed JSON.
  check_rejected(R"({"type": "hermite-coons", "bottom": {"bezier": [[0,0,0],[1,0,0]]}})", "top", "missing");
  check_rejected(R"({"type": "bilinear", "corner": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]]})", "corner", "unknown field");
}

TEST_CASE("coons surface: bad options and unreadable files exit 2", "[cli][surfaces]") {
  TempDir dir;
  const std::string spec = surface_data("seed000_ferguson_1.json");
  CommandResult r = run_coons("surface " + quoted(spec) + " --sample 1");
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error: command line: --samples: ", 0) == 0);
  r = run_coons("surface " + quoted(spec) + " --obj " + quoted(dir.file("missing/s.obj")));
  CHECK(r.status == 2);
  CHECK(r.err.rfind("error: command line: --obj: ", 0) == 0);
  r = run_coons("surface " + quoted(dir.write("broken.json", "{\"type\": ")));
  CHECK(r.status == 2);
  CHECK(r.err.find("malformed JSON") != std::string::npos);
  r = run_coons("surface " + quoted(dir.file("absent.json")));
  CHECK(r.status == 2);
  CHECK(r.out.empty());
}

TEST_CASE("coons join: bicubic Coons patches over C1 transversal curves join G1, bilinear ones do not",
          "[cli][surfaces]") {
  const std::string dir = std::string(COONS_DATA_DIR) + "/surfaces/";
  auto join = [&](const std::string& kind) {
    const CommandResult r = run_command(std::string(COONS_BINARY) + " join '" + dir + "join_" + kind +
                                        "_a.json' right '" + dir + "join_" + kind + "_b.json' left");
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(r.out);
  };
  const nlohmann::json hermite = join("hermite"), bilinear = join("bilinear");
  CHECK(hermite["c0_gap"].get<double>() < 1e-12);
  CHECK(hermite["g1"] == true);
  CHECK(hermite["max_normal_angle_rad"].get<double>() < 1e-8);
  CHECK(bilinear["c0"] == true);
  CHECK(bilinear["g1"] == false);
  CHECK(bilinear["max_normal_angle_deg"].get<double>() > 1);
  const CommandResult bad = run_command(std::string(COONS_BINARY) + " join '" + dir + "join_hermite_a.json' middle '" +
                                        dir + "join_hermite_b.json' left");
  CHECK(bad.status == 2);
  CHECK_THAT(bad.err, Catch::Contains("FIRST_SIDE"));
}

TEST_CASE("coons join: patches of every type that share a side exactly meet C0 (the size is sampled)",
          "[cli][surfaces]") {
  // two `bilinear` patches sharing the side x = 1 with a rounding-level gap: the size used to be 0
  // for this type, so any gap at all reported c0 false
  TempDir dir;
  const std::string a = dir.write("a.json", R"({"name": "a", "type": "bilinear",
    "corners": [[0, 0, 0], [1, 0, 0.1], [0, 1, 0], [1, 1, 0.30000000000000004]]})");
  const std::string b = dir.write("b.json", R"({"name": "b", "type": "bilinear",
    "corners": [[1, 0, 0.1], [2, 0, 0], [1, 1, 0.3], [2, 1, 0.5]]})");
  const CommandResult r = run_command(std::string(COONS_BINARY) + " join '" + a + "' right '" + b + "' left");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const nlohmann::json seam = nlohmann::json::parse(r.out);
  CHECK(seam["c0_gap"].get<double>() > 0);  // not an exact match: rounding only
  CHECK(seam["c0_gap"].get<double>() < 1e-15);
  CHECK(seam["c0"] == true);
  // a real gap stays one
  const std::string c = dir.write("c.json", R"({"name": "c", "type": "bilinear",
    "corners": [[1, 0, 0.1001], [2, 0, 0], [1, 1, 0.3], [2, 1, 0.5]]})");
  const CommandResult g = run_command(std::string(COONS_BINARY) + " join '" + a + "' right '" + c + "' left");
  REQUIRE(g.status == 0);
  CHECK(nlohmann::json::parse(g.out)["c0"] == false);
  // sides collapsed to one point: no normal exists along them, so no G1 claim (it used to be true
  // with an angle of 0 over no compared sample)
  const std::string d = dir.write("d.json", R"({"name": "d", "type": "bilinear",
    "corners": [[0, 0, 0], [0, 0, 0], [0, 1, 0], [1, 1, 0.5]]})");
  const std::string e = dir.write("e.json", R"({"name": "e", "type": "bilinear",
    "corners": [[0, 0, 0], [0, 0, 0], [0, -1, 0], [1, -1, -0.5]]})");
  const CommandResult apex = run_command(std::string(COONS_BINARY) + " join '" + d + "' bottom '" + e + "' bottom");
  REQUIRE(apex.status == 0);
  const nlohmann::json point = nlohmann::json::parse(apex.out);
  CHECK(point["c0"] == true);
  CHECK(point["normals_compared"] == 0);
  CHECK(point["g1"] == false);
  // and no angle or place of it either (they were 0.0, a measurement that was never made)
  CHECK(point["max_normal_angle_rad"].is_null());
  CHECK(point["max_normal_angle_deg"].is_null());
  CHECK(point["at"].is_null());
}

TEST_CASE("coons join: a surface that is not finite on the seam is bad input naming the file and the side",
          "[cli][surfaces]") {
  // z of the shared side is NaN for t in (0.5099, 0.5101): between the reader's 65 samples t = k/64,
  // on the seam sample t = 0.51. Both patches share that side, so the NaN sample was skipped and
  // the report said c0 true with a gap of 0.
  TempDir dir;
  const std::string z = "sqrt((t-0.5099)*(t-0.5101))-sqrt(0.4901*0.4899)*t-sqrt(0.5099*0.5101)*(1-t)";
  auto expr = [](const std::string& cx, const std::string& cy, const std::string& cz) {
    return json{{"expr", {cx, cy, cz}}};
  };
  const std::string a = dir.write("a.json", json{{"type", "bilinear-coons"},
                                                 {"bottom", expr("t", "0", "0")},
                                                 {"top", expr("t", "1", "0")},
                                                 {"left", expr("0", "t", "0")},
                                                 {"right", expr("1", "t", z)}}
                                                .dump());
  const std::string b = dir.write("b.json", json{{"type", "bilinear-coons"},
                                                 {"bottom", expr("1+t", "0", "0")},
                                                 {"top", expr("1+t", "1", "0")},
                                                 {"left", expr("1", "t", z)},
                                                 {"right", expr("2", "t", "0")}}
                                                .dump());
  const CommandResult r = run_coons("join " + quoted(a) + " right " + quoted(b) + " left");
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  // the reader's search for poles finds the NaN (join's own check of its seam samples would too)
  CHECK(r.err.rfind("error: " + a + ": right.expr[2]: ", 0) == 0);
  CHECK(contains(r.err, "is not finite near t = 0.5099"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  // the second surface is named when the first is finite there
  const std::string c = dir.write("c.json", R"({"type": "bilinear", "corners": [[0, 0, 0], [1, 0, 0], [0, 1, 0],
    [1, 1, 0]]})");
  const CommandResult second = run_coons("join " + quoted(c) + " right " + quoted(b) + " left --reversed");
  INFO(second.out << second.err);
  CHECK(second.status == 2);
  CHECK(second.err.rfind("error: " + b + ": left.expr[2]: ", 0) == 0);
}

TEST_CASE("coons surface --reference: a B-spline net is refused naming its knots, not read as a Bezier net",
          "[cli][surfaces]") {
  TempDir dir;
  const std::string spec = quoted(surface_data("seed000_hermite_coons_1.json"));
  // the solve report of a B-spline boundary holds "net" (the B-spline control net) and "bspline"
  const std::string wave = kData + "/boundaries/bspline_wave.json";
  const CommandResult solved = run_coons("solve " + quoted(wave));
  REQUIRE(solved.status == 0);
  REQUIRE(json::parse(solved.out).contains("bspline"));
  const std::string report = dir.write("wave.solve.json", solved.out);
  const std::string why = "a B-spline net is not a Bézier net";
  const std::pair<std::string, std::string> cases[] = {{report, "error: " + report + ": bspline: " + why},
                                                       {wave, "error: " + wave + ": knots_u: " + why}};
  for (const auto& [reference, start] : cases) {
    const CommandResult r = run_coons("surface " + spec + " --sample 5 --reference " + quoted(reference));
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind(start, 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("coons surface: a curve with a pole between the reader's samples is bad input naming the curve",
          "[cli][surfaces]") {
  // z = 0.001/(t − 0.3) + a linear term that makes it vanish at both ends: finite at the reader's
  // 65 samples t = k/64 and at k/1024, infinite at t = 0.3, where the search for poles ends
  TempDir dir;
  const std::string spec = dir.write("spole.json",
                                     R"json({"type": "bilinear-coons",
          "bottom": {"expr": ["t", "0", "0.001/(t-0.3)+0.001/0.3-t*(0.001/0.7+0.001/0.3)"]},
          "top": {"expr": ["t", "1", "0"]}, "left": {"expr": ["0", "t", "0"]}, "right": {"expr": ["1", "t", "0"]}})json");
  const CommandResult r = run_coons("surface " + quoted(spec));
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(contains(r.err, "spole.json: bottom.expr[2]: '0.001/(t-0.3)"));
  CHECK(contains(r.err, "has a pole or is not finite near t = 0.3,"));
}

TEST_CASE("coons surface: curvatures of a model far from the origin, and none where no sample has one",
          "[cli][surfaces]") {
  // The bundled Hermite pair moved by 1e8 in x printed mean curvature 0 (its expression curves'
  // second derivatives were NaN by rounding); a cylinder wound 1000 times, whose derivatives do
  // not settle, printed 0 too, a flat surface.
  TempDir dir;
  const std::string moved = dir.write("moved.json", R"json({"type": "ruled",
      "curves": [{"expr": ["1e8 + cos(t)", "sin(t)", "0"], "interval": [0, 3]},
                 {"expr": ["1e8 + cos(t)", "sin(t)", "1"], "interval": [0, 3]}]})json");
  const std::string near = dir.write("near.json", R"json({"type": "ruled",
      "curves": [{"expr": ["cos(t)", "sin(t)", "0"], "interval": [0, 3]},
                 {"expr": ["cos(t)", "sin(t)", "1"], "interval": [0, 3]}]})json");
  const auto sampled = [](const std::string& file) {
    const CommandResult r = run_coons("surface " + quoted(file) + " --samples 5");
    INFO(r.err);
    REQUIRE(r.status == 0);
    return nlohmann::json::parse(r.out)["sampled"];
  };
  const nlohmann::json at_origin = sampled(near), far = sampled(moved);
  CHECK(at_origin["singular_samples"] == 0);
  CHECK(far["singular_samples"] == 0);
  CHECK(at_origin["max_abs_mean_curvature"].get<double>() == Approx(0.5).epsilon(1e-6));  // a unit cylinder
  CHECK(far["max_abs_mean_curvature"].get<double>() == Approx(0.5).epsilon(2e-2));
  const std::string wound = dir.write("wound.json", R"json({"type": "ruled",
      "curves": [{"expr": ["cos(t)", "sin(t)", "0"], "interval": [0, 6283.185307179586]},
                 {"expr": ["cos(t)", "sin(t)", "1"], "interval": [0, 6283.185307179586]}]})json");
  // Inside, central differences do not settle: the samples at the 3 inner values of t, 3 × 5 of the
  // 5 × 5, are singular. At the two ends, differences inside the interval (one-sided) do, and give
  // the cylinder's curvature 0.5 (the largest of them; it was 0, a flat surface).
  const nlohmann::json none = sampled(wound);
  CHECK(none["singular_samples"] == 3 * 5);
  CHECK(none["max_abs_mean_curvature"].get<double>() == Approx(0.5).epsilon(1e-6));
  // detail far below any step: no sample has a curvature, and none is printed
  const std::string rough = dir.write("rough.json", R"json({"type": "ruled",
      "curves": [{"expr": ["cos(t) + 1e-3*sin(1e9*t)", "sin(t)", "0"], "interval": [0, 3]},
                 {"expr": ["cos(t) + 1e-3*sin(1e9*t)", "sin(t)", "1"], "interval": [0, 3]}]})json");
  const nlohmann::json nowhere = sampled(rough);
  CHECK(nowhere["singular_samples"] == 5 * 5);  // every sample
  CHECK(nowhere["max_abs_mean_curvature"].is_null());
}

TEST_CASE("coons surface: the fits of a general Coons patch's cross derivatives are no floor of max_surface_deviation",
          "[cli][surfaces]") {
  // The pillow's sides are Bézier; its cross derivatives are fitted (0.0028), but they are tangents,
  // not points of the surface: the net's patch lies 0.00092 from the surface, and it printed 0.0028.
  const CommandResult r =
      run_coons("surface " + quoted(kData + "/surfaces/seed001_general_coons_pillow.json") + " --samples 5");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json net = json::parse(r.out)["net"];
  for (const json& fit : net["curve_fits"]) CHECK(fit["curve"].get<std::string>().rfind('d', 0) == 0);
  const double surface = net["max_surface_deviation"], curves = net["max_curve_deviation"];
  CHECK(surface < 0.5 * curves);
  CHECK(surface == Approx(0.000918).epsilon(1e-2));  // an independent evaluation on 201 x 201 points (review)
}
