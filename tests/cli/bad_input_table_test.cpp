// The bad-input table (issue 10): malformed files, values and option combinations across every
// command. Each case must exit 2 with exactly one `error:` line that names the file (or "command
// line"), the field and the reason, print nothing on standard output and leave no file in the
// output folder.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "coons/config.h"
#include "support/cli_support.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Case {
  std::string args;     //!< after `coons`; {OUT} is the output folder, {IN} the folder of inputs
  std::string mention;  //!< the field or file the error line must name
};

std::string replace_all(std::string s, const std::string& what, const std::string& with) {
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + with.size()))
    s.replace(at, what.size(), with);
  return s;
}

}  // namespace

TEST_CASE("coons: the bad-input table (every command, exit 2, one error line, nothing written)", "[cli][bad-input]") {
  TempDir inputs;
  const json dome = json::parse(std::ifstream(kData + "/boundaries/dome.json"));
  auto variant = [&](const std::string& name, const std::function<void(json&)>& edit) {
    json doc = dome;
    edit(doc);
    return "{IN}/" + name;
  };
  auto write_variant = [&](const std::string& name, const std::function<void(json&)>& edit) {
    json doc = dome;
    edit(doc);
    inputs.write(name, doc.dump());
    return "{IN}/" + name;
  };
  (void)variant;
  inputs.write("broken.json", "{\"bottom\": [[0,0,0],");
  // a device where a file is read whole: /dev/zero as three.js, and as a shard file a rerun reads
  // (both were read without end, to 13 and 9 GB)
  fs::create_directories(inputs.path / "shard_dev");
  fs::create_symlink("/dev/zero", inputs.path / "shard_dev" / "shard-0-of-1.jsonl");
  inputs.write("empty.json", "");
  inputs.write("array.json", "[1, 2, 3]");
  inputs.write("inf.json",
               "{\"bottom\":[[0,0,0],[1e999,0,0]],\"top\":[[0,1,0],[1,1,0]],\"left\":[[0,0,0],[0,1,0]],\"right\":[[1,0,"
               "0],[1,1,0]]}");
  fs::create_directories(inputs.path / "emptyfolder");
  inputs.write("notafolder", "x");
  inputs.write("a.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 2\n2 2 2\n");
  {  // a plane whose sides have degree 10: the base of a perturbed family above the default degree 3
    json plane = {{"degree", {10, 10}}};
    for (int k = 0; k <= 10; ++k) {
      const double t = k / 10.0;
      plane["bottom"].push_back({t, 0, 0});
      plane["top"].push_back({t, 1, 0});
      plane["left"].push_back({0, t, 0});
      plane["right"].push_back({1, t, 0});
    }
    inputs.write("degree10.json", plane.dump());
  }
  const std::string notop = write_variant("notop.json", [](json& d) { d.erase("top"); });
  const std::string longleft = write_variant("long.json", [](json& d) { d["left"].push_back({-1, 1, 0}); });
  const std::string four = write_variant("four.json", [](json& d) { d["bottom"][1] = {1, 2, 3, 4}; });
  const std::string corner = write_variant("corner.json", [](json& d) { d["right"][0][2] = 0.5; });
  const std::string degree = write_variant("degree.json", [](json& d) { d["degree"] = {4, 3}; });
  const std::string string_point = write_variant("string.json", [](json& d) { d["top"][1][0] = "x"; });
  const std::string name_number = write_variant("name.json", [](json& d) { d["name"] = 5; });
  const std::string sphere5 = write_variant("sphere5.json", [](json& d) { d["target"] = {{"sphere", 5}}; });
  const std::string target_list = write_variant("tlist.json", [](json& d) { d["target"] = json::array({1}); });
  const std::string no_radius = write_variant("noradius.json", [](json& d) { d["target"]["sphere"].erase("radius"); });
  const std::string neg_radius = write_variant("negradius.json", [](json& d) { d["target"]["sphere"]["radius"] = -1; });
  const std::string cone = write_variant("cone.json", [](json& d) { d["target"] = {{"cone", {{"apex", {0, 0, 0}}}}}; });
  const std::string curves_list = write_variant("curves.json", [](json& d) { d["curves"] = json::array(); });
  const std::string curves_gap = write_variant("gap.json", [](json& d) {
    d["curves"]["bottom"] = {{"bezier", {{-1, -1, 0}, {1, -1, 0.5}}}};
  });
  // beyond one ring (issue 11): ribbons, rings, free grids, masks
  const json cap = json::parse(std::ifstream(kData + "/boundaries/sphere_cap_ribbons.json"));
  const json island = json::parse(std::ifstream(kData + "/free_sets/island.json"));
  auto write_edit = [&](const json& base, const std::string& name, const std::function<void(json&)>& edit) {
    json doc = base;
    edit(doc);
    inputs.write(name, doc.dump());
    return "{IN}/" + name;
  };
  const std::string ribbon_gap = write_edit(cap, "ribbon_gap.json", [](json& d) {
    d["ribbons"]["left"][1][2] = d["ribbons"]["left"][1][2].get<double>() + 0.01;
  });
  const std::string ribbon_short = write_edit(cap, "ribbon_short.json", [](json& d) { d["ribbons"]["top"].erase(0); });
  const std::string ribbon_missing =
      write_edit(cap, "ribbon_missing.json", [](json& d) { d["ribbons"].erase("right"); });
  const std::string rings_zero = write_edit(island, "rings0.json", [](json& d) { d["rings"] = 0; });
  const std::string rings_many = write_edit(island, "rings9.json", [](json& d) { d["rings"] = 9; });
  const std::string free_ring = write_edit(island, "free_ring.json", [](json& d) { d["free"][1][4] = 1; });
  const std::string free_value = write_edit(island, "free_value.json", [](json& d) { d["free"][3][4] = 7; });
  const std::string free_shape = write_edit(island, "free_shape.json", [](json& d) { d["free"].erase(0); });
  const std::string free_sides = write_variant("free_sides.json", [](json& d) { d["free"] = {{0, 0}, {0, 0}}; });
  // one data ring and a free point next to it: fine for 3x3 masks, the 5x5 stencil leaves the net
  const std::string free_edge = write_edit(island, "free_edge.json", [](json& d) {
    d["rings"] = 1;
    d["free"][1][5] = 1;
  });
  // a stencil with W(0, ±1) = −1: two free neighbours along j alone make the system singular
  inputs.write("stencil_pair.json", "{\"weights\": [[1, 0, 1], [-4, null, -4], [1, 0, 1]]}");
  const std::string free_pair = write_edit(island, "free_pair.json", [](json& d) {
    for (auto& row : d["free"])
      for (auto& x : row) x = 0;
    d["free"][5][3] = 1;
    d["free"][5][4] = 1;
  });
  inputs.write("stencil_asym.json", "{\"weights\": [[0, 1, 0], [2, null, 1], [0, 1, 0]]}");
  inputs.write("stencil_flat.json", "{\"weights\": [[0, 0, 0], [0, 1, 0], [0, 0, 0]]}");
  // A file stencil whose symbol dips to −8e-9 between two of the samples symbol_nonnegative takes
  // (σ = 1 + 2w₁cos θ + 2w₂cos 2θ, see stencil_test.cpp), on a net whose free points form one
  // column of 300: the system is singular to rounding (it was solved into z ≈ 6e7, exit 0).
  {
    const double w1 = -0.6666907169580457, w2 = 0.16669071695804574;
    json column =
        json::array({json::array({0, 0, w2, 0, 0}), json::array({0, 0, w1, 0, 0}), json::array({0, 0, nullptr, 0, 0}),
                     json::array({0, 0, w1, 0, 0}), json::array({0, 0, w2, 0, 0})});
    inputs.write("stencil_dip.json", json{{"weights", column}}.dump());
    json net = json::array();
    for (int i = 0; i <= 303; ++i) {
      json row = json::array();
      for (int j = 0; j <= 4; ++j) row.push_back({i / 303.0, j / 4.0, std::sin(3 * i / 303.0)});
      net.push_back(row);
    }
    inputs.write("tall.json", json{{"name", "tall"}, {"rings", 2}, {"net", net}}.dump());
  }
  // B-spline knots closer than kMinKnotSpan of the range: within one side (1e-15 after knot 3:
  // the solve reported success with a mask residual of 0.17), and between two sides given apart.
  const json wave = json::parse(std::ifstream(kData + "/boundaries/bspline_wave.json"));
  const std::string knot_close = write_edit(wave, "knot_close.json", [](json& d) { d["knots_u"][4] = 1e-15; });
  const std::string knots_apart = write_edit(wave, "knots_apart.json", [](json& d) {
    json top = d["knots_u"];
    top[5] = top[5].get<double>() + 1e-11;
    d["knots_u"] = {{"bottom", d["knots_u"]}, {"top", top}};
  });
  const std::string good = quoted(kData + "/boundaries/dome.json");
  const std::string pillow = quoted(kData + "/boundaries/pillow.json");
  const std::string surface = quoted(kData + "/surfaces/join_bilinear_a.json");
  const std::string surface_b = quoted(kData + "/surfaces/join_bilinear_b.json");
  inputs.write("badtype.json", "{\"type\": \"teapot\"}");
  inputs.write("nocorners.json", "{\"type\": \"bilinear\"}");
  // a bilinear patch 1e-170 across: join read its open seam (gap 1.4e-170) as closed, surface its
  // Gaussian curvature 1e320 as 0
  // a triangle 1e-100 across: its Gaussian curvature (about 1e200) is fine, but at 1e-160 it leaves
  // the doubles; --ply and --vtu refuse a model below 1e-60 as surface does
  inputs.write("tiny_triangle.json", R"({"type": "triangle", "degree": 1, "sides": [[[0, 0, 0], [1e-100, 0, 0]],
                                [[1e-100, 0, 0], [0, 1e-100, 0]], [[0, 1e-100, 0], [0, 0, 0]]]})");
  // a triangle with a rectangular form's field: it was ignored, and the knots' triangle solved as a Bezier one
  inputs.write("tri_knots.json", R"({"type": "triangle", "sides": [[[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [0, 1, 0]],
                                [[0, 1, 0], [0, 0, 0]]], "knots_u": [0, 0, 1, 1]})");
  inputs.write("tri_rings.json", R"({"type": "triangle", "sides": [[[0, 0, 0], [1, 0, 0]], [[1, 0, 0], [0, 1, 0]],
                                [[0, 1, 0], [0, 0, 0]]], "rings": 2})");
  // a triangle's solve report read back: "net" rows and no "sides"
  inputs.write("tri_report.json", R"({"type": "triangle", "degree": 1, "net": [[[0, 0, 0], [1, 0, 0]], [[0, 1, 0]]]})");
  inputs.write("tiny.json", R"({"type": "bilinear", "corners": [[0, 0, 0], [1e-170, 0, 0], [0, 1e-170, 0],
                                [1e-170, 1e-170, 1e-170]]})");
  // a ruled surface between a line and a Bezier curve of degree 3000: its 3001 by 2 net's energies
  // need about 60 MB (degree 30000 took 881 MB under --max-memory 10MB)
  {
    json wavy = json::array(), line = json::array({{0, 0, 0}, {1, 0, 0}});
    for (int i = 0; i <= 3000; ++i) wavy.push_back({i / 3000.0, 1, 0.1 * (i % 3)});
    inputs.write("ruled3000.json",
                 json{{"type", "ruled"}, {"curves", {{{"bezier", line}}, {{"bezier", wavy}}}}}.dump());
  }

  const std::vector<Case> cases = {
      // solve: files
      {"solve {IN}/missing.json", "missing.json"},
      {"solve {IN}/broken.json", "broken.json"},
      {"solve {IN}/empty.json", "empty.json"},
      {"solve {IN}/array.json", "array.json"},
      {"solve {IN}/inf.json", "inf.json"},
      {"solve " + notop, "top"},
      {"solve " + longleft, "right"},
      {"solve " + four, "bottom[1]"},
      {"solve " + corner, "corner"},
      {"solve " + degree, "degree"},
      {"solve " + string_point, "top"},
      {"solve " + name_number, "name"},
      {"solve " + knot_close, "knots_u[4]"},
      {"solve " + knots_apart, "knots_u"},
      {"solve " + write_variant("deep.json",
                                [](json& d) {
                                  json t = 1;
                                  for (int k = 0; k < 200; ++k) t = json::array({t});
                                  d["target"] = t;
                                }),
       "deep.json"},
      {"solve " + write_variant("bigdegree.json",
                                [](json& d) {
                                  d["degree"] = {4294967299LL, 4294967299LL};
                                }),
       "degree"},
      {"solve " + write_variant("huge.json", [](json& d) { d["bottom"][1][2] = 1e308; }), "bottom"},
      {"refit " +
           write_variant("deeptarget.json",
                         [](json& d) {
                           json t = json::object();
                           for (int k = 0; k < 200; ++k) t = json{{"sphere", t}};
                           d["target"] = t;
                         }) +
           " --degree 4 4 --out {OUT}/r.json",
       "deeptarget.json"},
      // solve: options
      {"solve " + quoted(kData + "/boundaries/seed_example1.json") + " --method hermite-coons", "degree"},
      {"solve " + good + " --alpha -0.4 --solver eigen-ldlt", "--alpha"},
      {"solve " + good + " --solver nonesuch", "--solver"},
      {"solve " + good + " --method nonesuch", "--method"},
      {"solve " + good + " --frobnicate", "frobnicate"},
      {"solve " + good + " --solver gauss-seidel --omega 2.5", "omega"},
      {"solve " + good + " --corner-tolerance -1", "--corner-tolerance"},
      {"solve " + good + " --mu -1", "--mu"},
      {"solve " + good + " --alpha nan", "--alpha"},
      // curvatures (--ply of a triangle) of a model below 1e-60 would leave the doubles
      {"export {IN}/tiny_triangle.json --ply --out {OUT}/t",
       "tiny_triangle.json: sides[0][1]: the largest coordinate magnitude of the model is 1e-100, below 1e-60"},
      // (the defaults of a triangle's export are OBJ, PLY and VTU)
      {"export {IN}/tiny_triangle.json --out {OUT}/t", "tiny_triangle.json: sides[0][1]: the largest coordinate"},
      {"solve {IN}/tri_knots.json", "tri_knots.json: knots_u: belongs to a rectangular boundary"},
      // a backend only for definite systems fails at every c != 0 of a search's or a sweep's range:
      // search-alpha tried its 9 scan points and exited 3, where view refused it at once
      {"search-alpha " + quoted(kData + "/triangles/dome_half.json") + " --objective thin_plate --solver cg",
       "--solver: cg is only for symmetric positive definite systems"},
      {"sweep " + quoted(kData + "/triangles/dome_half.json") + " --solver cg --out {OUT}/s",
       "--solver: cg is only for symmetric positive definite systems"},
      {"search-alpha {IN}/tri_knots.json --objective thin_plate", "tri_knots.json: knots_u:"},
      {"sweep {IN}/tri_rings.json --out {OUT}/s", "tri_rings.json: rings: belongs to a rectangular boundary"},
      {"view {IN}/tri_rings.json --out {OUT}/v.html", "tri_rings.json: rings:"},
      {"refit " + good + " --degree 4 4 --out {OUT}/" + std::string(236, 'y'),
       "command line: --out: the file name is 236 bytes long, more than 235"},
      // a singular member of the 3x3 family on a file without a free grid names --alpha (it named
      // "free[1][1]" of a file that has no "free")
      {"export " + good + " --alpha 0.5 --out {OUT}/e",
       "command line: --alpha: alpha = 0.5 on the 4 by 4 net of " + kData +
           "/boundaries/dome.json: the mask system is singular: the free points (1, 1)"},
      {"solve " + good + " --alpha 0.5 --solver eigen-lu", "command line: --alpha: alpha = 0.5 on the 4 by 4 net"},
      // an alpha the named solver refuses names the file whose system it is (the contract's bad input
      // "an alpha outside what the chosen solver accepts" names the file, the field and the reason)
      {"solve " + good + " --alpha 0.4 --solver eigen-llt",
       "command line: --alpha: 0.4 is outside [-0.25, 0.25], where the mask system of " + kData +
           "/boundaries/dome.json is positive definite; eigen-llt needs that"},
      // beyond kMaxAlpha: `fast` called the dome singular at 1e160, and at 1e308 the singularity
      // check named four points that do not decouple
      {"solve " + good + " --alpha 1e308", "--alpha: 1e+308 is beyond the bound |alpha| <= 1e+60"},
      {"solve " + good + " --alpha -1e61 --solver eigen-lu", "--alpha: -1e+61 is beyond the bound"},
      {"solve " + quoted(kData + "/triangles/dome_half.json") + " --alpha 1e200", "--alpha: 1e+200 is beyond"},
      // a triangle is studied up to tri::kMaxTriDegree (degree 400 ran out of memory, exit 1)
      {"study " + quoted(kData + "/triangles/dome_half.json") + " --degrees 6 41 --out {OUT}",
       "--degrees: 41 is above 40, the largest degree of a triangular boundary"},
      {"search-alpha " + good + " --objective thin_plate --allow-indefinite --lower -1e308 --upper 1e308",
       "command line: --lower: must lie in [-1e60, 1e60]"},
      {"search-alpha " + quoted(kData + "/triangles/dome_half.json") + " --objective thin_plate --upper 1e61",
       "command line: --upper: must lie in [-1e60, 1e60]"},
      // the option at fault alone, not "--lower/--upper/--scan"
      {"search-alpha " + good + " --objective thin_plate --scan 2",
       "command line: --scan: must be in [3, 10001], not 2"},
      {"search-alpha " + quoted(kData + "/triangles/dome_half.json") +
           " --objective thin_plate --lower 0.2 --upper 0.1",
       "command line: --lower/--upper: need lower < upper, not 0.2 and 0.1"},
      {"solve " + good + " --alpha ''", "--alpha: an empty value"},  // was alpha = 0, exit 0
      // strtod reads these as 0 (ERANGE): they solved at alpha = 0 and weight 0, exit 0
      {"solve " + good + " --alpha 1e-400", "--alpha: '1e-400' is below the smallest double and would be read as 0"},
      // (hexadecimal, which strtod reads too, is refused before its size is looked at)
      {"solve " + good + " --alpha=-0x1p-2000", "--alpha: '-0x1p-2000' is not a decimal number"},
      {"sweep " + good + " --from 1e-999 --out {OUT}", "--from: '1e-999' is below the smallest double"},
      {"batch " + good + " --alphas 0 1e-330 --out {OUT}", "--alphas: '1e-330' is below the smallest double"},
      {"search-alpha " + good + " --objective target --target sphere:1e-400,0,-1,1.73",
       "--target: '1e-400' is below the smallest double"},  // was a centre x of 0
      {"solve " + good + " --threads '' --solver fast", "--threads: an empty value"},
      {"solve " + good + " --max-memory ''", "--max-memory: an empty value"},
      {"solve ''", "BOUNDARY: an empty value"},
      {"solve " + good + " --max-memory lots", "--max-memory"},
      {"solve " + good + " --max-memory 0x10", "--max-memory"},  // was read as 16 bytes
      {"solve " + good + " --max-memory 1e-3", "--max-memory"},  // was read as a thousandth of a byte
      // CLI11's own words put the option after "Could not convert:", not where every field goes
      {"solve " + good + " --solver cg --max-iterations 99999999999",
       "command line: --max-iterations: '99999999999' is not an integer from -2147483648 to 2147483647"},
      {"solve " + good + " --solver cg --max-iterations 1.5",
       "command line: --max-iterations: '1.5' is not an integer"},
      {"solve " + good + " --alpha abc", "command line: --alpha: 'abc' is not a number"},
      {"solve " + good + " --max-memory ' 5MB'", "--max-memory"},
      {"solve " + good + " --method coons --tolerance 1e-6", "--tolerance"},
      {"solve " + good + " --method coons --mu -1", "--mu"},  // a closed form's --mu is still checked
      {"solve " + good + " --alpha 0.1 --mu 2", "--mu"},
      {"solve " + good + " --tolerance -1 --solver cg", "tolerance"},
      {"solve", "BOUNDARY"},
      {"solve " + ribbon_gap, "ribbons.left[1]"},
      {"solve " + ribbon_short, "ribbons.top"},
      {"solve " + ribbon_missing, "ribbons.right"},
      {"solve " + rings_zero, "rings"},
      {"solve " + rings_many, "rings"},
      {"solve " + free_ring + " --mask c1-coons", "free[1][4]"},
      {"solve " + free_value, "free[3][4]"},
      {"solve " + free_shape, "free"},
      {"solve " + free_sides, "free"},
      {"solve " + free_edge + " --mask biharmonic", "rings"},
      {"solve " + good + " --mask c1-coons", "rings"},
      {"solve " + free_pair + " --mask file:{IN}/stencil_pair.json", "free[5][3]: the mask system is singular"},
      {"solve " + good + " --mask nonesuch", "--mask"},
      {"solve " + good + " --mask file:", "--mask"},
      {"solve " + good + " --mask file:{IN}/missing.json", "missing.json"},
      {"solve " + good + " --mask file:{IN}/stencil_asym.json", "stencil_asym.json: weights[1][0]"},
      {"solve " + good + " --mask file:{IN}/stencil_flat.json", "stencil_flat.json: weights"},
      {"solve " + good + " --weight 0.5", "--weight"},
      {"solve " + good + " --mask c1-coons --weight 0.5", "--weight"},
      {"solve " + good + " --mask c1-family", "--weight"},
      {"solve " + good + " --mask c1-family --weight 1.5", "--weight"},
      {"solve " + good + " --mask biharmonic --alpha 0.1", "--alpha"},
      {"solve " + good + " --method coons --mask c1-coons", "--mask"},
      {"solve " + quoted(kData + "/boundaries/sphere_cap_ribbons.json") + " --method coons", "--method"},
      {"solve " + quoted(kData + "/free_sets/island.json") + " --method hermite-coons", "--method"},
      // solvers
      {"solvers --frobnicate", "frobnicate"},
      // export
      {"export " + good + " --samples 1 --out {OUT}", "--samples"},
      {"export " + good + " --mtx --method coons --out {OUT}", "--mtx"},
      {"export " + good + " --mask c1-coons --out {OUT}", "rings"},
      {"export " + good + " --weight 0.5 --out {OUT}", "--weight"},
      {"export " + free_ring + " --mask c1-coons --out {OUT}", "free[1][4]"},
      {"export " + free_pair + " --mask file:{IN}/stencil_pair.json --mtx --out {OUT}", "free[5][3]"},
      {"export " + good + " --prefix ../x --out {OUT}", "--prefix"},
      {"export " + good + " --prefix " + std::string(81, 'x') + " --out {OUT}", "--prefix: is 81 bytes long"},
      {"solve " + good + " --method foo", "--method: 'foo' is not one of alpha, coons, hermite-coons"},
      {"solve " + good + " --method 1", "--method: '1' is not one of"},  // the enum's number was taken
      {"sweep " + good + " --parameter beta --out {OUT}", "--parameter: 'beta' is not one of alpha, mu"},
      {"export " + corner + " --out {OUT}", "corner"},
      {"export " + good + " --solver nonesuch --out {OUT}", "--solver"},
      {"export " + good + " --obj --samples 50000 --out {OUT}", "--samples"},
      {"export " + good + " --out {IN}/notafolder/out", "notafolder"},
      {"export " + sphere5 + " --method coons --solver cholmod --out {OUT}", "--solver"},
      // batch
      {"batch {IN}/emptyfolder --out {OUT}", "emptyfolder: the folder holds no *.json boundary file"},
      {"batch " + good + " --alphas 0.3 --out {OUT}", "--alphas"},
      {"batch " + good + " --alphas -0.1 -0.1 --out {OUT}", "--alphas"},
      {"batch " + good + " --samples 1 --out {OUT}", "--samples"},
      {"solve {IN}/tri_report.json", "tri_report.json: net: a triangular net (a solve report?) is not read back"},
      // mu bounds the search's compressed scale cannot tell apart: the message gave its values, 0.999999998875 twice
      {"search-alpha " + good + " --parameter mu --objective thin_plate --lower 8e9 --upper 8.0000000000001e9",
       "command line: --lower/--upper: mu bounds 8000000000 and 8000000000.0001 are too close together"},
      // a bad value of an integer list is named alone (CLI11 quoted the whole list as one value)
      {"degree-limit " + good + " --degrees 8 12 16 9999999999",
       "command line: --degrees: '9999999999' is not an integer from -2147483648 to 2147483647"},
      {"study " + good + " --degrees 3 x4 --out {OUT}", "command line: --degrees: 'x4' is not an integer"},
      // an option nothing reads: --allow-indefinite relaxes a check of alpha only
      {"solve " + quoted(kData + "/boundaries/sphere_cap_ribbons.json") + " --mask c1-coons --allow-indefinite",
       "command line: --allow-indefinite: --allow-indefinite lets Cholesky-type solvers run"},
      {"export " + good + " --mask biharmonic --allow-indefinite --out {OUT}", "--allow-indefinite"},
      // a sides-form file gives its second ring as "ribbons" and has no "rings" field to blame
      {"sweep " + quoted(kData + "/boundaries/saddle_bump_ribbons.json") + " --out {OUT}",
       "saddle_bump_ribbons.json: ribbons: coons sweep works on the one-ring problem"},
      // view names the option at fault alone, not "--alphas/--samples/--from/--to"
      {"view " + good + " --samples 1 --out {OUT}/v.html", "command line: --samples: must be in [2, 257], not 1"},
      {"view " + good + " --three-js /dev/zero --out {OUT}/v.html", "/dev/zero: --three-js: is not a regular file"},
      {"study " + good + " --degrees 3 4 --shard 0/1 --out {IN}/shard_dev",
       "shard-0-of-1.jsonl: --out: exists and is not a regular file"},
      {"view " + good + " --alphas 1 --out {OUT}/v.html",
       "command line: --alphas: the number of frames must be in [2, 2001], not 1"},
      {"view " + good + " --from 0.1 --to -0.1 --out {OUT}/v.html", "command line: --from/--to: the interval must lie"},
      {"batch " + good + " " + corner + " --out {OUT}", "corner"},
      {"batch " + good + " --solver nonesuch --out {OUT}", "--solver"},
      {"batch " + good + " {IN}/missing.json --out {OUT}", "missing.json"},
      {"batch " + good + " --out {IN}/notafolder/out", "notafolder"},
      // an empty value is refused, not read as 0 (every command: registry.cpp)
      {"batch " + good + " --alphas '' --out {OUT}", "--alphas: an empty value"},
      {"search-alpha " + good + " --objective thin_plate --lower ''", "--lower: an empty value"},
      {"sweep " + good + " --count '' --out {OUT}", "--count: an empty value"},
      {"study " + good + " --degrees 3 '' --out {OUT}", "--degrees: an empty value"},
      // search-alpha
      {"search-alpha " + good + " --objective curvature", "--objective"},
      {"search-alpha " + good + " --objective '-1*thin_plate'", "--objective"},
      {"search-alpha " + good + " --objective thin_plate --lower -0.4", "--lower"},
      {"search-alpha " + good + " --objective thin_plate --upper 0.3", "--upper"},
      {"search-alpha " + pillow + " --objective target", "--target"},
      {"search-alpha " + good + " --objective target --target {IN}/nonexistent.json", "nonexistent.json"},
      {"search-alpha " + good + " --objective target --target sphere:0,0,x,1", "--target"},
      {"search-alpha " + good + " --objective target --target sphere:0,0,0", "--target"},
      {"search-alpha " + good + " --objective target --target plane:0,0,0,0,0,0", "--target"},
      {"search-alpha " + good + " --objective thin_plate --parameter beta", "--parameter"},
      {"search-alpha " + good + " --objective thin_plate --scan 1", "--scan"},
      {"search-alpha " + good + " --objective e3 --scan 100000000", "--scan"},  // ran for minutes, 7 GB
      {"search-alpha " + good + " --objective thin_plate --parameter mu --lower 5 --upper 1", "--lower"},
      {"search-alpha " + sphere5 + " --objective target", "target.sphere"},
      {"search-alpha " + target_list + " --objective target", "target"},
      {"search-alpha " + no_radius + " --objective target", "target.sphere.radius"},
      {"search-alpha " + neg_radius + " --objective target", "target.sphere.radius"},
      {"search-alpha " + cone + " --objective target", "target"},
      {"search-alpha " + good + " --objective thin_plate --target coons", "--target"},
      {"search-alpha " + good, "--objective"},
      // sweep
      {"sweep " + good + " --count 1 --out {OUT}", "--count"},
      {"sweep " + good + " --from 0.1 --to -0.1 --out {OUT}", "--from"},
      {"sweep " + good + " --from -0.3 --out {OUT}", "--from"},
      {"sweep " + good + " --parameter beta --out {OUT}", "--parameter"},
      {"sweep " + good + " --parameter mu --from -1 --out {OUT}", "--from"},
      {"sweep " + good + " --target sphere:1,2 --out {OUT}", "--target"},
      {"sweep " + good + " --samples 1 --out {OUT}", "--samples"},
      {"sweep " + pillow + " --samples 5 --out {OUT}", "--samples"},  // no target: the samples were ignored
      {"sweep " + quoted(kData + "/triangles/monkey_saddle.json") + " --samples 5 --out {OUT}", "--samples"},
      {"sweep " + sphere5 + " --out {OUT}", "target.sphere"},
      {"sweep " + good + " --solver nonesuch --out {OUT}", "--solver"},
      // study
      {"study " + good + " --degrees 1 3 --out {OUT}", "--degrees"},
      {"study " + good + " --degrees 3 300 --out {OUT}", "--degrees"},
      {"study " + good + " --degrees 6 4 --out {OUT}", "--degrees"},
      {"study {IN}/emptyfolder --out {OUT}", "emptyfolder: the folder holds no *.json boundary file"},
      {"study " + good + " " + corner + " --degrees 3 4 --out {OUT}", "corner"},
      {"study " + sphere5 + " --degrees 3 4 --out {OUT}", "target.sphere"},
      {"study " + curves_list + " --degrees 3 4 --out {OUT}", "curves"},
      {"study " + curves_gap + " --degrees 3 4 --out {OUT}", "corner"},
      {"study " + good + " --solver nonesuch --out {OUT}", "--solver"},
      // refit
      {"refit " + good + " --degree 0 0 --out {OUT}/r.json", "--degree"},
      {"refit " + pillow + " --degree 2 2 --out {OUT}/r.json", "curves"},
      {"refit " + good + " --degree 2001 3 --out {OUT}/r.json", "--degree"},
      {"refit {IN}/missing.json --degree 4 4 --out {OUT}/r.json", "missing.json"},
      {"refit " + sphere5 + " --degree 4 4 --out {OUT}/r.json", "target.sphere"},
      {"refit " + curves_gap + " --degree 4 4 --out {OUT}/r.json", "corner"},
      {"refit " + good + " --degree 4", "--degree"},
      // an output path through a regular file, or a name longer than a file name may be, named by
      // its option (they were "cannot create the file: Not a directory" and "File name too long")
      {"refit " + good + " --degree 4 4 --out {IN}/broken.json/sub/x.json", "broken.json' is a file, not a folder"},
      {"refit " + good + " --degree 4 4 --out {OUT}/" + std::string(300, 'x') + ".json",
       "command line: --out: the file name is 305 bytes long"},
      {"surface " + surface + " --obj {IN}/broken.json/s.obj", "broken.json' is a file, not a folder"},
      // surface
      {"surface " + surface + " --samples 1 --obj {OUT}/s.obj", "--samples"},
      {"surface " + surface + " --fit-degree 0 --obj {OUT}/s.obj", "--fit-degree"},
      {"surface {IN}/badtype.json --obj {OUT}/s.obj", "type"},
      {"surface {IN}/nocorners.json --obj {OUT}/s.obj", "corners"},
      {"surface " + surface + " --obj {OUT}/missing/s.obj", "--obj"},
      {"surface {IN}/missing.json --obj {OUT}/s.obj", "missing.json"},
      {"surface " + surface + " --sample 100000 --obj {OUT}/s.obj", "--samples"},
      {"surface {IN}/ruled3000.json --max-memory 10MB --obj {OUT}/s.obj",
       "ruled3000.json: curves[1]: the exact energies of its 3001 by 2 Bezier net needs about"},
      {"surface " + surface + " --reference {IN}/broken.json --obj {OUT}/s.obj", "broken.json"},
      // join
      {"join " + surface + " middle " + surface_b + " left", "FIRST_SIDE"},
      {"join " + surface + " right " + surface_b + " left --samples 1", "--samples"},
      {"join {IN}/missing.json right " + surface_b + " left", "missing.json"},
      {"join {IN}/broken.json right " + surface_b + " left", "broken.json"},
      {"join {IN}/tiny.json right {IN}/tiny.json left",
       "tiny.json: corners[1]: the largest coordinate magnitude of the model is 1e-170, below 1e-60"},
      {"surface {IN}/tiny.json --obj {OUT}/s.obj", "tiny.json: corners[1]: the largest coordinate magnitude"},
      // degree-limit
      {"degree-limit {IN}/broken.json", "broken.json"},
      {"degree-limit " + good + " --degrees 8 4", "--degrees"},
      {"degree-limit " + good + " --objective target", "--objective"},
      {"solve {IN}/tall.json --mask file:{IN}/stencil_dip.json --solver eigen-lu", "singular"},
      // fast5 solves the C1 masks, so the reason is the search's need of a matrix, not "3x3 only"
      {"search-alpha " + quoted(kData + "/boundaries/sphere_cap_ribbons.json") +
           " --parameter weight --objective e3 --solver fast5",
       "works from the grid stencil only; the search refills"},
      // a backend that does not solve the 3x3 alpha family, refused by every search command before
      // any search (separable-banded takes alpha = -1/4 only; the sine-basis evaluator would answer
      // under its name)
      {"sweep " + good + " --solver separable-banded --out {OUT}/w", "separable-banded does not solve the 3x3 alpha"},
      {"view " + good + " --solver separable-banded --out {OUT}/v.html", "separable-banded does not solve the 3x3"},
      {"study " + good + " --degrees 3 --solver separable-banded --out {OUT}/s",
       "separable-banded does not solve the 3x3 alpha family"},
      {"study " + good + " --degrees 3 --solver separable-banded --shard 1/2 --out {OUT}/s",
       "separable-banded does not solve the 3x3 alpha family"},
      {"study --family random-smooth --count 2 --degrees 3 --solver separable-banded --out {OUT}/s",
       "separable-banded does not solve the 3x3 alpha family"},
      {"degree-limit " + good + " --degrees 3 4 --solver separable-banded",
       "separable-banded does not solve the 3x3 alpha family"},
      // --corner-tolerance is checked by every command that reads boundaries (nan and inf were
      // taken by study, degree-limit and surface)
      {"study " + good + " --degrees 3 --corner-tolerance nan --out {OUT}/s", "--corner-tolerance"},
      {"degree-limit " + good + " --degrees 3 4 --corner-tolerance inf", "--corner-tolerance"},
      {"surface " + surface + " --corner-tolerance inf", "--corner-tolerance"},
      {"surface " + surface + " --derivative-tolerance inf", "--derivative-tolerance"},
      // two outputs that are one file under two spellings (the second used to overwrite the first)
      {"surface " + surface + " --obj {OUT}/x.obj --ply {OUT}/./x.obj", "same name"},
      {"export " + good + " --out {OUT} --step {OUT}/d.step --iges {OUT}/../out/d.step",
       COONS_HAVE_OCCT ? "same file" : "OpenCASCADE"},
      // --samples without a target term, on a triangle as on a rectangle (it was ignored)
      {"search-alpha " + quoted(kData + "/triangles/sphere_octant.json") + " --objective thin_plate --samples 5",
       "--samples"},
      // a file of another kind names its "type" (it said "bottom: missing")
      {"refit " + quoted(kData + "/triangles/sphere_octant.json") + " --degree 5 6", "type"},
      {"degree-limit " + quoted(kData + "/triangles/sphere_octant.json"), "type"},
      {"batch " + quoted(kData + "/triangles/sphere_octant.json") + " --out {OUT}", "type"},
      {"solve " + surface, "type"},
      // a mu bound the compressed scale cannot resolve (1e19 came back as mu: null, success)
      {"search-alpha " + good + " --objective dirichlet --parameter mu --upper 1e19", "--upper"},
      // solver options are blamed on their option (they said "solver options")
      {"solve " + good + " --solver gauss-seidel --omega 0", "--omega"},
      {"solve " + good + " --solver cg --tolerance 0", "--tolerance"},
      {"solve " + good + " --solver cg --max-iterations -1", "--max-iterations"},
      {"solve " + good + " --solver cg --time-limit -1", "--time-limit: must be finite and >= 0"},
      {"solve " + good + " --solver cg --time-limit nan", "--time-limit: must be finite and >= 0"},
      {"solve " + good + " --solver eigen-lu --time-limit 1", "--time-limit: --time-limit is a stopping rule"},
      {"solve " + good + " --method coons --time-limit 1", "--time-limit does not apply"},
      {"solve " + quoted(kData + "/triangles/sphere_octant.json") + " --solver cg --tolerance 2", "--tolerance"},
      // target samples beyond the memory limit (1e10 of them ran out of memory: exit 1)
      {"search-alpha " + good + " --objective target --samples 100000", "--samples"},
      {"sweep " + good + " --samples 100000 --out {OUT}", "--samples"},
      {"search-alpha " + quoted(kData + "/triangles/sphere_octant.json") + " --objective target --samples 100000",
       "--samples"},
      {"sweep " + quoted(kData + "/triangles/sphere_octant.json") + " --samples 100000 --out {OUT}", "--samples"},
      // the option at fault is named: --samples, not the triangle's degree; --face, not --edges
      {"export " + quoted(kData + "/triangles/sphere_octant.json") + " --samples 1000000 --out {OUT}", "--samples"},
      {"import-step {IN}/missing.step --face -2 --out {OUT}/b.json", COONS_HAVE_OCCT ? "--face" : "OpenCASCADE"},
      // -1 is also the "not given" of the import options: it was blamed on --edges
      {"import-step {IN}/missing.step --face -1 --out {OUT}/b.json",
       COONS_HAVE_OCCT ? "--face: must be >= 0" : "OpenCASCADE"},
      // a triangle has no STEP/IGES surface (--step was ignored)
      {"export " + quoted(kData + "/triangles/sphere_octant.json") + " --out {OUT} --step {OUT}/t.step", "--step"},
      // an output named by the user that is a folder: --force cannot replace it (it said "give --force")
      {"view " + good + " --out {OUT}", "--out: is a folder"},
      {"refit " + good + " --degree 4 4 --out {OUT}", "--out: is a folder"},
      {"surface " + surface + " --obj {OUT}", "--obj: is a folder"},
      {"export " + good + " --out {OUT} --step {OUT}", COONS_HAVE_OCCT ? "--step: is a folder" : "OpenCASCADE"},
      // view (checks of the command line come before three.js is read: the same errors without it)
      {"view " + good + " --out {OUT}/missing/page.html", "--out"},
      // bench-matrix
      {"bench-matrix {IN}/missing.mtx", "missing.mtx"},
      {"bench-matrix {IN}/broken.json", "broken.json"},
      // the shared check of solver options names the option (all but --tolerance were --max-iterations)
      {"bench-matrix {IN}/a.mtx --tolerance 2", "--tolerance: must lie in (0, 1)"},
      {"bench-matrix {IN}/a.mtx --max-iterations -1", "--max-iterations: must be >= 0"},
      // import-step (without OpenCASCADE every use says it is not built)
      {"import-step {IN}/missing.step --face 0 --out {OUT}/b.json", COONS_HAVE_OCCT ? "missing.step" : "OpenCASCADE"},
      // the import's options, checked before the file is read, each naming its option (CLI11
      // itself counts the edges and keeps --face and --edges apart)
      {"import-step {IN}/missing.step --edges 0,1,2 --out {OUT}/b.json",
       "command line: --edges: At least 4 required"},  // (CLI11's, with or without OpenCASCADE)
      {"import-step {IN}/missing.step --edges 0,1,2,2 --out {OUT}/b.json",
       COONS_HAVE_OCCT ? "command line: --edges: the 4 indices must differ" : "OpenCASCADE"},
      {"import-step {IN}/missing.step --face 0 --edges 0,1,2,3 --out {OUT}/b.json",
       "command line: --face excludes --edges"},
      {"import-step {IN}/missing.step --out {OUT}/b.json",
       COONS_HAVE_OCCT ? "command line: --face/--edges: give exactly one of --face K and --edges a,b,c,d"
                       : "OpenCASCADE"},
      {"import-step {IN}/missing.step --face 0 --gap-tolerance -1 --out {OUT}/b.json",
       COONS_HAVE_OCCT ? "command line: --gap-tolerance: must be finite and >= 0" : "OpenCASCADE"},
      // a single output file in a folder that does not exist names its option and the folder (they
      // named the file: "cannot create the file")
      {"import-step " + quoted(kData + "/cad/four_edges.step") + " --face 0 --out {OUT}/missing/b.json",
       COONS_HAVE_OCCT ? "command line: --out: the folder" : "OpenCASCADE"},
      {"export " + good + " --out {OUT} --step {OUT}/missing/d.step",
       COONS_HAVE_OCCT ? "command line: --step: the folder" : "OpenCASCADE"},
      {"export " + good + " --out {OUT} --iges {OUT}/missing/d.igs",
       COONS_HAVE_OCCT ? "command line: --iges: the folder" : "OpenCASCADE"},
      // the family study names the option of the member at fault (all were blamed on --family)
      {"study --family perturbed:" + quoted(kData + "/boundaries/dome.json") + " --amplitude 2 --out {OUT}/s",
       "command line: --amplitude: the amplitude must be in [0, 1], not 2"},
      {"study --family random-smooth --count 0 --out {OUT}/s", "command line: --count: the count must be in"},
      {"study --family perturbed:{IN}/degree10.json --out {OUT}/s",
       "command line: --degrees: degree 3 is outside [10, 200] (the sides have degree 10) (the default degrees: "
       "give --degrees)"},
      // a number with a stray x is no number; only 0x is hexadecimal (it said "hexadecimal" for both)
      {"solve " + good + " --alpha 0.1x", "command line: --alpha: '0.1x' is not a number"},
      // no command, unknown command
      {"frobnicate", "frobnicate"},
      {"", "command"},
  };
  REQUIRE(cases.size() >= 60);
  std::map<std::string, int> per_command;
  for (const Case& c : cases) {
    TempDir out_dir;
    const std::string out = (out_dir.path / "out").string();
    fs::create_directories(out);  // an existing, empty output folder: nothing may appear in it
    const std::string args = replace_all(replace_all(c.args, "{OUT}", out), "{IN}", inputs.path.string());
    INFO("coons " << args);
    const CommandResult r = run_command(std::string(kCoons).append(" ").append(args));
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    // "error: FILE: FIELD: reason" (or "error: command line: ..."): at least file and reason
    CHECK(std::count(r.err.begin(), r.err.end(), ':') >= 2);
    CHECK_THAT(r.err, Catch::Contains(c.mention));
    CHECK(fs::is_empty(out));
    CHECK(std::distance(fs::directory_iterator(out_dir.path), fs::directory_iterator()) == 1);
    ++per_command[c.args.substr(0, c.args.find(' '))];
  }
  for (const std::string& command : coons_commands()) {
    INFO(command);
    CHECK(per_command[command] >= 1);
  }
}
