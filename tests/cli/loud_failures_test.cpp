// Loud failures of the command line (issues 10 and 17), driven through the real binary: every
// exception mapped to an exit status and one `error:` line, every write checked, nothing
// overwritten or half-written, names that are data, sizes checked before memory is taken,
// contradictory options refused, reruns byte-identical apart from the timing block.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <vector>

#include "solvers/registry.h"
#include "support/cli_support.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

std::string dome() { return kData + "/boundaries/dome.json"; }

int lines(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

// exit 2, exactly one `error:` line, nothing on standard output
void check_refused(const CommandResult& r, const std::string& mention, int status = 2) {
  INFO(r.err);
  CHECK(r.status == status);
  CHECK(r.out.empty());
  CHECK(r.err.rfind("error: ", 0) == 0);
  CHECK(lines(r.err) == 1);
  CHECK_THAT(r.err, Catch::Contains(mention));
}

std::vector<std::string> files_under(const fs::path& root) {
  std::vector<std::string> out;
  if (!fs::exists(root)) return out;
  for (const auto& e : fs::recursive_directory_iterator(root)) out.push_back(fs::relative(e.path(), root).string());
  std::sort(out.begin(), out.end());
  return out;
}

json dome_doc() { return json::parse(std::ifstream(dome())); }

// A boundary of degree (n, n) on the unit square, z = 0 (large sides, small file per point).
std::string flat_boundary(const TempDir& dir, const std::string& name, int n) {
  std::ostringstream s;
  auto side = [&](const char* key, auto point) {
    s << '"' << key << "\": [";
    for (int k = 0; k <= n; ++k) {
      const auto [x, y] = point(double(k) / n);
      s << (k ? "," : "") << '[' << x << ',' << y << ",0]";
    }
    s << ']';
  };
  s << "{\"name\": \"" << name << "\", ";
  side("bottom", [](double t) { return std::pair{t, 0.0}; });
  s << ", ";
  side("top", [](double t) { return std::pair{t, 1.0}; });
  s << ", ";
  side("left", [](double t) { return std::pair{0.0, t}; });
  s << ", ";
  side("right", [](double t) { return std::pair{1.0, t}; });
  s << "}";
  return dir.write(name + ".json", s.str());
}

bool well_formed_obj(const fs::path& file, int vertices, int faces) {
  std::ifstream in(file);
  int v = 0, f = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "v") {
      double x, y, z;
      if (!(words >> x >> y >> z)) return false;
      ++v;
    } else if (tag == "f") {
      ++f;
    }
  }
  return v == vertices && f == faces;
}

}  // namespace

TEST_CASE("coons: a target of the wrong type is an input error for search-alpha, sweep and study", "[cli][loud]") {
  TempDir dir;
  json doc = dome_doc();
  doc["target"] = {{"sphere", 5}};
  const std::string bad = dir.write("badtarget.json", doc.dump());
  const std::string out = dir.file("out");
  check_refused(run_coons("search-alpha " + quoted(bad) + " --objective target"), "target.sphere");
  check_refused(run_coons("sweep " + quoted(bad) + " --out " + quoted(out)), "target.sphere");
  check_refused(run_coons("study " + quoted(bad) + " --degrees 3 4 --out " + quoted(out)), "target.sphere");
  CHECK(!fs::exists(out));  // no empty figures/ either
  doc["target"] = json::array({1, 2});
  check_refused(run_coons("search-alpha " + quoted(dir.write("t2.json", doc.dump())) + " --objective target"),
                "target");
}

TEST_CASE("coons: a file without name whose file name is not UTF-8 is solved, exported and reported", "[cli][loud]") {
  TempDir dir;
  json doc = dome_doc();
  doc.erase("name");
  const std::string file = dir.write("bad\xff\xfe.json", doc.dump());
  const CommandResult solve = run_coons("solve " + quoted(file));
  REQUIRE(solve.status == 0);
  CHECK(json::parse(solve.out)["degree"] == json::array({3, 3}));
  const std::string out = dir.file("out");
  const CommandResult exp = run_coons("export " + quoted(file) + " --samples 5 --out " + quoted(out));
  REQUIRE(exp.status == 0);
  for (const auto& f : files_under(out)) CHECK(f.find('\xff') == std::string::npos);  // the name was made safe
  CHECK(files_under(out).size() == 4);
  json spec = json::parse(std::ifstream(kData + "/surfaces/join_bilinear_a.json"));
  spec.erase("name");
  const std::string surface = dir.write("surface\xff.json", spec.dump());
  const CommandResult r = run_coons("surface " + quoted(surface) + " --samples 3 --obj " + quoted(dir.file("s.obj")));
  REQUIRE(r.status == 0);
  CHECK(json::parse(r.out)["points"].size() == 3);
  CHECK(fs::exists(dir.file("s.obj")));
}

TEST_CASE("coons batch: an output folder that cannot be created is an input error, nothing left", "[cli][loud]") {
  TempDir dir;
  const std::string blocker = dir.write("file", "not a folder");
  check_refused(run_coons("batch " + quoted(dome()) + " --samples 3 --out " + quoted(blocker + "/out")), "file");
  CHECK(files_under(dir.path) == std::vector<std::string>{"file"});
}

TEST_CASE("coons: a failed write to standard output is an error with the OS reason", "[cli][loud]") {
  TempDir dir;
  const std::string out = dir.file("out");
  for (const std::string& args :
       {" solve " + quoted(dome()), " search-alpha " + quoted(dome()) + " --objective thin_plate",
        " export " + quoted(dome()) + " --samples 3 --out " + quoted(out), std::string(" solvers")}) {
    INFO(args);
    const CommandResult r = run_command(std::string("( ").append(kCoons).append(args).append(" >/dev/full )"));
    CHECK(r.status == 2);
    CHECK(r.err == "error: <stdout>: write failed: No space left on device\n");
  }
  CHECK(!fs::exists(out));  // the export published nothing
}

TEST_CASE("coons export: eight concurrent exports to one folder and prefix publish complete files", "[cli][loud]") {
  TempDir dir;
  const std::string out = dir.file("out");
  const int k = 40;
  std::vector<std::thread> threads;
  threads.reserve(8);
  std::vector<int> status(8, -1);
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      status[t] = run_coons("export " + quoted(dome()) + " --alpha " + std::to_string(-0.25 + 0.05 * t) +
                            " --obj --force --samples " + std::to_string(k) + " --prefix same --out " + quoted(out))
                      .status;
    });
  for (auto& t : threads) t.join();
  for (int s : status) CHECK(s == 0);
  CHECK(files_under(out) == std::vector<std::string>{"same.net.obj", "same.surface.obj"});  // no staging files left
  CHECK(well_formed_obj(fs::path(out) / "same.surface.obj", k * k, 2 * (k - 1) * (k - 1)));
  CHECK(well_formed_obj(fs::path(out) / "same.net.obj", 16, 9));
}

TEST_CASE("coons export: a command stopped by SIGTERM while it writes leaves no staging file", "[cli][loud]") {
  // Interrupted while writing a 700 x 700 OBJ (tens of MB), it left OUT/dome.surface.obj.tmp-PID-0.
  // The shell waits until the staging file exists, so the signal is known to come mid-write.
  TempDir dir;
  const std::string out = dir.file("out");
  const CommandResult r = run_command("( " + kCoons + " export " + quoted(dome()) + " --obj --samples 700 --out " +
                                      quoted(out) + " & pid=$!; " + "for i in $(seq 1 3000); do ls " + quoted(out) +
                                      " 2>/dev/null | grep -q tmp && break; sleep 0.01; done; " + "ls " + quoted(out) +
                                      " | grep -c tmp; kill -TERM $pid; wait $pid; echo \"status $?\" )");
  INFO(r.out << r.err);
  CHECK(r.out.rfind("1\n", 0) == 0);                 // a staging file was there when the signal came
  CHECK_THAT(r.out, Catch::Contains("status 143"));  // 128 + SIGTERM: it died of the signal
  CHECK(files_under(out).empty());
}

TEST_CASE("coons export: an existing file is not overwritten without --force", "[cli][loud]") {
  TempDir dir;
  const std::string out = dir.file("out");
  REQUIRE(run_coons("export " + quoted(dome()) + " --obj --samples 3 --out " + quoted(out)).status == 0);
  const auto before = fs::last_write_time(fs::path(out) / "dome.surface.obj");
  check_refused(run_coons("export " + quoted(dome()) + " --obj --samples 4 --out " + quoted(out)), "--force");
  CHECK(fs::last_write_time(fs::path(out) / "dome.surface.obj") == before);
  CHECK(run_coons("export " + quoted(dome()) + " --obj --samples 4 --force --out " + quoted(out)).status == 0);
}

TEST_CASE("coons: output names carry what distinguishes them", "[cli][loud]") {
  TempDir dir;
  // two α that agree to three digits give two files
  const std::string out = dir.file("batch");
  REQUIRE(run_coons("batch " + quoted(dome()) + " --alphas -0.1 -0.1004 --samples 3 --out " + quoted(out)).status == 0);
  CHECK(fs::exists(fs::path(out) / "dome-3x3" / "alpha-0.1.json"));
  CHECK(fs::exists(fs::path(out) / "dome-3x3" / "alpha-0.1004.json"));
  check_refused(run_coons("batch " + quoted(dome()) + " --alphas -0.1 -0.1 --out " + quoted(dir.file("twice"))),
                "twice");
  // three boundaries named dome at different degrees, and two at the same degree
  const std::string at4 = dir.file("dome4.json"), at6 = dir.file("dome6.json");
  REQUIRE(run_coons("refit " + quoted(dome()) + " --degree 4 4 --out " + quoted(at4)).status == 0);
  REQUIRE(run_coons("refit " + quoted(dome()) + " --degree 6 6 --out " + quoted(at6)).status == 0);
  const std::string three = dir.file("three");
  REQUIRE(run_coons("batch " + quoted(dome()) + " " + quoted(at4) + " " + quoted(at6) + " " + quoted(dome()) +
                    " --alphas 0 --samples 3 --out " + quoted(three))
              .status == 0);
  for (const char* folder : {"dome-3x3", "dome-4x4", "dome-6x6", "dome-3x3-2"})
    CHECK(fs::is_directory(fs::path(three) / folder));
  // an α sweep and a μ sweep
  const std::string sweeps = dir.file("sweeps");
  REQUIRE(run_coons("sweep " + quoted(dome()) + " --count 3 --out " + quoted(sweeps)).status == 0);
  REQUIRE(run_coons("sweep " + quoted(dome()) + " --parameter mu --count 3 --out " + quoted(sweeps)).status == 0);
  CHECK(fs::exists(fs::path(sweeps) / "dome.sweep-alpha.jsonl"));
  CHECK(fs::exists(fs::path(sweeps) / "dome.sweep-mu.jsonl"));
}

TEST_CASE("coons: names from input files never place a file outside the output folder", "[cli][loud]") {
  TempDir dir;
  const std::vector<std::string> names = {"../escaped",
                                          "../../escaped2",
                                          "/tmp/coons-absolute-" + std::to_string(getpid()),
                                          "a/b/c",
                                          "ctl\x01\x1b[31m\nname",
                                          std::string(1000, 'n'),
                                          "",
                                          ".",
                                          ".."};
  int k = 0;
  for (const std::string& name : names) {
    INFO(name);
    json doc = dome_doc();
    doc["name"] = name;
    const std::string file = dir.write("in" + std::to_string(k) + ".json", doc.dump());
    const fs::path out = dir.path / ("out" + std::to_string(k++));
    CHECK(run_coons("export " + quoted(file) + " --samples 3 --out " + quoted(out.string())).status == 0);
    CHECK(run_coons("sweep " + quoted(file) + " --count 3 --out " + quoted(out.string())).status == 0);
    CHECK(run_coons("batch " + quoted(file) + " --alphas 0 --samples 3 --out " + quoted(out.string())).status == 0);
    CHECK(run_coons("study " + quoted(file) + " --degrees 3 4 --out " + quoted((out / "study").string())).status == 0);
    for (const auto& f : files_under(out)) CHECK(fs::path(f).begin()->string() != "..");
  }
  // nothing beside the output folders and the inputs
  for (const auto& entry : fs::directory_iterator(dir.path)) {
    const std::string n = entry.path().filename().string();
    CHECK((n.rfind("in", 0) == 0 || n.rfind("out", 0) == 0));
  }
  CHECK(!fs::exists(dir.path.parent_path() / "escaped.surface.obj"));
  CHECK(!fs::exists("/tmp/coons-absolute-" + std::to_string(getpid()) + ".surface.obj"));
}

TEST_CASE("coons: contradictory options are errors naming both", "[cli][loud]") {
  const std::string d = quoted(dome());
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {" solve " + d + " --method coons --mask c1-coons", {"--method", "--mask"}},
      {" solve " + d + " --method hermite-coons --omega 1.5", {"--method", "--omega"}},
      {" solve " + d + " --method coons --solver eigen-lu", {"--method", "--solver"}},
      {" solve " + d + " --alpha -0.1 --mu 3", {"--alpha", "--mu"}},
      {" solve " + d + " --solver eigen-ldlt --omega 1.5", {"--omega", "gauss-seidel"}},
      {" export " + d + " --method coons --tolerance 1e-6", {"--method", "--tolerance"}},
      {" search-alpha " + d + " --objective thin_plate --target coons", {"--target", "thin_plate"}},
      {" search-alpha " + d + " --objective thin_plate --samples 9", {"--samples", "thin_plate"}},
      {" search-alpha " + d + " --objective thin_plate --parameter mu --allow-indefinite",
       {"--allow-indefinite", "mu"}},
  };
  for (const auto& [args, mentions] : cases) {
    INFO(args);
    const CommandResult r = run_command(kCoons + args);
    check_refused(r, mentions[0]);
    for (const auto& m : mentions) CHECK_THAT(r.err, Catch::Contains(m));
  }
}

TEST_CASE("coons solve: a failing solver prints its report and one error line (exit 3)", "[cli][loud]") {
  const CommandResult r =
      run_coons("solve " + quoted(kData + "/boundaries/helicoid.json") + " --solver jacobi --max-iterations 3");
  CHECK(r.status == 3);
  const json report = json::parse(r.out);
  CHECK(report["solver"]["status"] != "success");
  CHECK(lines(r.err) == 1);
  CHECK_THAT(r.err, Catch::StartsWith("error: ") && Catch::Contains("jacobi") && Catch::Contains("relative residual") &&
                        Catch::Contains(report["solver"]["status"].get<std::string>()));
  // a sweep whose values fail in part of the range says which part
  TempDir dir;
  const CommandResult sweep = run_coons("sweep " + quoted(kData + "/boundaries/helicoid.json") +
                                        " --solver jacobi --count 5 --out " + quoted(dir.file("s")));
  CHECK(sweep.status == 3);
  CHECK(lines(sweep.err) == 1);
  const json summary = json::parse(sweep.out);
  REQUIRE(summary.contains("failed_intervals"));
  CHECK(summary["failed_values"].get<int>() >= 1);
  CHECK(summary["failed_intervals"][0][0] == -0.25);
}

TEST_CASE("coons solve: alpha at the bound ±1e60 is solved alike by fast, dst and eigen-lu", "[cli][loud]") {
  // fast's pivots square the weights: beyond about 1e154 they overflowed and it called the dome
  // singular, while eigen-lu solved it; kMaxAlpha = 1e60 keeps every backend on this side
  for (const char* alpha : {"1e60", "-1e60"}) {
    std::vector<json> nets;
    for (const char* solver : {"fast", "dst", "eigen-lu"}) {
      const CommandResult r = run_coons("solve " + quoted(dome()) + " --alpha " + alpha + " --solver " + solver);
      INFO(alpha << " " << solver << ": " << r.err);
      REQUIRE(r.status == 0);
      CHECK(r.out.find("nan") == std::string::npos);
      nets.push_back(json::parse(r.out)["net"]);
    }
    for (std::size_t k = 1; k < nets.size(); ++k)
      for (std::size_t i = 0; i < nets[0].size(); ++i)
        for (std::size_t j = 0; j < nets[0][i].size(); ++j)
          for (std::size_t c = 0; c < 3; ++c)
            CHECK(nets[k][i][j][c].get<double>() == Approx(nets[0][i][j][c].get<double>()).margin(1e-12));
  }
}

TEST_CASE("coons solve export and batch: a failed solve reports the relative residual of X = 0, which is 1",
          "[cli][loud]") {
  TempDir dir;
  // α = −0.6 makes the dome's 2×2 system indefinite (eigenvalues 1/2 + α, 1 + α, 3/2 − 3α):
  // Cholesky stops at a non-positive pivot and X = 0 (the report and the error line used to say
  // "relative residual 0", as for a perfect solve). (α = −1/2 is singular: refused as input.)
  const std::string args = quoted(dome()) + " --solver eigen-llt --alpha -0.6 --allow-indefinite";
  for (const std::string& command : {"solve " + args, "export " + args + " --out " + quoted(dir.file("e"))}) {
    const CommandResult r = run_coons(command);
    INFO(command << "\n" << r.err);
    CHECK(r.status == 3);
    const json report = json::parse(r.out);
    CHECK(report["solver"]["status"] == "not_positive_definite");
    CHECK(report["solver"]["relative_residual"] == 1);
    CHECK(report["net"].is_null());
    CHECK(lines(r.err) == 1);
    CHECK_THAT(r.err, Catch::Contains("not_positive_definite, relative residual 1 ("));
  }
  // a backend that cannot take the system: batch's report of that net, a triangle's solve
  const CommandResult batch = run_coons("batch " + quoted(dome()) + " --solver separable-banded --alphas -0.1 " +
                                        "--samples 3 --out " + quoted(dir.file("b")));
  INFO(batch.err);
  CHECK(batch.status == 3);
  const json net = json::parse(read_text(dir.file("b") + "/dome-3x3/alpha-0.1.json"));
  CHECK(net["solver"]["status"] == "not_applicable");
  CHECK(net["solver"]["relative_residual"] == 1);
  CHECK_THAT(batch.err, Catch::Contains("not_applicable, relative residual 1 ("));
  // its table row: no numbers (it used to print energies and a mask residual of 0)
  const std::string table = read_text(dir.file("b") + "/metrics.md");
  const auto row = table.find("-0.1 |");
  REQUIRE(row != std::string::npos);
  const std::string line = table.substr(row, table.find('\n', row) - row);
  INFO(line);
  CHECK_THAT(line, Catch::Contains("|           - |            - |"));
  CHECK_THAT(line, Catch::Contains("not_applicable"));
  CHECK(line.find("e+") == std::string::npos);
  CHECK(line.find("e-") == std::string::npos);
  const CommandResult tri =
      run_coons("solve " + quoted(kData + "/triangles/planar_bulge.json") + " --solver separable-banded");
  INFO(tri.err);
  CHECK(tri.status == 3);
  CHECK(json::parse(tri.out)["solver"]["relative_residual"] == 1);
}

TEST_CASE("coons batch: a failed solve takes away the OBJ files an earlier run left under its name", "[cli][loud]") {
  TempDir dir;
  const std::string out = dir.file("b");
  const std::string args = "batch " + quoted(dome()) + " --alphas -0.1 --samples 3 --out " + quoted(out);
  const CommandResult first = run_coons(args + " --solver eigen-ldlt");
  INFO(first.err);
  REQUIRE(first.status == 0);
  const std::string stem = out + "/dome-3x3/alpha-0.1";
  REQUIRE(std::filesystem::exists(stem + ".surface.obj"));
  REQUIRE(std::filesystem::exists(stem + ".net.obj"));
  // the same net again with a backend that cannot take it: its report says so, and no OBJ file of
  // the earlier solve stands beside it (they used to stay, an earlier run's surface unmarked)
  const CommandResult second = run_coons(args + " --solver separable-banded");
  INFO(second.err);
  CHECK(second.status == 3);
  CHECK(json::parse(read_text(stem + ".json"))["solver"]["status"] == "not_applicable");
  CHECK_FALSE(std::filesystem::exists(stem + ".surface.obj"));
  CHECK_FALSE(std::filesystem::exists(stem + ".net.obj"));
  CHECK(std::filesystem::exists(out + "/dome-3x3/coons.surface.obj"));  // the closed form solved again
}

TEST_CASE("coons: sizes are checked before memory is taken", "[cli][loud]") {
  TempDir dir;
  check_refused(run_coons("export " + quoted(dome()) + " --obj --samples 50000 --out " + quoted(dir.file("out"))),
                "needs about");
  CHECK(!fs::exists(dir.file("out")));
  const std::string spec = kData + "/surfaces/seed000_ferguson_1.json";
  if (fs::exists(spec)) check_refused(run_coons("surface " + quoted(spec) + " --sample 100000"), "needs about");
  const std::string huge = flat_boundary(dir, "huge", 40000);
  const std::string o = quoted(dir.file("o"));
  for (const std::string& args : {" solve " + quoted(huge), " search-alpha " + quoted(huge) + " --objective thin_plate",
                                  " export " + quoted(huge) + " --out " + o, " sweep " + quoted(huge) + " --out " + o,
                                  " batch " + quoted(huge) + " --out " + o}) {
    INFO(args);
    const CommandResult r = run_command(kCoons + args);
    check_refused(r, "needs about");
    CHECK_THAT(r.err, Catch::Contains("(40000, 40000)"));
  }
  check_refused(run_coons("study " + quoted(huge) + " --out " + quoted(dir.file("o"))), "needs about");
  CHECK(!fs::exists(dir.file("o")));
  const std::string big = flat_boundary(dir, "big", 3000);
  check_refused(run_coons("solve " + quoted(big) + " --max-memory 1GB"), "needs about");
  check_refused(run_coons("solve " + quoted(dome()) + " --max-memory lots"), "--max-memory");
}

TEST_CASE("coons solve: reruns are byte-identical apart from the timing block and solver seconds", "[cli][loud]") {
  for (const char* solver : {"eigen-ldlt", "fast", "auto"}) {
    INFO(solver);
    if (std::string(solver) != "auto" && !coons::solvers::find_solver(solver)) {
      WARN("skipped: " << solver << " is not built here");  // fast needs FFTW
      continue;
    }
    const std::string cmd =
        kCoons + " solve " + quoted(kData + "/boundaries/helicoid.json") + " --alpha -0.1 --solver " + solver;
    const CommandResult a = run_command(cmd), b = run_command(cmd);
    INFO(a.err << b.err);
    REQUIRE(a.status == 0);
    REQUIRE(b.status == 0);
    json ja = json::parse(a.out), jb = json::parse(b.out);
    CHECK(ja.contains("timing"));
    for (json* j : {&ja, &jb}) {
      j->erase("timing");
      (*j)["solver"].erase("seconds");  // the contract's timing field (docs/formats.md)
    }
    CHECK(ja.dump() == jb.dump());
  }
}

TEST_CASE("coons: every command's --help ends with a worked example, an unknown command is named", "[cli]") {
  std::vector<std::string> commands = {""};
  for (const std::string& name : coons_commands()) commands.push_back(" " + name);
  for (const std::string& cmd : commands) {
    INFO(cmd);
    const CommandResult r = run_command(kCoons + cmd + " --help");
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("Example:\n  coons"));
  }
  check_refused(run_coons("frobnicate"), "unknown command 'frobnicate'");
  CHECK_THAT(run_coons("search-alpha --help").out, Catch::Contains("discrete_thin_plate"));
  CHECK_THAT(run_coons("surface --help").out, Catch::Contains("--samples"));
}

TEST_CASE("coons search-alpha: discrete objectives and weighted sums with spaces", "[cli][alpha]") {
  for (const char* objective : {"discrete_twist", "discrete_dirichlet", "discrete_thin_plate", "thin_plate + 10*target",
                                " 2*e3 +thin_plate "}) {
    INFO(objective);
    const CommandResult r = run_coons("search-alpha " + quoted(dome()) + " --objective " + quoted(objective));
    REQUIRE(r.status == 0);
    const json report = json::parse(r.out);
    CHECK(report["objective"].get<std::string>().find(' ') == std::string::npos);
    CHECK(report["solver"].contains("name"));
    CHECK(report["solver"].contains("status"));
  }
}

TEST_CASE("coons study: results.json is the same on a rerun and names each entry's kind", "[cli][alpha]") {
  TempDir dir;
  const std::string args =
      " study " + quoted(dome()) + " " + quoted(kData + "/boundaries/pillow.json") + " --degrees 3 4 --out ";
  REQUIRE(run_command(kCoons + args + quoted(dir.file("a"))).status == 0);
  REQUIRE(run_command(kCoons + args + quoted(dir.file("b"))).status == 0);
  std::ifstream a(fs::path(dir.file("a")) / "results.json"), b(fs::path(dir.file("b")) / "results.json");
  std::stringstream ta, tb;
  ta << a.rdbuf();
  tb << b.rdbuf();
  CHECK(ta.str() == tb.str());
  std::map<std::string, int> kinds;
  for (const auto& e : json::parse(ta.str())) ++kinds[e["kind"].get<std::string>()];
  CHECK(kinds["shape"] == 2);
  CHECK(kinds["degree_law"] == 4);
  CHECK(kinds["fit_deviation"] == 1);    // the dome has curves
  CHECK(kinds["reference_table"] == 1);  // and a target
}

TEST_CASE("coons: progress with named phases on a terminal, nothing on standard error otherwise", "[cli][loud]") {
  TempDir dir;
  const std::string sweep = kCoons + " sweep " + quoted(dome()) + " --count 5 --out " + quoted(dir.file("s"));
  const CommandResult quiet = run_command(sweep);
  REQUIRE(quiet.status == 0);
  CHECK(quiet.err.empty());
  CHECK(json::parse(quiet.out)["timing"].contains("solve"));
  if (!fs::exists("/usr/bin/script")) {
    WARN("no /usr/bin/script (util-linux): the terminal half of this test is skipped");
    return;
  }
  // under a pseudo-terminal (script) standard error is a terminal: the phases are shown
  const CommandResult tty =
      run_command("script -qec " + quoted(kCoons + " solve " + dome() + " --solver eigen-ldlt") + " /dev/null");
  CHECK(tty.status == 0);
  CHECK_THAT(tty.out, Catch::Contains("coons solve: read") && Catch::Contains("coons solve: solve") &&
                          Catch::Contains("coons solve: metrics"));
}

TEST_CASE("coons search-alpha: wide bounds find the dome's minimum near zero, not a bound", "[cli][loud]") {
  // A linear scan of [-0.3, 1e12] (or of [-1e60, 1e60]) put no point near the family's scale: the
  // search reported -0.0443 (13.4687) "at a bound", or -0.749 (189.3) between the poles.
  const CommandResult reference = run_coons("search-alpha " + quoted(dome()) + " --objective thin_plate");
  REQUIRE(reference.status == 0);
  const double alpha = json::parse(reference.out)["alpha"], value = json::parse(reference.out)["value"];
  for (const char* bounds : {"--lower=-0.3 --upper=1e12", "--lower=-1e60 --upper=1e60", "--lower=-1 --upper=1e12"})
    for (const char* solver : {"fast", "eigen-lu"}) {
      const CommandResult r = run_coons("search-alpha " + quoted(dome()) +
                                        " --objective thin_plate --allow-indefinite " + bounds + " --solver " + solver);
      INFO(bounds << " " << solver << ": " << r.err << r.out);
      REQUIRE(r.status == 0);
      const json report = json::parse(r.out);
      CHECK(report["status"] == "success");
      CHECK(report["at_bound"] == false);
      CHECK(report["alpha"].get<double>() == Approx(alpha).margin(1e-7));
      CHECK(report["value"].get<double>() == Approx(value).epsilon(1e-12));
    }
}

TEST_CASE("coons search-alpha: bounds beyond 1e60 are refused, up to it no member is '-nan'", "[cli][loud]") {
  // --upper 1e308 once made the closed-form eigenvalue ratio NaN ("singular ... = -nan <= 1e-06"),
  // and ±1e308 made the scan's step overflow; kMaxAlpha (mask9.h) bounds every alpha now
  const CommandResult refused =
      run_coons("search-alpha " + quoted(dome()) + " --objective e3 --upper 1e308 --allow-indefinite --lower -0.2");
  CHECK(refused.status == 2);
  CHECK(refused.out.empty());
  CHECK(refused.err == "error: command line: --upper: must lie in [-1e60, 1e60]\n");
  const CommandResult r =
      run_coons("search-alpha " + quoted(dome()) + " --objective e3 --upper 1e60 --allow-indefinite --lower -0.2");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.out.find("nan") == std::string::npos);
  const json report = json::parse(r.out);
  CHECK(report["failed_evaluations"].get<int>() == 0);
  CHECK(report["alpha"].get<double>() == Approx(-0.2));
  CHECK(report["at_bound"] == true);
}

TEST_CASE("coons search-alpha: evaluations that fail are reported and no optimum is claimed on them", "[cli][loud]") {
  // Jacobi diverges for α < 0 on the helicoid: the search says where, claims nothing, exits 3
  const CommandResult r = run_coons("search-alpha " + quoted(kData + "/boundaries/helicoid.json") +
                                    " --objective thin_plate --solver jacobi");
  CHECK(r.status == 3);
  CHECK(lines(r.err) == 1);
  const json report = json::parse(r.out);
  CHECK(report["status"] != "success");
  CHECK(report["alpha"].is_null());
  CHECK(report["failed_evaluations"].get<int>() > 0);
  REQUIRE(!report["failed_intervals"].empty());
  CHECK(report["failed_intervals"][0][0] == -0.25);
  CHECK(report["solver"]["status"] == "failure");
  // a search whose every evaluation succeeded says so too
  const json ok = json::parse(run_coons("search-alpha " + quoted(dome()) + " --objective thin_plate").out);
  CHECK(ok["failed_evaluations"] == 0);
  CHECK(ok["failed_intervals"].empty());
}

TEST_CASE("coons view, surface and export: an output that cannot be put in place prints nothing", "[cli][loud]") {
  // the report used to be printed before the files were renamed into place
  TempDir dir;
  const std::string folder = dir.file("taken");
  fs::create_directories(folder);
  // export: its surface OBJ is a folder; the net OBJ, put in place before, must be taken back
  const std::string out = dir.file("out");
  fs::create_directories(fs::path(out) / "dome.surface.obj");
  const std::string spec = quoted(kData + "/surfaces/join_bilinear_a.json");
  for (const std::string& args : {"view " + quoted(dome()) + " --alphas 5 --samples 3 --force --out " + quoted(folder),
                                  "surface " + spec + " --samples 3 --force --obj " + quoted(folder),
                                  "export " + quoted(dome()) + " --obj --samples 3 --force --out " + quoted(out)}) {
    const CommandResult r = run_coons(args);
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::Contains("is a folder"));  // refused before anything is written, since require_new_output
  }
  CHECK(fs::is_directory(folder));
  CHECK(fs::is_empty(folder));
  CHECK(files_under(out) == std::vector<std::string>{"dome.surface.obj"});
}

TEST_CASE("coons batch, study, degree-limit: a folder without a boundary file is named", "[cli][loud]") {
  // "error: command line: BOUNDARY: no boundary files given or found" did not say which folder
  TempDir dir;
  const std::string empty = dir.file("empty");
  std::filesystem::create_directories(empty);
  for (const std::string& command : {"batch " + quoted(empty) + " --out " + quoted(dir.file("o")),
                                     "study " + quoted(empty) + " --out " + quoted(dir.file("s")),
                                     "degree-limit " + quoted(empty) + " --degrees 3 4"}) {
    const CommandResult r = run_coons(command);
    INFO(command);
    CHECK(r.status == 2);
    CHECK(r.err == "error: " + empty + ": the folder holds no *.json boundary file\n");
  }
  CHECK_FALSE(std::filesystem::exists(dir.file("o")));
  CHECK_FALSE(std::filesystem::exists(dir.file("s")));
}

TEST_CASE("coons batch: each failed net's line names the net", "[cli][loud]") {
  // two identical lines for alpha = -0.1 and 0 did not say which net failed
  TempDir dir;
  const CommandResult r =
      run_coons("batch " + quoted(dome()) + " --solver separable-banded --out " + quoted(dir.file("o")));
  CHECK(r.status == 3);
  REQUIRE(lines(r.err) == 2);
  CHECK_THAT(r.err, Catch::Contains("solver: separable-banded not_applicable, relative residual 1 (alpha-0.1: needs "));
  CHECK_THAT(r.err, Catch::Contains("solver: separable-banded not_applicable, relative residual 1 (alpha+0: needs "));
}

TEST_CASE("coons view: an --out that is no regular file is refused as such, --force or not", "[cli][loud]") {
  // /dev/full was answered "exists; give --force to overwrite it", and with --force "not a regular file"
  for (const char* force : {"", " --force"}) {
    const CommandResult r = run_coons("view " + quoted(dome()) + " --out /dev/full" + force);
    CHECK(r.status == 2);
    CHECK(r.err == "error: /dev/full: --out: is not a regular file (--force replaces regular files only)\n");
  }
}

TEST_CASE("coons solve: a misspelt net is the error, not the sides it is missing", "[cli][loud]") {
  // {"NET": ...} was reported as "bottom: missing", a field never meant
  TempDir dir;
  for (const char* key : {"NET", "nett"}) {
    const std::string file =
        dir.write(std::string(key) + ".json", std::string("{\"") + key + "\": [[[0,0,0],[0,1,0]],[[1,0,0],[1,1,0]]]}");
    const CommandResult r = run_coons("solve " + quoted(file));
    CHECK(r.status == 2);
    CHECK(r.err ==
          "error: " + file + ": " + key + ": unknown field; did you mean \"net\"? (the file has no \"net\")\n");
  }
}

TEST_CASE("coons search-alpha: an iterative solver's noise on a flat objective is flat, not an optimum",
          "[cli][loud]") {
  // jacobi's e3 of the saddle (exactly 0) scanned 3e-22 ... 3.5e-30 and reported alpha* = 0, gauss-seidel 0.1875
  for (const char* solver : {"jacobi", "gauss-seidel"}) {
    const CommandResult r =
        run_coons("search-alpha " + quoted(kData + "/boundaries/saddle.json") + " --objective e3 --solver " + solver);
    INFO(solver << ": " << r.err << r.out);
    REQUIRE(r.status == 0);
    const json report = json::parse(r.out);
    CHECK(report["status"] == "flat");
    CHECK(report["alpha"].is_null());
    CHECK_THAT(report["message"].get<std::string>(), Catch::Contains("iterative solver's relative residuals"));
  }
}

TEST_CASE("coons: a hexadecimal number on the command line is refused, as the file readers refuse it", "[cli][loud]") {
  // --alpha 0x10 solved at alpha = 16 and --weight 0x.8 at 0.5 (strtod), --alphas 0x5 gave 5 frames
  for (const auto& [args, option] : {std::pair{" --alpha 0x10", "--alpha"}, std::pair{" --alpha 0x1p-3", "--alpha"},
                                     std::pair{" --mask c1-family --weight 0x.8", "--weight"}}) {
    const CommandResult r = run_coons("solve " + quoted(dome()) + args);
    INFO(args);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::StartsWith(std::string("error: command line: ") + option + ": '0x"));
    CHECK_THAT(r.err, Catch::Contains("is not a decimal number (hexadecimal is not read)"));
  }
  TempDir dir;
  const CommandResult frames =
      run_coons("view " + quoted(dome()) + " --alphas 0x5 --out " + quoted(dir.file("v.html")));
  CHECK(frames.status == 2);
  CHECK_THAT(frames.err, Catch::StartsWith("error: command line: --alphas: '0x5' is not a decimal number"));
  CHECK_FALSE(std::filesystem::exists(dir.file("v.html")));
  CHECK(run_coons("solve " + quoted(dome()) + " --alpha -1e-1").status == 0);  // decimal exponents stay
  // strtod and strtoll skip white space before the prefix: ' 0x10' was read as 16 (review of
  // 2026-12-04); and CLI11 reads integers in base 0, so --max-iterations 010 was 8
  for (const auto& [args, message] :
       {std::pair{" --alpha ' 0x10'", "--alpha: ' 0x10' is not a decimal number (hexadecimal is not read)"},
        std::pair{" --alpha ' -0X1p-3'", "--alpha: ' -0X1p-3' is not a decimal number"},
        std::pair{" --solver cg --max-iterations 010",
                  "--max-iterations: '010' has a leading zero, which would be read "
                  "as octal"},
        std::pair{" --alpha 0.1x", "--alpha: '0.1x' is not a number"}}) {
    const CommandResult r = run_coons("solve " + quoted(dome()) + args);
    INFO(args);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK_THAT(r.err, Catch::StartsWith(std::string("error: command line: ") + message));
  }
  CHECK(run_coons("solve " + quoted(dome()) + " --alpha 010").status == 0);  // a real number: decimal 10
}

TEST_CASE("coons sweep: an interval too narrow for --count distinct values is refused", "[cli][loud]") {
  // 100000 values of [-0.25, -0.2499999999999999] were a handful of doubles, each written many times
  TempDir dir;
  const CommandResult r = run_coons(
      "sweep " + quoted(dome()) + " --from -0.25 --to -0.2499999999999999 --count 1000 --out " + quoted(dir.file("s")));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::StartsWith("error: command line: --from/--to: the interval [-0.25, -0.2499999999999999] is "
                                      "too narrow for 1000 distinct values"));
  CHECK_FALSE(std::filesystem::exists(dir.file("s")));
}
