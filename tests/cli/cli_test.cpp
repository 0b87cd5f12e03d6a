// The command-line contract of docs/formats.md, driven through the real binary.
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "coons/alpha/family_search.h"
#include "coons/config.h"
#include "coons/io/boundary_io.h"
#include "coons/io/net_json.h"
#include "coons/net/coons_net.h"
#include "solvers/registry.h"
#include "support/cli_support.h"

using namespace coons;
using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

TEST_CASE("coons solve: the report of docs/formats.md, numbers that read back exactly", "[cli]") {
  const std::string file = kData + "/boundaries/dome.json";
  const CommandResult r = run_coons("solve " + quoted(file) + " --alpha -0.2 --solver eigen-ldlt");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["boundary"] == "dome");
  CHECK(report["degree"] == json::array({3, 3}));
  CHECK(report["method"] == "alpha");
  CHECK(report["alpha"] == -0.2);
  CHECK(report["beta"].get<double>() == 0.25 - (-0.2));
  CHECK(report["solver"]["name"] == "eigen-ldlt");
  CHECK(!report["solver"].contains("picked_by"));
  CHECK(report["solver"]["status"] == "success");
  for (const char* key : {"analyze", "factorize", "solve"}) CHECK(report["solver"]["seconds"].contains(key));
  for (const char* key : {"twist_energy", "thin_plate_energy", "dirichlet_energy", "e3_energy", "discrete_twist_energy",
                          "discrete_dirichlet_energy", "mask_residual"})
    CHECK(report["metrics"][key].is_number());
  CHECK(report["metrics"]["thin_plate_energy"].get<double>() == Approx(18.320).margin(5e-4));
  CHECK(report["net"].size() == 4);
  CHECK(report["net"][0].size() == 4);
}

TEST_CASE("coons solve: the closed-form Coons net is printed bit-exactly", "[cli]") {
  const std::string file = kData + "/boundaries/helicoid.json";
  const CommandResult r = run_coons("solve " + quoted(file) + " --method coons");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  const ControlNet expected = discrete_coons_net(read_boundary_file(file).boundary);
  CHECK(net_of(report).points == expected.points);
  CHECK(report["solver"]["status"] == "not_applicable");
}

TEST_CASE("coons solvers: lists eigen-ldlt, as lines and as JSON", "[cli]") {
  const CommandResult lines = run_coons("solvers");
  REQUIRE(lines.status == 0);
  CHECK_THAT(lines.out, Catch::Contains("eigen-ldlt\n"));
  const CommandResult js = run_coons("solvers --json");
  REQUIRE(js.status == 0);
  const json names = json::parse(js.out);
  CHECK(std::find(names.begin(), names.end(), "eigen-ldlt") != names.end());
}

TEST_CASE("coons: --help works on every command", "[cli]") {
  std::vector<std::string> commands = {""};
  for (const std::string& name : coons_commands()) commands.push_back(" " + name);
  for (const std::string& cmd : commands) {
    const CommandResult r = run_command(kCoons + cmd + " --help");
    INFO(cmd);
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("Usage"));
  }
}

TEST_CASE("coons solve: each bad input gives exit 2, one error line and no output", "[cli]") {
  TempDir dir;
  const json good = json::parse(std::ifstream(kData + "/boundaries/dome.json"));
  auto variant = [&](const std::string& name, const std::function<void(json&)>& edit) {
    json doc = good;
    edit(doc);
    return dir.write(name, doc.dump());
  };
  struct Case {
    std::string what, args, must_mention;
  };
  const std::string dome = kData + "/boundaries/dome.json";
  const std::vector<Case> cases = {
      {"unreadable file", quoted((dir.path / "missing.json").string()), "missing.json"},
      {"malformed JSON", quoted(dir.write("broken.json", "{\"bottom\": [[0,0,0],")), "malformed JSON"},
      {"missing field", quoted(variant("nofield.json", [](json& d) { d.erase("top"); })), "top"},
      {"extra-length field",
       quoted(variant("long.json",
                      [](json& d) {
                        d["left"].push_back({-1, 1, 0});
                      })),
       "right"},
      {"point with 4 numbers",
       quoted(variant("four.json",
                      [](json& d) {
                        d["bottom"][1] = {1, 2, 3, 4};
                      })),
       "bottom[1]"},
      {"non-finite number",
       quoted(dir.write("inf.json",
                        "{\"bottom\":[[0,0,0],[1e999,0,0]],\"top\":[[0,1,0],[1,1,0]],\"left\":[[0,0,0],[0,1,0]],"
                        "\"right\":[[1,0,0],[1,1,0]]}")),
       "inf.json"},
      {"corners disagree", quoted(variant("corner.json", [](json& d) { d["right"][0][2] = 0.5; })),
       "bottom-right corner"},
      {"degree disagrees",
       quoted(variant("degree.json",
                      [](json& d) {
                        d["degree"] = {4, 3};
                      })),
       "degree"},
      {"degree too small for hermite-coons",
       quoted(kData + "/boundaries/seed_example1.json") + " --method hermite-coons", "degree"},
      {"alpha outside the definite range", quoted(dome) + " --alpha -0.4 --solver eigen-ldlt", "--alpha"},
      {"unknown solver", quoted(dome) + " --solver nonesuch", "--solver"},
      {"unknown method", quoted(dome) + " --method nonesuch", "--method"},
      {"unknown option", quoted(dome) + " --frobnicate", "frobnicate"},
      {"SOR factor out of range", quoted(dome) + " --solver gauss-seidel --omega 2.5", "omega"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    const CommandResult r = run_coons("solve " + c.args);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::Contains(c.must_mention));
  }
  // export writes nothing when the input is bad
  const std::string out = (dir.path / "out").string();
  const CommandResult r = run_coons("export " + quoted(variant("corner2.json", [](json& d) { d["top"][0][0] = 7; })) +
                                    " --out " + quoted(out));
  CHECK(r.status == 2);
  CHECK(!fs::exists(out));
}

TEST_CASE("coons export: OBJ files and a Matrix Market system", "[cli]") {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const CommandResult r = run_coons("export " + quoted(kData + "/boundaries/pillow.json") +
                                    " --alpha -0.1 --samples 9 --out " + quoted(out));
  REQUIRE(r.status == 0);
  for (const char* f : {"pillow.surface.obj", "pillow.net.obj", "pillow.A.mtx", "pillow.B.mtx"})
    CHECK(fs::exists(fs::path(out) / f));
  std::ifstream obj(fs::path(out) / "pillow.surface.obj");
  int vertices = 0, faces = 0;
  for (std::string line; std::getline(obj, line);) {
    vertices += line.rfind("v ", 0) == 0;
    faces += line.rfind("f ", 0) == 0;
  }
  CHECK(vertices == 81);
  CHECK(faces == 2 * 8 * 8);
}

TEST_CASE("coons batch: nets, OBJ files and a metrics table for every boundary", "[cli]") {
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const CommandResult r = run_coons("batch " + quoted(kData + "/boundaries/dome.json") + " " +
                                    quoted(kData + "/boundaries/saddle.json") + " --samples 5 --out " + quoted(out));
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("dome"));
  CHECK(fs::exists(fs::path(out) / "metrics.md"));
  for (const char* f : {"dome-3x3/coons.json", "dome-3x3/alpha-0.25.json", "dome-3x3/alpha-0.1.json",
                        "dome-3x3/alpha+0.json", "saddle-3x3/coons.surface.obj", "saddle-3x3/alpha-0.1.net.obj"})
    CHECK(fs::exists(fs::path(out) / f));
}

TEST_CASE("coons batch: a folder entry *.json that is no regular file is named, not waited on", "[cli][bad-input]") {
  // a FIFO named incoming.json beside a boundary blocked the run forever waiting for a writer
  // (`timeout 10` makes a regression fail instead of hang)
  const TempDir dir;
  const std::filesystem::path folder = dir.path / "in";
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(kData + "/boundaries/dome.json", folder / "dome.json");
  REQUIRE(mkfifo((folder / "incoming.json").c_str(), 0600) == 0);
  const CommandResult r =
      run_command("timeout 10 " + kCoons + " batch " + quoted(folder.string()) + " --out " + quoted(dir.file("out")));
  INFO(r.err);
  CHECK(r.status == 2);
  CHECK(r.err == "error: " + (folder / "incoming.json").string() +
                     ": is not a regular file (a folder given as input is read for its regular *.json files)\n");
  CHECK_FALSE(std::filesystem::exists(dir.file("out")));
}

TEST_CASE("coons batch: the table tells two files of one name apart and a name cannot break a row", "[cli]") {
  // Two files named "dome" gave rows that could not be told apart, a '|' in a name added a column,
  // an alpha of 7 characters pushed its row out of line, and the title said "bundled" of any file.
  TempDir dir;
  std::string text = read_text(kData + "/boundaries/dome.json");
  const std::string a = dir.write("a.json", text);
  const std::string b = dir.write("b.json", text);
  const auto name_at = text.find("\"dome\"");
  REQUIRE(name_at != std::string::npos);
  text.replace(name_at, 6, "\"we|ird\"");
  const std::string c = dir.write("c.json", text);
  const std::string out = dir.file("out");
  const CommandResult r = run_coons("batch " + quoted(a) + " " + quoted(b) + " " + quoted(c) +
                                    " --alphas -0.25 -0.1004 --samples 3 --out " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string table = read_text(out + "/metrics.md");
  INFO(table);
  CHECK_THAT(table, Catch::StartsWith("# coons batch: metrics of every boundary given"));
  CHECK_THAT(table, Catch::Contains("| dome (dome-3x3) ") && Catch::Contains("| dome (dome-3x3-2) "));
  CHECK_THAT(table, Catch::Contains("| we\\|ird "));
  // every row has the header's 12 unescaped bars, at the same places
  std::istringstream lines(table.substr(table.find("| boundary")));
  std::string line, header;
  std::getline(lines, header);
  std::vector<std::size_t> bars;
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == '|') bars.push_back(i);
  CHECK(bars.size() == 12);
  int rows = 0;
  while (std::getline(lines, line)) {
    INFO(line);
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < line.size(); ++i)
      if (line[i] == '|' && (i == 0 || line[i - 1] != '\\')) at.push_back(i);
    CHECK(at == bars);
    ++rows;
  }
  CHECK(rows == 1 + 3 * 3);  // the separator and three nets of each file
}

TEST_CASE("coons batch: a name of wide characters keeps the table's columns in line", "[cli]") {
  // The width of a cell was its number of code points, so a row named in CJK characters (two
  // columns each on a terminal) pushed every bar after the name out of line.
  TempDir dir;
  std::string text = read_text(kData + "/boundaries/dome.json");
  const auto name_at = text.find("\"dome\"");
  REQUIRE(name_at != std::string::npos);
  text.replace(name_at, 6, "\"\u5706\u9876\"");  // 圆顶: 6 bytes of UTF-8, 4 columns
  const std::string wide = dir.write("wide.json", text);
  const std::string out = dir.file("out");
  const CommandResult r = run_coons("batch " + quoted(wide) + " --alphas -0.1 --samples 3 --out " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::string table = read_text(out + "/metrics.md");
  INFO(table);
  std::istringstream lines(table.substr(table.find("| boundary")));
  std::string line, header;
  std::getline(lines, header);
  const auto bars_of = [](const std::string& l, std::size_t shift_after_name) {
    std::vector<std::size_t> at;
    for (std::size_t i = 0; i < l.size(); ++i)
      if (l[i] == '|') at.push_back(at.empty() ? i : i - shift_after_name);
    return at;
  };
  const std::vector<std::size_t> bars = bars_of(header, 0);
  REQUIRE(bars.size() == 12);
  int named = 0;
  while (std::getline(lines, line)) {
    INFO(line);
    const bool is_wide = line.find("\u5706\u9876") != std::string::npos;
    named += is_wide ? 1 : 0;
    // in bytes, the bars after the name sit 2 further right than in columns
    CHECK(bars_of(line, is_wide ? 2 : 0) == bars);
  }
  CHECK(named == 2);  // the Coons net and alpha = -0.1
}

TEST_CASE("coons batch: the bundled folder, its B-spline boundary included, as solve gives each net", "[cli]") {
  // `coons batch data/boundaries` (the README's example) stopped at bspline_wave.json: "a B-spline
  // boundary is read by solve, export, search-alpha and study only"; and --threads was refused
  TempDir dir;
  const std::string out = (dir.path / "out").string();
  const CommandResult r =
      run_coons("batch " + quoted(kData + "/boundaries") + " --samples 5 --threads 2 --out " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 0);
  for (const char* f :
       {"bspline_wave-7x6/coons.json", "bspline_wave-7x6/alpha-0.1.json", "bspline_wave-7x6/alpha-0.1.surface.obj",
        "bspline_wave-7x6/coons.net.obj", "dome-3x3/alpha-0.1.json"})
    CHECK(fs::exists(fs::path(out) / f));
  for (const auto& [file, arguments] :
       {std::pair{"bspline_wave-7x6/alpha-0.1.json", "/boundaries/bspline_wave.json --alpha -0.1"},
        std::pair{"bspline_wave-7x6/coons.json", "/boundaries/bspline_wave.json --method coons"},
        std::pair{"dome-3x3/alpha-0.1.json", "/boundaries/dome.json --alpha -0.1"}}) {
    INFO(file);
    std::ifstream in(fs::path(out) / file);
    const json batched = json::parse(in);
    const CommandResult solved = run_coons("solve " + kData + arguments);
    REQUIRE(solved.status == 0);
    const json single = json::parse(solved.out);
    CHECK(batched["net"] == single["net"]);
    CHECK(batched["metrics"] == single["metrics"]);
  }
  std::ifstream table(fs::path(out) / "metrics.md");
  const std::string md((std::istreambuf_iterator<char>(table)), std::istreambuf_iterator<char>());
  CHECK(md.find("| bspline_wave           |     7x6 | alpha (B-spline) |   -0.1 |") != std::string::npos);
}

TEST_CASE("coons solve: every kind of boundary reports read, solve, metrics and write seconds", "[cli]") {
  // the mask, free-set and triangle reports used to close their timing before printing: no "write"
  for (const std::string& arguments :
       {quoted(kData + "/boundaries/dome.json"), quoted(kData + "/boundaries/bspline_wave.json"),
        quoted(kData + "/boundaries/sphere_cap_ribbons.json") + " --mask c1-family --weight 0.5",
        quoted(kData + "/free_sets/l_hole.json"), quoted(kData + "/triangles/sphere_octant.json")}) {
    const CommandResult r = run_coons("solve " + arguments);
    INFO(arguments << "\n" << r.err);
    REQUIRE(r.status == 0);
    const json report = json::parse(r.out);
    for (const char* phase : {"read", "solve", "metrics", "write"}) {
      INFO(phase);
      REQUIRE(report["timing"].contains(phase));
      CHECK(report["timing"][phase].get<double>() >= 0);
    }
  }
}

TEST_CASE("coons solve: a boundary from a pipe gives the net of the same file", "[cli]") {
  // the input is read twice (is it a triangle? then the reader): the second read of a pipe was
  // empty ("malformed JSON at byte 1"), and a FIFO's waited for a writer forever
  for (const char* file : {"/boundaries/dome.json", "/triangles/sphere_octant.json"}) {
    const std::string path = quoted(kData + file);
    const CommandResult direct = run_coons("solve " + path);
    const CommandResult piped = run_command(fmt::format("(cat {} | {} solve /dev/stdin)", path, kCoons));
    INFO(file << "\n" << piped.err);
    REQUIRE(direct.status == 0);
    REQUIRE(piped.status == 0);
    CHECK(json::parse(piped.out)["net"] == json::parse(direct.out)["net"]);
  }
}

TEST_CASE("coons search-alpha: the report of docs/formats.md", "[cli][alpha]") {
  const CommandResult r =
      run_coons("search-alpha " + quoted(kData + "/boundaries/dome.json") + " --objective thin_plate");
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  for (const char* key : {"boundary", "degree", "objective", "alpha", "mu", "value", "bounds", "flat", "at_bound",
                          "evaluations", "status"})
    CHECK(report.contains(key));
  CHECK(report["status"] == "success");
  CHECK(report["bounds"] == json::array({-0.25, 0.25}));
  CHECK(report["alpha"].get<double>() > -0.25);
  CHECK(report["alpha"].get<double>() < 0);
  // μ of α at degree n: α = −n²/(4(n² + μ))
  const double alpha = report["alpha"], mu = report["mu"];
  CHECK(alpha == Approx(-9.0 / (4 * (9 + mu))).epsilon(1e-12));
  // μ is searched on a compressed scale; its bounds are reported as given, to the last digit
  for (const auto& [options, bounds] :
       {std::pair{std::string(), json::array({0.0, 9000.0})},
        std::pair{std::string(" --lower 0.3 --upper 7777.7"), json::array({0.3, 7777.7})}}) {
    const CommandResult by_mu = run_coons(fmt::format("search-alpha {} --objective thin_plate --parameter mu{}",
                                                      quoted(kData + "/boundaries/dome.json"), options));
    REQUIRE(by_mu.status == 0);
    CHECK(json::parse(by_mu.out)["bounds"] == bounds);  // the dome is 3 by 3: 1000·m·n = 9000
  }
  const CommandResult flat = run_command(
      kCoons + " search-alpha " + quoted(kData + "/boundaries/sixteen_vector_twist.json").append(" --objective e3"));
  REQUIRE(flat.status == 0);
  CHECK(json::parse(flat.out)["flat"] == true);
  CHECK(json::parse(flat.out)["alpha"].is_null());
}

TEST_CASE("coons search-alpha --parameter mu: every mu printed lies within the bounds, which end the scan exactly",
          "[cli][alpha]") {
  // mn·s/(1 − s) of the compressed scale rounds: on a 3×7 net the upper bound 21000 came back as the
  // optimum 21000.000000000713 and as the scan's last point, beyond the bounds printed beside them
  TempDir dir;
  json net = json::array();
  for (int i = 0; i <= 3; ++i) {
    json row = json::array();
    for (int j = 0; j <= 7; ++j) {
      const double u = i / 3.0, v = j / 7.0;
      row.push_back({u + 0.1 * v * v, v - 0.2 * u * u, 0.3 * std::sin(3 * u + 1) * std::cos(2 * v) + 0.1 * u * v});
    }
    net.push_back(row);
  }
  const std::string file = quoted(dir.write("wide.json", json{{"name", "wide"}, {"net", net}}.dump()));
  for (const std::string options : {"", " --upper 777.7", " --lower 0.3 --upper 5"}) {
    for (const char* objective : {"thin_plate", "dirichlet", "twist"}) {
      const CommandResult r =
          run_coons(fmt::format("search-alpha {} --parameter mu --objective {}{}", file, objective, options));
      INFO(objective << options << ": " << r.err);
      REQUIRE(r.status == 0);
      const json report = json::parse(r.out);
      const double lower = report["bounds"][0], upper = report["bounds"][1];
      CHECK(report["scan"].front()[0].get<double>() == lower);
      CHECK(report["scan"].back()[0].get<double>() == upper);
      for (const auto& point : report["scan"]) {
        CHECK(point[0].get<double>() >= lower);
        CHECK(point[0].get<double>() <= upper);
      }
      if (!report["mu"].is_null()) {
        CHECK(report["mu"].get<double>() >= lower);
        CHECK(report["mu"].get<double>() <= upper);
      }
    }
  }
}

TEST_CASE("coons search-alpha: bad input gives exit 2 and one error line", "[cli][alpha]") {
  const std::string dome = quoted(kData + "/boundaries/dome.json");
  const std::pair<std::string, std::string> cases[] = {
      {dome + " --objective curvature", "--objective"},
      {dome + " --objective thin_plate --lower -0.4", "--lower"},
      {dome + " --objective thin_plate --upper 0.3", "--upper"},
      {quoted(kData + "/boundaries/pillow.json") + " --objective target", "--target"},
      {dome + " --objective target --target /nonexistent/net.json", "net.json"},
      {dome + " --objective target --target sphere:0,0,x,1", "--target"},
      {dome + " --objective thin_plate --parameter beta", "--parameter"},
  };
  for (const auto& [args, mention] : cases) {
    INFO(args);
    const CommandResult r = run_command(std::string(kCoons).append(" search-alpha ").append(args));
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK_THAT(r.err, Catch::Contains(mention));
  }
  // an explicit flag accepts indefinite bounds
  const CommandResult wide =
      run_coons("search-alpha " + dome + " --objective thin_plate --lower -0.3 --allow-indefinite --solver eigen-lu");
  CHECK(wide.status == 0);
}

TEST_CASE("coons search-alpha --parameter weight: the C1 family on two data rings, one ring is bad input",
          "[cli][alpha]") {
  TempDir dir;
  const ControlNet net = make_random_net(7, 6, 12);
  json doc = {{"name", "two rings"}, {"net", net_to_json(net)}, {"rings", 2}};
  const std::string two = dir.write("two.json", doc.dump());
  const CommandResult r =
      run_coons("search-alpha " + quoted(two) + " --objective e3 --parameter weight --solver eigen-ldlt");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  CHECK(report["parameter"] == "weight");
  CHECK(report["mask"] == "c1-family");
  CHECK(report["bounds"] == json::array({0.0, 1.0}));
  for (const char* key : {"weight", "value", "flat", "at_bound", "evaluations", "solves", "status", "scan", "evaluator",
                          "failed_evaluations", "failed_intervals", "solver", "timing"})
    CHECK(report.contains(key));
  // the contract's fields of every search report are there, null: the search is not over α
  CHECK(report.at("alpha").is_null());
  CHECK(report.at("mu").is_null());
  CHECK_FALSE(report.contains("beta"));
  // the library's search on the same problem, the same answer
  std::string why;
  const AlphaSearchSummary s =
      search_weight(rings_problem(net, 2), *parse_objective("e3", &why), backend("eigen-ldlt"));
  REQUIRE(report["status"] == to_string(s.status));
  if (s.parameter)
    CHECK(report["weight"].get<double>() == Approx(*s.parameter).margin(1e-12));
  else
    CHECK(report["weight"].is_null());
  CHECK(report["value"].get<double>() == Approx(s.value).epsilon(1e-12));

  // the same two rings as sides with "ribbons": the same search
  json with_ribbons = boundary_to_json(boundary_of(net));
  auto column = [&](int j) {
    json c = json::array();
    for (int i = 0; i <= net.m; ++i) c.push_back({net.at(i, j)(0), net.at(i, j)(1), net.at(i, j)(2)});
    return c;
  };
  auto row = [&](int i) {
    json c = json::array();
    for (int j = 0; j <= net.n; ++j) c.push_back({net.at(i, j)(0), net.at(i, j)(1), net.at(i, j)(2)});
    return c;
  };
  with_ribbons["ribbons"] = {
      {"bottom", column(1)}, {"top", column(net.n - 1)}, {"left", row(1)}, {"right", row(net.m - 1)}};
  const std::string ribbons = dir.write("ribbons.json", with_ribbons.dump());
  const CommandResult rr =
      run_coons("search-alpha " + quoted(ribbons) + " --objective e3 --parameter weight --solver eigen-ldlt");
  INFO(rr.err);
  REQUIRE(rr.status == 0);
  const json by_ribbons = json::parse(rr.out);
  CHECK(by_ribbons["status"] == report["status"]);
  CHECK(by_ribbons["weight"] == report["weight"]);
  CHECK(by_ribbons["value"].get<double>() == Approx(report["value"].get<double>()).epsilon(1e-12));

  // one ring: bad input naming the field
  doc["rings"] = 1;
  const std::string one = dir.write("one.json", doc.dump());
  const std::string sides = quoted(kData + "/boundaries/dome.json");
  const std::pair<std::string, std::string> cases[] = {
      {quoted(one) + " --objective e3 --parameter weight", "rings"},
      {sides + " --objective e3 --parameter weight", "ribbons"},
      {quoted(two) + " --objective e3 --parameter weight --upper 1.5", "--upper"},
      {quoted(two) + " --objective e3 --parameter weight --solver gauss-seidel", "--solver"},
  };
  for (const auto& [args, mention] : cases) {
    INFO(args);
    const CommandResult bad = run_command(std::string(kCoons).append(" search-alpha ").append(args));
    CHECK(bad.status == 2);
    CHECK(bad.out.empty());
    CHECK(bad.err.rfind("error: ", 0) == 0);
    CHECK(std::count(bad.err.begin(), bad.err.end(), '\n') == 1);
    CHECK_THAT(bad.err, Catch::Contains(mention));
  }
}

TEST_CASE("coons sweep: one JSON line per alpha with every metric, and a plot", "[cli][alpha]") {
  TempDir dir;
  const std::string out = (dir.path / "sweep").string();
  const CommandResult r =
      run_coons("sweep " + quoted(kData + "/boundaries/dome.json") + " --count 11 --out " + quoted(out));
  REQUIRE(r.status == 0);
  std::ifstream in(fs::path(out) / "dome.sweep-alpha.jsonl");
  int lines = 0;
  for (std::string line; std::getline(in, line); ++lines) {
    const json j = json::parse(line);
    for (const char* key : {"alpha", "beta", "mu", "twist_energy", "thin_plate_energy", "dirichlet_energy", "e3_energy",
                            "discrete_twist_energy", "discrete_dirichlet_energy", "mask_residual", "rms_target"})
      CHECK(j.contains(key));
    CHECK(j["mask_residual"].get<double>() < 1e-12);
  }
  CHECK(lines == 11);
  CHECK(fs::exists(fs::path(out) / "dome.sweep-alpha.png"));
  CHECK(r.err.empty());  // no progress indicator when stderr is not a terminal
}

TEST_CASE("coons sweep: a boundary whose energies are all 0 still gets its plot", "[cli][alpha]") {
  // every curve was left out as zero and gnuplot failed ("all points y value undefined"): png_error
  TempDir dir;
  json side = json::array();
  for (int k = 0; k <= 3; ++k) side.push_back({0.0, 0.0, 0.0});
  const std::string file = dir.write(
      "zero.json", json{{"name", "zero"}, {"bottom", side}, {"top", side}, {"left", side}, {"right", side}}.dump());
  const std::string out = (dir.path / "sweep").string();
  const CommandResult r = run_coons("sweep " + quoted(file) + " --count 3 --out " + quoted(out));
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  const json summary = json::parse(r.out);
  CHECK_FALSE(summary.contains("png_error"));
  CHECK(fs::exists(fs::path(out) / "zero.sweep-alpha.png"));
}

TEST_CASE("coons study: a report with computed tables and figures", "[cli][alpha]") {
  TempDir dir;
  const std::string out = (dir.path / "study").string();
  const CommandResult r =
      run_coons("study " + quoted(kData + "/boundaries/dome.json") + " " + quoted(kData + "/boundaries/pillow.json") +
                " --degrees 3 4 6 --out " + quoted(out));
  REQUIRE(r.status == 0);
  std::ifstream in(fs::path(out) / "report.md");
  std::stringstream text;
  text << in.rdbuf();
  CHECK_THAT(text.str(), Catch::Contains("| -0.25 | 0.828427 | 24.787 | 9.877 |"));
  CHECK_THAT(text.str(), Catch::Contains("| -0.2 | 0.724874 | 18.320 | 9.320 |"));
  CHECK_THAT(text.str(), Catch::Contains("coons study"));
  for (const char* f :
       {"figures/dome_energies.png", "figures/dome_nets.png", "figures/alpha_vs_degree.png", "results.json"})
    CHECK(fs::exists(fs::path(out) / f));
}

TEST_CASE("coons refit: analytic sides at any degree, elevation otherwise, exit 2 below a Bezier degree",
          "[cli][alpha]") {
  TempDir dir;
  const std::string out = (dir.path / "dome6.json").string();
  const CommandResult r =
      run_coons("refit " + quoted(kData + "/boundaries/dome.json") + " --degree 6 6 --out " + quoted(out));
  REQUIRE(r.status == 0);
  const BoundaryFile f = read_boundary_file(out);
  CHECK(f.boundary.m == 6);
  CHECK(json::parse(r.out)["method"] == "refit");
  CHECK(json::parse(r.out)["max_deviation"].get<double>() < 1e-5);
  CHECK(run_coons("solve " + quoted(out)).status == 0);
  // the refitted file keeps the analytic sides and the target: refit again, fit the sphere
  const json written = json::parse(std::ifstream(out));
  CHECK(written.contains("curves"));
  CHECK(written.contains("target"));
  const CommandResult fit = run_coons("search-alpha " + quoted(out) + " --objective target");
  REQUIRE(fit.status == 0);
  CHECK(json::parse(fit.out)["alpha"].get<double>() > -0.25);
  const CommandResult up = run_coons("refit " + quoted(kData + "/boundaries/pillow.json") + " --degree 5 4");
  REQUIRE(up.status == 0);
  CHECK(json::parse(up.out)["method"] == "elevated");
  const CommandResult down = run_coons("refit " + quoted(kData + "/boundaries/pillow.json") + " --degree 2 2");
  CHECK(down.status == 2);
  CHECK(down.out.empty());
  CHECK_THAT(down.err, Catch::Contains("curves"));
}

TEST_CASE(
    "coons search-alpha: a grid backend that does not solve the 3x3 family is bad input, not a success by "
    "another evaluator",
    "[cli][alpha]") {
  // separable-banded takes only alpha = -1/4, fast5 only 5x5 stencils: the search used to answer
  // through the sine basis and report them as the successful solver
  for (const char* solver : {"separable-banded", "fast5"}) {
    if (!solvers::find_solver(solver)) continue;  // fast5 needs FFTW
    const CommandResult r = run_coons("search-alpha " + quoted(kData + "/boundaries/dome.json") +
                                      " --objective thin_plate --solver " + solver);
    INFO(solver << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind(std::string("error: command line: --solver: ") + solver, 0) == 0);
  }
  // the alpha-gamma search reports the seconds it took (it used to print 0)
  const CommandResult g = run_coons("search-alpha " + quoted(kData + "/boundaries/dome.json") +
                                    " --objective thin_plate --parameter alpha-gamma --solver eigen-ldlt");
  REQUIRE(g.status == 0);
  const json report = json::parse(g.out);
  CHECK(report["solver"]["iterations"].get<int>() > 0);
  CHECK(report["solver"]["seconds"]["search"].get<double>() > 0);
}

TEST_CASE("coons solve: --tolerance or --max-iterations with a direct or structured solver is bad input", "[cli]") {
  // they used to be accepted and ignored
  for (const char* args : {" --solver eigen-ldlt --tolerance 1e-3", " --solver dst --max-iterations 3",
                           " --solver separable-banded --max-iterations 3"}) {
    if (std::string(args).find("dst") != std::string::npos && !solvers::find_solver("dst")) continue;  // FFTW
    const CommandResult r = run_coons("solve " + quoted(kData + "/boundaries/dome.json") + args);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::Contains("is a stopping rule of the iterative solvers"));
  }
  CHECK(run_coons("solve " + quoted(kData + "/boundaries/dome.json") + " --solver cg --tolerance 1e-8").status == 0);
}

TEST_CASE("coons solve --time-limit: an iterative solve stops not_converged at the limit with its iterate", "[cli]") {
  // Gauss-Seidel at degree 30 needs tens of thousands of sweeps to 1e-14 (seconds); 0.05 s stops it
  // after a few hundred. The check is the status and the message, not a duration.
  TempDir dir;
  const std::string b = dir.file("dome30.json");
  REQUIRE(run_coons("refit " + quoted(kData + "/boundaries/dome.json") + " --degree 30 30 --out " + quoted(b)).status ==
          0);
  const CommandResult r = run_coons("solve " + quoted(b) +
                                    " --solver gauss-seidel --time-limit 0.05 --max-iterations 100000000 "
                                    "--tolerance 1e-14");
  INFO(r.err);
  CHECK(r.status == 3);
  const json report = json::parse(r.out);
  CHECK(report["solver"]["status"] == "not_converged");
  CHECK_THAT(report["solver"]["message"].get<std::string>(), Catch::Contains("time limit 0.05 s reached"));
  CHECK(report["solver"]["relative_residual"].get<double>() < 1);  // the iterate is kept, not zeroed
  // CG too, each column with its share of the limit: the first column took it all, and the X
  // returned had two zero columns, a true relative residual of 1
  for (const char* krylov : {"cg", "cg-jacobi", "bicgstab"}) {
    const CommandResult k = run_coons("solve " + quoted(b) + " --solver " + krylov +
                                      " --time-limit 0.001 --max-iterations 100000000 --tolerance 1e-300");
    INFO(krylov << ": " << k.err);
    CHECK(k.status == 3);
    const json solved = json::parse(k.out);
    CHECK(solved["solver"]["status"] == "not_converged");
    CHECK(solved["solver"]["relative_residual"].get<double>() < 0.5);
  }
  if (solvers::find_solver("hypre-amg")) {
    const CommandResult hypre = run_coons("solve " + quoted(b) + " --solver hypre-amg --time-limit 1");
    CHECK(hypre.status == 2);
    CHECK_THAT(hypre.err, Catch::Contains("hypre-amg has no clock in its iterations"));
  }
}

TEST_CASE("coons solve --solver bicgstab: a breakdown right after the first step keeps that step's iterate", "[cli]") {
  // The dome's 4 unknowns: the incomplete LU is exact, one step solves the system, and at a
  // tolerance below rounding the next step's restart divides by w = 0. Eigen's counter restarts
  // with it, so the count after the breakdown said 1 and the search for the last finite iterate
  // ended on the guess: X = 0, relative residual 1.
  for (const char* limit : {"", " --max-iterations 2147483647"}) {
    const CommandResult r =
        run_coons("solve " + quoted(kData + "/boundaries/dome.json") + " --solver bicgstab --tolerance 1e-300" + limit);
    INFO(limit << "\n" << r.err);
    CHECK(r.status == 3);
    const json report = json::parse(r.out);
    CHECK(report["solver"]["status"] == "not_converged");
    CHECK(report["solver"]["relative_residual"].get<double>() < 1e-14);  // (the true residual of the X kept)
  }
}

TEST_CASE("coons solve --method hermite-coons: alpha, beta and mask_residual are numbers, of the alpha = -1/4 mask",
          "[cli]") {
  // (they were null: the contract's report has numbers there; the partially bicubic net satisfies
  // no mask, and its residual against the Coons net's mask says how far it lies from that net)
  const std::string helicoid = quoted(kData + "/boundaries/helicoid.json");
  const json h = report_of("solve " + helicoid + " --method hermite-coons");
  const json c = report_of("solve " + helicoid + " --method coons");
  CHECK(h["mask"] == "alpha");
  CHECK(h["alpha"].get<double>() == -0.25);
  CHECK(h["beta"].get<double>() == 0.5);
  const double hermite_residual = h["metrics"]["mask_residual"].get<double>();
  const double coons_residual = c["metrics"]["mask_residual"].get<double>();
  CHECK(coons_residual < 1e-14);  // the Coons net satisfies the alpha = -1/4 mask
  // the helicoid's nets differ (the dome's do not), so the partially bicubic one does not (its residual is that of the
  // net's difference from the Coons net, on which the mask is linear)
  const double gap = max_difference(net_of(h), net_of(c));
  REQUIRE(gap > 1e-3);
  CHECK(hermite_residual > 1e-6 * gap);
  CHECK(hermite_residual <= 4 * gap);  // |d - (1/2)(4 edges of d) + (1/4)(4 diagonals of d)| <= (1 + 2 + 1) gap
}

TEST_CASE(
    "coons solve: a closed form takes --alpha and --mu as the mask of its mask_residual, and the defaults "
    "--solver auto and --mask alpha",
    "[cli]") {
  const std::string dome = quoted(kData + "/boundaries/dome.json");
  const json p = report_of("solve " + dome + " --method coons");
  const json m = report_of("solve " + dome + " --method coons --alpha -0.1 --solver auto --mask alpha");
  const json u = report_of("solve " + dome + " --method coons --mu 4");
  CHECK(m["net"] == p["net"]);  // the same closed-form net
  CHECK(u["net"] == p["net"]);
  CHECK(m["alpha"].get<double>() == -0.1);
  CHECK(m["solver"]["status"] == "not_applicable");
  // the Coons net satisfies alpha = -1/4 only: another member's residual is not zero
  CHECK(p["metrics"]["mask_residual"].get<double>() < 1e-14);
  CHECK(m["metrics"]["mask_residual"].get<double>() > 1e-6);
  CHECK(u["mu"].get<double>() == 4);
  CHECK(u["metrics"]["mask_residual"].get<double>() > 1e-6);
  // a B-spline boundary's Coons net likewise, against the non-uniform family's member
  const std::string wave = quoted(kData + "/boundaries/bspline_wave.json");
  const json wp = report_of("solve " + wave + " --method coons");
  const json wm = report_of("solve " + wave + " --method coons --alpha -0.1");
  CHECK(wm["net"] == wp["net"]);
  CHECK(wm["alpha"].get<double>() == -0.1);
  CHECK(wp["metrics"]["mask_residual"].get<double>() < 1e-12);
  CHECK(wm["metrics"]["mask_residual"].get<double>() > 1e-6);
  // an option that asks for what a closed form does not do is still refused
  const CommandResult solver = run_coons("solve " + dome + " --method coons --solver cholmod");
  CHECK(solver.status == 2);
  CHECK_THAT(solver.err, Catch::Contains("--solver"));
}

TEST_CASE("coons refit: a file with ribbons or a free grid is bad input, not a boundary that lost its second ring",
          "[cli]") {
  for (const auto& [file, field] : {std::pair{kData + "/boundaries/sphere_cap_ribbons.json", std::string("ribbons")},
                                    std::pair{kData + "/free_sets/island.json", std::string("rings")}}) {
    const CommandResult r = run_coons("refit " + quoted(file) + " --degree 8 8");
    INFO(r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    std::string expected = "error: ";
    expected.append(file).append(": ").append(field).append(": ");
    CHECK(r.err.rfind(expected, 0) == 0);
  }
}

TEST_CASE("coons degree-limit: an interior optimum at alpha* >= 0 is interior, with no mu", "[cli]") {
  // the quarter cylinder's thin-plate optimum at degree 3 lies at alpha ≈ 0.03, inside the bounds
  // (it used to be labelled at_bound because no mu exists for alpha >= 0)
  const CommandResult r = run_coons("degree-limit " + quoted(kData + "/boundaries/quarter_cylinder.json") +
                                    " --degrees 3 4 --continuum-degrees 4");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const json report = json::parse(r.out);
  const double alpha = report["alpha_star"][0];
  REQUIRE(alpha > 0);
  REQUIRE(alpha < 0.25);
  CHECK(report["optimum"][0] == "interior");
  CHECK(report["mu_star"][0].is_null());
}

TEST_CASE("coons study: a solve that fails gives 'failed' and null, never its zero-filled net's numbers", "[cli]") {
  // Jacobi diverges at alpha = -1/4 (the Coons mask): that reference row, the value at Coons and the
  // best-fit ratio used to be printed from the frame with a zero interior
  TempDir dir;
  const std::string out = dir.file("study");
  const CommandResult r = run_coons("study " + quoted(kData + "/boundaries/dome.json") +
                                    " --degrees 3 --solver jacobi --out " + quoted(out));
  INFO(r.err);
  REQUIRE(r.status == 3);  // the report is written, the exit status says that solves failed
  CHECK(r.err.rfind("error: ", 0) == 0);
  const std::string md = read_text(out + "/report.md");
  CHECK_THAT(md, Catch::Contains("| -0.25 | failed | failed | failed | failed |"));
  CHECK_THAT(md, !Catch::Contains("× closer"));
  const json results = json::parse(read_text(out + "/results.json"));
  bool shape = false, reference = false;
  for (const json& part : results) {
    if (part["kind"] == "shape") {
      shape = true;
      CHECK(part["thin_plate"]["coons"].is_null());
      CHECK(part["thin_plate"]["laplace"].get<double>() > 0);  // alpha = 0 converges
    }
    if (part["kind"] == "reference_table") {
      reference = true;
      CHECK(part["rows"][0]["thin_plate"].is_null());
      CHECK(part["coons_over_best"].is_null());
    }
  }
  CHECK(shape);
  CHECK(reference);
}

TEST_CASE("coons export: --method coons without output flags writes the OBJ files (no Matrix Market to refuse)",
          "[cli]") {
  // it used to turn on --mtx by default and then refuse it: "--mtx: Matrix Market export needs --method alpha"
  TempDir dir;
  for (const std::string& file : {kData + "/boundaries/dome.json", kData + "/boundaries/bspline_wave.json"}) {
    const std::string out = dir.file(fs::path(file).stem().string());
    const CommandResult r = run_coons("export " + quoted(file) + " --method coons --out " + quoted(out));
    INFO(file << "\n" << r.err);
    REQUIRE(r.status == 0);
    bool obj = false, mtx = false;
    for (const auto& entry : fs::directory_iterator(out)) {
      obj = obj || entry.path().extension() == ".obj";
      mtx = mtx || entry.path().extension() == ".mtx";
    }
    CHECK(obj);
    CHECK_FALSE(mtx);
  }
}

TEST_CASE("coons solve: a field one edit from one coons reads is warned about on standard error, then ignored",
          "[cli]") {
  // "fre" for "free" solved the file with every interior point free, silently, exit 0
  TempDir dir;
  json doc = json::parse(read_text(kData + "/free_sets/l_hole.json"));
  doc["fre"] = doc["free"];
  doc.erase("free");
  const std::string file = dir.write("typo.json", doc.dump());
  for (const std::string& command : {std::string("solve "), std::string("search-alpha --objective twist ")}) {
    const CommandResult r = run_coons(command + quoted(file));
    INFO(command << r.err);
    CHECK(r.status == 0);
    CHECK(r.err == "warning: " + file + ": fre: unknown field, ignored (did you mean \"free\"?)\n");
  }
  json dome = json::parse(read_text(kData + "/boundaries/dome.json"));
  dome["descripton"] = dome["description"];
  const std::string typo = dir.write("dome.json", dome.dump());
  json wave = json::parse(read_text(kData + "/boundaries/bspline_wave.json"));
  wave["descripton"] = wave["description"];
  const std::string bspline = dir.write("wave.json", wave.dump());  // study reads B-splines apart (review r63a)
  const CommandResult study =
      run_coons("study " + quoted(typo) + " " + quoted(bspline) + " --degrees 3 --out " + quoted(dir.file("study")));
  CHECK(study.status == 0);
  for (const std::string& file : {typo, bspline})
    CHECK(study.err.find("warning: " + file + ": descripton: unknown field, ignored (did you mean \"description\"?)") !=
          std::string::npos);
  // the bundled files spell every field as coons reads it
  const CommandResult bundled = run_coons("solve " + quoted(kData + "/boundaries/sphere_cap_ribbons.json"));
  CHECK(bundled.status == 0);
  CHECK(bundled.err.empty());
}

TEST_CASE("coons export: its solver block is solve's, picked_by auto and the closed form's block included", "[cli]") {
  // export printed the bare summary: no "picked_by": "auto", and no block at all for a closed form
  TempDir dir;
  const std::string pillow = kData + "/boundaries/pillow.json";
  const std::string wave = kData + "/boundaries/bspline_wave.json";
  const std::string hole = kData + "/free_sets/l_hole.json";
  int run = 0;
  for (const auto& [file, options] :
       std::vector<std::pair<std::string, std::string>>{{pillow, " --alpha -0.1"},
                                                        {pillow, " --alpha -0.1 --solver eigen-lu"},
                                                        {pillow, " --method coons"},
                                                        {wave, " --alpha -0.2"},
                                                        {wave, " --method coons"},
                                                        {hole, " --mask biharmonic"}}) {
    INFO(file << options);
    const CommandResult solved = run_coons("solve " + quoted(file) + options);
    const CommandResult exported =
        run_coons("export " + quoted(file) + options + " --obj --out " + quoted(dir.file(std::to_string(++run))));
    INFO(solved.err << exported.err);
    REQUIRE(solved.status == 0);
    REQUIRE(exported.status == 0);
    json a = json::parse(solved.out)["solver"], b = json::parse(exported.out)["solver"];
    a.erase("seconds");
    b.erase("seconds");
    CHECK(a == b);
    CHECK(b.contains("picked_by") == (options.find("--solver") == std::string::npos && b["name"] != "closed-form"));
  }
}

TEST_CASE("coons export: a net with no point to solve for writes no Matrix Market system and refuses --mtx", "[cli]") {
  // A 2 x 2 net and a triangle of degree 2 were written as "0 0 0", which bench-matrix refuses
  TempDir dir;
  const std::string square = dir.write("square.json",
                                       R"({"name": "square", "bottom": [[0,0,0],[1,0,0]], "top": [[0,1,0],[1,1,0]],
                    "left": [[0,0,0],[0,1,0]], "right": [[1,0,0],[1,1,0]]})");
  const std::string triangle =
      dir.write("triangle.json", R"({"name": "triangle", "type": "triangle", "sides": [[[0,0,0],[0.5,0,0.1],[1,0,0]],
                          [[1,0,0],[0.5,0.5,0.1],[0,1,0]], [[0,1,0],[0,0.5,0.1],[0,0,0]]]})");
  for (const std::string& file : {square, triangle}) {
    const std::string out = dir.file(fs::path(file).stem().string());
    const CommandResult plain = run_coons("export " + quoted(file) + " --out " + quoted(out));
    INFO(file << "\n" << plain.err);
    REQUIRE(plain.status == 0);
    CHECK(fs::exists(fs::path(out) / (fs::path(file).stem().string() + ".net.obj")));
    for (const auto& entry : fs::directory_iterator(out)) CHECK(entry.path().extension() != ".mtx");
    CHECK(json::parse(plain.out).count("matrix_market") == 0);
    const CommandResult asked = run_coons("export " + quoted(file) + " --mtx --out " + quoted(out + "-mtx"));
    CHECK(asked.status == 2);
    CHECK_THAT(asked.err,
               Catch::StartsWith("error: " + file + ": --mtx: ") && Catch::Contains("there is no system to write"));
    CHECK_FALSE(fs::exists(out + "-mtx"));
  }
}

TEST_CASE("coons search-alpha and sweep: without a target a memory refusal names the degree not --samples", "[cli]") {
  // 41 x 41 target samples were counted for a search of e3 on a file without a target, and the
  // refusal named --samples, which was neither given nor used
  TempDir dir;
  const std::string b = dir.file("dome40.json");
  REQUIRE(run_coons("refit " + quoted(kData + "/boundaries/dome.json") + " --degree 40 30 --out " + quoted(b)).status ==
          0);
  json refitted = json::parse(read_text(b));
  refitted.erase("target");  // (with the dome's sphere the sweep does take the samples)
  dir.write("dome40.json", refitted.dump());
  for (const std::string& command :
       {"search-alpha " + quoted(b) + " --objective e3 --max-memory 100K",
        "sweep " + quoted(b) + " --count 3 --max-memory 100K --out " + quoted(dir.file("s"))}) {
    const CommandResult r = run_coons(command);
    INFO(command << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK_THAT(r.err,
               Catch::StartsWith("error: " + b + ": degree: a ") && Catch::Contains("degree (40, 30) needs about"));
  }
}

TEST_CASE("coons solve and sweep: --threads 2 gives the net and the sweep lines of one thread", "[cli]") {
  // Degree 140 (139 × 139 free points): large enough that two threads really run: dst takes
  // min(threads, 139/32), fast min(threads, 139/64) and mg threads levels of 2048 points or more.
  TempDir dir;
  Boundary smooth = make_smooth_boundary(140, 140, 11);
  smooth.name = "big";
  const std::string big = quoted(dir.write("big.json", boundary_to_json(smooth).dump()));
  for (const char* solver : {"fast", "dst", "mg"}) {
    if (!solvers::find_solver(solver)) continue;  // fast and dst need FFTW
    const std::string args = std::string("solve ") + big + " --alpha -0.1 --solver " + solver;
    const CommandResult one = run_coons(args + " --threads 1"), two = run_coons(args + " --threads 2");
    INFO(solver << "\n" << one.err << two.err);
    REQUIRE(one.status == 0);
    REQUIRE(two.status == 0);
    CHECK(json::parse(two.out)["net"] == json::parse(one.out)["net"]);
  }
  const std::string sweep = "sweep " + big + " --solver " + (solvers::find_solver("fast") ? "fast" : "mg");
  std::array<std::vector<json>, 2> lines;
  for (int threads : {1, 2}) {
    const std::string out = (dir.path / std::to_string(threads)).string();
    const CommandResult r =
        run_coons(sweep + " --count 7 --threads " + std::to_string(threads) + " --out " + quoted(out));
    REQUIRE(r.status == 0);
    std::ifstream in(fs::path(out) / "big.sweep-alpha.jsonl");
    for (std::string line; std::getline(in, line);) {
      json j = json::parse(line);
      j.erase("solver");  // its seconds differ
      lines[std::size_t(threads - 1)].push_back(j);
    }
  }
  CHECK(lines[0].size() == 7);
  CHECK(lines[1] == lines[0]);
  const std::string dome = quoted(kData + "/boundaries/dome.json");
  for (const char* bad : {" --threads -1", " --threads 257"}) {
    const CommandResult r = run_coons("solve " + dome + bad);
    INFO(bad << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::Contains("--threads: must lie in 0 .. 256"));
  }
}

TEST_CASE("coons search-alpha: a search whose every solve failed prints value null, not 0", "[cli][alpha]") {
  const CommandResult r = run_coons("search-alpha " + quoted(kData + "/boundaries/oscillating.json") +
                                    " --objective thin_plate --solver jacobi --lower -0.25 --upper -0.1");
  REQUIRE(r.status == 3);
  const json j = json::parse(r.out);
  CHECK(j["status"] == "solver_failed");
  CHECK(j["value"].is_null());
}

TEST_CASE("coons solve: options that a request cannot use are bad input, not ignored", "[cli]") {
  const std::string dome = quoted(kData + "/boundaries/dome.json");
  const std::string triangle = quoted(kData + "/triangles/planar_bulge.json");
  const std::pair<std::string, std::string> cases[] = {
      {"solve " + dome + " --solver cg --threads 2", "command line: --threads: cg runs on one thread"},
      {"solve " + dome + " --tolerance 1e-6", "--solver auto picks one that solves exactly"},
      {"solve " + triangle + " --mask c1-coons --weight 0.5", "command line: --mask: does not apply to a triangular"},
      {"export " + triangle + " --mask biharmonic --out unused", "command line: --mask: does not apply"},
      {"solve " + triangle + " --threads 2", "command line: --threads: does not apply"},
      {"solve " + triangle + " --tolerance 1e-3", "command line: --tolerance: --tolerance is a stopping rule"}};
  for (const auto& [args, message] : cases) {
    const CommandResult r = run_coons(args);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::Contains(message));
  }
  CHECK(run_coons("solve " + dome + " --solver mg --threads 2").status == 0);
}

namespace {

// The JSON boundary of the flat grid (i/m, j/n, 0) of degree (m, n).
std::string flat_grid_boundary(int m, int n) {
  auto side = [](int k, const std::function<json(int)>& point) {
    json s = json::array();
    for (int i = 0; i <= k; ++i) s.push_back(point(i));
    return s;
  };
  const double dm = m, dn = n;
  json doc;
  doc["bottom"] = side(m, [&](int i) { return json{i / dm, 0.0, 0.0}; });
  doc["top"] = side(m, [&](int i) { return json{i / dm, 1.0, 0.0}; });
  doc["left"] = side(n, [&](int j) { return json{0.0, j / dn, 0.0}; });
  doc["right"] = side(n, [&](int j) { return json{1.0, j / dn, 0.0}; });
  return doc.dump();
}

}  // namespace

TEST_CASE("coons solve: a singular alpha mask system is refused by every backend as the stencil path refuses it",
          "[cli]") {
  // α = 1/2 at degree (3, 3) and α = −1/2 at degree (4, 4) are eigenvalues of the mask operator:
  // the system is singular but consistent, so some backends return one of its many solutions.
  TempDir dir;
  const std::string flat3 = quoted(dir.write("flat3.json", flat_grid_boundary(3, 3)));
  const std::string flat4 = quoted(dir.write("flat4.json", flat_grid_boundary(4, 4)));
  for (const std::string solver : {"auto", "eigen-lu", "umfpack", "cholmod", "eigen-ldlt", "gmres", "mg", "bicgstab"}) {
    if (solver != "auto" && !solvers::find_solver(solver)) continue;
    for (const std::string& args : {flat3 + " --alpha 0.5", flat4 + " --alpha -0.5"}) {
      const CommandResult r = run_coons(fmt::format("solve {} --solver {} --allow-indefinite", args, solver));
      INFO(args << " --solver " << solver << "\n" << r.out << r.err);
      CHECK(r.status == 2);
      CHECK(r.out.empty());
      CHECK(contains(r.err, ": the mask system is singular: the free points"));
      CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
      const CommandResult e = run_coons(
          fmt::format("export {} --solver {} --allow-indefinite --out {}", args, solver, quoted(dir.file("out"))));
      CHECK(e.status == 2);
      CHECK(contains(e.err, "the mask system is singular"));
    }
  }
  // a near value is solved
  CHECK(run_coons("solve " + flat3 + " --alpha 0.49 --solver eigen-lu").status == 0);
  // singular to rounding, not exactly: −0.33333333333 beside the singular −1/3 of degree (6, 6) has
  // an exact solution; the refusal says how near it is and what counts as singular
  const std::string flat6 = quoted(dir.write("flat6.json", flat_grid_boundary(6, 6)));
  const CommandResult near = run_coons("solve " + flat6 + " --alpha -0.33333333333 --solver eigen-lu");
  INFO(near.err);
  CHECK(near.status == 2);
  CHECK(contains(near.err, "to within rounding: the smallest eigenvalue or singular value is "));
  CHECK(contains(near.err, "and at most 1e-10 counts as singular"));
}

TEST_CASE("coons refit: a curve with a pole between the reader's samples is bad input naming the curve", "[cli]") {
  // z = 0.001/(t − 0.3) + a linear term that makes it vanish at both ends: finite at the reader's
  // 65 samples t = k/64 and at k/1024, infinite at t = 0.3, where the search for poles ends
  TempDir dir;
  const json doc = json::parse(R"json({
    "bottom": [[0, 0, 0], [1, 0, 0]], "top": [[0, 1, 0], [1, 1, 0]],
    "left": [[0, 0, 0], [0, 1, 0]], "right": [[1, 0, 0], [1, 1, 0]],
    "curves": {"bottom": {"expr": ["t", "0", "0.001/(t-0.3)+0.001/0.3-t*(0.001/0.7+0.001/0.3)"]},
               "top": {"expr": ["t", "1", "0"]}, "left": {"expr": ["0", "t", "0"]},
               "right": {"expr": ["1", "t", "0"]}}})json");
  const std::string file = dir.write("pole.json", doc.dump());
  const CommandResult r = run_coons("refit " + quoted(file) + " --degree 3 3");
  INFO(r.out << r.err);
  CHECK(r.status == 2);
  CHECK(r.out.empty());
  CHECK(contains(r.err, "pole.json: curves.bottom.expr[2]: '0.001/(t-0.3)"));
  CHECK(contains(r.err, "has a pole or is not finite near t = 0.3,"));
}

TEST_CASE("coons search-alpha and study: a model below 1e-60 is bad input, solve takes it", "[cli][alpha]") {
  // the pillow scaled by 1e-170: its energies are zero in doubles, and the search called it flat
  nlohmann::json doc = nlohmann::json::parse(read_text(kData + "/boundaries/pillow.json"));
  for (const char* side : {"bottom", "top", "left", "right"})
    for (nlohmann::json& point : doc[side])
      for (nlohmann::json& c : point) c = c.get<double>() * 1e-170;
  TempDir dir;
  const std::string file = (dir.path / "tiny_pillow.json").string();
  std::ofstream(file) << doc.dump();
  for (const std::string& args :
       {"search-alpha " + quoted(file) + " --objective thin_plate",
        "study " + quoted(file) + " --degrees 3 --out " + quoted((dir.path / "s").string())}) {
    INFO(args);
    const CommandResult r = run_coons(args);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: " + file + ": ", 0) == 0);
    CHECK_THAT(r.err, Catch::Contains("below 1e-60"));
  }
  CHECK_FALSE(std::filesystem::exists(dir.path / "s"));
  const CommandResult solve = run_coons("solve " + quoted(file) + " --alpha -0.1");
  CHECK(solve.status == 0);
  // the other readers of the searches: a triangle, and the base of a perturbed family
  nlohmann::json tri = nlohmann::json::parse(read_text(kData + "/triangles/sphere_octant.json"));
  for (nlohmann::json& side : tri["sides"])
    for (nlohmann::json& point : side)
      for (nlohmann::json& c : point) c = c.get<double>() * 1e-170;
  tri.erase("target");
  const std::string tri_file = (dir.path / "tiny_octant.json").string();
  std::ofstream(tri_file) << tri.dump();
  for (const std::string& args :
       {"search-alpha " + quoted(tri_file) + " --objective thin_plate",
        "study " + quoted(tri_file) + " --degrees 3 --out " + quoted((dir.path / "t").string()),
        "study --family perturbed:" + file + " --count 2 --degrees 3 --out " + quoted((dir.path / "f").string())}) {
    INFO(args);
    const CommandResult r = run_coons(args);
    CHECK(r.status == 2);
    CHECK_THAT(r.err, Catch::Contains("below 1e-60"));
  }
  CHECK(run_coons("solve " + quoted(tri_file)).status == 0);
}

#if COONS_HAVE_HYPRE
TEST_CASE("coons solve --solver hypre-amg: a stop before the iteration limit is not called the limit", "[cli][hypre]") {
  // hypre's GMRES stopped after 336 of 500 iterations without a flag, its X with a true residual of
  // 129, and the message said "iteration limit 500 reached" (the same for --max-iterations 1000)
  TempDir dir;
  const std::string file = dir.write(
      "n9.json",
      R"json({"name":"n9","bottom":[[-0.75,0.75,-0.75],[-0.75,-1.25,-2.0],[-0.25,-0.25,1.75],[-1.25,-0.25,-1.75],[1.25,1.5,2.25],[1.0,2.25,1.25],[-0.25,-0.5,-2.25],[-1.5,-2.25,-0.25],[-1.5,-0.75,-0.25],[1.75,-2.25,-2.0]],"top":[[-0.25,-0.75,-1.5],[-2.25,-0.25,-0.25],[1.25,-0.5,-1.25],[0.5,2.25,-1.5],[2.0,-1.25,-1.0],[-1.0,0.0,1.5],[0.25,1.5,-0.75],[2.0,-0.25,-1.75],[2.0,-1.5,-2.0],[2.25,1.0,-1.75]],"left":[[-0.75,0.75,-0.75],[-0.5,-2.25,0.0],[0.75,1.0,1.75],[1.5,-0.5,1.25],[1.0,2.0,-1.75],[0.75,-0.5,-1.25],[-1.25,1.75,-2.0],[-1.75,-2.25,2.25],[0.5,-1.25,-2.0],[-0.25,-0.75,-1.5]],"right":[[1.75,-2.25,-2.0],[-1.0,-1.25,-1.75],[-2.0,-0.5,0.25],[0.0,-1.75,-1.25],[-0.5,1.25,2.0],[1.75,-2.0,0.0],[-1.25,-0.5,-1.0],[0.0,-0.75,0.5],[-1.5,1.5,-0.75],[2.25,1.0,-1.75]]})json");
  for (const int limit : {500, 1000}) {
    const CommandResult r = run_coons("solve " + quoted(file) + " --alpha -0.6 --solver hypre-amg --max-iterations " +
                                      std::to_string(limit));
    INFO(r.out << r.err);
    CHECK(r.status == 3);
    const json solver = json::parse(r.out)["solver"];
    REQUIRE(solver["status"] == "not_converged");
    REQUIRE(solver["iterations"].get<int>() < limit);
    CHECK(solver["message"].get<std::string>().find("iteration limit") == std::string::npos);
    CHECK(solver["message"].get<std::string>().find("before the limit") != std::string::npos);
  }
}
#endif

TEST_CASE("coons solve: numbers that are zero or subnormal as written are read, a smaller one is refused", "[cli]") {
  const std::string file = quoted(kData + "/boundaries/dome.json");
  for (const auto& [text, alpha] : {std::pair{"0.0e-5", 0.0}, std::pair{"-0", 0.0}, std::pair{"-0x0p3", 0.0},
                                    std::pair{"4.9e-324", 4.9e-324}, std::pair{"-2e-310", -2e-310}}) {
    const CommandResult r = run_coons("solve " + file + " --alpha=" + text);
    INFO(text << ": " << r.err);
    REQUIRE(r.status == 0);
    const double read = nlohmann::json::parse(r.out)["alpha"].get<double>();
    CHECK(read == alpha);
    CHECK_FALSE(std::signbit(read) != std::signbit(alpha));  // -0 is folded to 0
  }
  const CommandResult tiny = run_coons("solve " + file + " --alpha=2e-324");  // rounds to 0
  CHECK(tiny.status == 2);
  CHECK_THAT(tiny.err, Catch::Contains("'2e-324' is below the smallest double"));
}
