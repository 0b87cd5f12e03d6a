// `coons study --family … --shard I/N` and `--merge` through the real binary at a tiny size: the
// merged report equals the unsharded one, the shards are disjoint and cover the task list, a rerun
// skips what is there and redoes a truncated last line, and bad input is one error line.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <vector>

#include "support/cli_support.h"

using namespace coons::test;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kFamily = "study --family random-smooth --count 4 --seed 3 --degrees 3 5";

}  // namespace

TEST_CASE("coons study --shard: three shards merged equal the unsharded run", "[cli]") {
  TempDir dir;
  const ShardedStudy run = run_sharded_study(kCoons + " " + kFamily, dir, 3);
  std::set<std::string> keys;
  size_t lines = 0;
  for (const std::vector<json>& shard : run.records)
    for (const json& record : shard) {
      keys.insert(record["key"].get<std::string>());
      ++lines;
      CHECK(record["study"]["count"] == 4);
      CHECK(record["parameter"] == "alpha");
    }
  CHECK(lines == 4 * 2 * 2);  // boundaries × degrees × objectives
  CHECK(keys.size() == lines);
  const json a = json::parse(read_text(dir.file("whole/results.json")));
  const json b = json::parse(read_text(dir.file("merged/results.json")));
  CHECK(a == b);
  CHECK(a["cells"].size() == 4);
  CHECK(a["cells"][0]["alpha_star"].size() == 4);
  CHECK(read_text(dir.file("whole/report.md")) == read_text(dir.file("merged/report.md")));
  CHECK(fs::exists(dir.file("merged/figures/alpha_family_thin_plate.png")));
  CHECK(fs::exists(dir.file("merged/figures/mu_family_e3.png")));
}

TEST_CASE("coons study --shard: a rerun skips finished tasks and redoes a truncated last line", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("shards");
  const std::string args = kFamily + " --shard 1/2 --out " + quoted(out);
  REQUIRE(run_coons(args).status == 0);
  const std::string file = out + "/shard-1-of-2.jsonl";
  const std::vector<json> first = read_json_lines(file);
  REQUIRE(first.size() == 8);
  // a job killed while writing its last record: half a line, no newline
  std::string text = read_text(file);
  text.resize(text.size() - 1 - first.back().dump().size() / 2);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  const CommandResult again = run_coons(args);
  INFO(again.err);
  REQUIRE(again.status == 0);
  CHECK(again.out.find("7 already there, 1 run") != std::string::npos);
  const std::vector<json> second = read_json_lines(file);
  REQUIRE(second.size() == first.size());
  for (size_t k = 0; k < first.size(); ++k) {
    json x = first[k], y = second[k];
    x.erase("seconds");
    y.erase("seconds");
    CHECK(x == y);
  }
  CHECK(run_coons(args).out.find("8 already there, 0 run") != std::string::npos);
}

TEST_CASE("coons study --shard/--merge: bad input is one error line, exit 2, nothing written", "[cli]") {
  TempDir dir;
  const std::string out = dir.file("out");
  REQUIRE(run_coons(kFamily + " --shard 0/2 --out " + quoted(dir.file("half"))).status == 0);
  for (const std::string& args :
       {kFamily + " --shard 3/3", kFamily + " --shard 1/0", kFamily + " --shard -1/2", kFamily + " --shard 1",
        kFamily + " --shard a/b", std::string("study --shard 2/2 ") + quoted(kData + "/boundaries/pillow.json"),
        "study --merge " + quoted(dir.file("none")), "study --merge " + quoted(dir.file("half")),
        kFamily + " --merge " + quoted(dir.file("half"))}) {
    const CommandResult r = run_coons(args + " --out " + quoted(out));
    INFO(args << "\n" << r.err);
    CHECK(r.status == 2);
    CHECK(r.out.empty());
    CHECK(r.err.rfind("error: ", 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("coons study --shard/--merge: records of another study or with a wrong key are refused", "[cli]") {
  TempDir dir;
  const std::string shards = dir.file("shards");
  for (int i = 0; i < 2; ++i)
    REQUIRE(run_coons(kFamily + " --shard " + std::to_string(i) + "/2 --out " + quoted(shards)).status == 0);
  // the same folder for a study with another seed: its shard file holds another study
  const CommandResult other =
      run_coons("study --family random-smooth --count 4 --seed 4 --degrees 3 5 --shard 0/2 --out " + quoted(shards));
  CHECK(other.status == 2);
  CHECK(other.err.find("shard-0-of-2.jsonl: study: holds tasks of another study") != std::string::npos);
  // a record whose key is not its task's: the merge names the file and the field
  const std::string file = shards + "/shard-1-of-2.jsonl";
  std::vector<json> records = read_json_lines(file);
  records[2]["index"] = records[2]["index"].get<int>() + 2;
  write_json_lines(file, records);
  const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("shard-1-of-2.jsonl: key: ") != std::string::npos);
  CHECK(merged.out.empty());
  CHECK_FALSE(fs::exists(dir.file("merged")));
}

TEST_CASE("coons study --merge: a record whose grid is not the study's length is refused, not read past", "[cli]") {
  // the key covers the task's inputs, not its result: an edited grid passes it. An empty grid on
  // the first optimum used to crash the merge, a shorter one on a later record to be read past its end
  TempDir dir;
  const std::string shards = dir.file("shards");
  REQUIRE(run_coons(kFamily + " --shard 0/1 --out " + quoted(shards)).status == 0);
  const std::string file = shards + "/shard-0-of-1.jsonl";
  const std::vector<json> records = read_json_lines(file);
  std::vector<size_t> optima;  // the records with an α*, whose grid the merge aggregates
  for (size_t k = 0; k < records.size(); ++k)
    if (records[k]["status"] == "interior" || records[k]["status"] == "at_bound") optima.push_back(k);
  REQUIRE(optima.size() >= 2);
  for (const auto& [at, grid] :
       {std::make_pair(optima.front(), json::array()), std::make_pair(optima[1], json::array({1.0, 2.0, 3.0}))}) {
    std::vector<json> edited = records;
    edited[at]["grid"] = grid;
    write_json_lines(file, edited);
    const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
    INFO(grid.dump() << "\n" << merged.err);
    CHECK(merged.status == 2);
    CHECK(merged.out.empty());
    CHECK(merged.err.rfind("error: ", 0) == 0);
    CHECK(merged.err.find("shard-0-of-1.jsonl: grid: has " + std::to_string(grid.size()) + " values") !=
          std::string::npos);
    CHECK(std::count(merged.err.begin(), merged.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(dir.file("merged")));
  }
}

TEST_CASE("coons study --merge: a line nested 140,000 deep is skipped, not a crash", "[cli]") {
  // read unbounded, the merge's copy of such a line recursed once per level: exit 139, no message
  TempDir dir;
  const std::string shards = dir.file("shards");
  REQUIRE(run_coons(kFamily + " --shard 0/1 --out " + quoted(shards)).status == 0);
  {
    std::ofstream out(shards + "/shard-0-of-1.jsonl", std::ios::binary | std::ios::app);
    out << R"({"key":"k","study":)" << std::string(140000, '[') << std::string(140000, ']') << "}\n";
  }
  const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 0);  // the line is no record (as a malformed one is not): the 16 tasks merge
  CHECK(merged.out.find("merged 16 tasks") != std::string::npos);
}

TEST_CASE("coons study --merge: an edited study block is refused before its task list is built", "[cli]") {
  // The task key does not cover count, degrees or objectives. A count of 100000 made the merge
  // build every task (1.6 GB for degrees 3 … 200) before it said that tasks were missing, and a
  // list naming an objective twice said "18446744073709551615 tasks outside the study's list".
  TempDir dir;
  const std::string shards = dir.file("shards");
  REQUIRE(run_coons(kFamily + " --shard 0/1 --out " + quoted(shards)).status == 0);
  const std::string file = shards + "/shard-0-of-1.jsonl";
  const std::vector<json> records = read_json_lines(file);
  REQUIRE(records.size() == 16);  // 4 boundaries × 2 degrees × 2 objectives
  const auto edit_all = [&](const std::string& field, const json& value) {
    write_json_lines(file, records, [&](json& r) { r["study"][field] = value; });
  };
  edit_all("count", 100000);
  const std::size_t total = 100000 * 2 * records[0]["study"]["objectives"].size();
  CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("--merge: " + std::to_string(total - 16) + " of " + std::to_string(total) +
                        " tasks are missing (the first: boundary 4, degree 3,") != std::string::npos);
  edit_all("count", 4);
  const std::string objective = records[0]["study"]["objectives"][0];
  edit_all("objectives", json::array({objective, objective}));
  merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("study.objectives: names '" + objective + "' twice") != std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("merged")));
}

TEST_CASE("coons study --merge: a study block's strings that are numbers are errors naming the field", "[cli]") {
  // value() of a number where a string belongs threw a JSON type_error naming no field
  TempDir dir;
  const std::string shards = dir.file("shards");
  REQUIRE(run_coons(kFamily + " --shard 0/1 --out " + quoted(shards)).status == 0);
  const std::string file = shards + "/shard-0-of-1.jsonl";
  const std::vector<json> records = read_json_lines(file);
  write_json_lines(file, records, [](json& r) { r["study"]["coons"]["version"] = 5; });
  CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("shard-0-of-1.jsonl: study.coons.version: is not a string") != std::string::npos);
  // "inputs", which tells a boundary-file study's shards, a number (a 33-byte line of the fuzzer's)
  write_json_lines(file, {json::parse(R"({"key":"k","study":{"inputs":5}})")});
  merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("shard-0-of-1.jsonl: family: missing") != std::string::npos);
  CHECK(merged.err.find("json.exception") == std::string::npos);
  CHECK_FALSE(fs::exists(dir.file("merged")));
}

TEST_CASE("coons study --family perturbed: a bundled shape's perturbations, sharded and merged", "[cli]") {
  TempDir dir;
  // the bundled shape by name, from the repository's root as the README runs it
  const std::string base = "cd " + quoted(COONS_DATA_DIR "/..") + " && " + kCoons +
                           " study --family perturbed:dome --count 3 --seed 2 "
                           "--degrees 3 4";
  run_sharded_study(base + " --amplitude 0.2", dir, 3);
  const json a = json::parse(read_text(dir.file("whole/results.json")));
  CHECK(a == json::parse(read_text(dir.file("merged/results.json"))));
  CHECK(read_text(dir.file("whole/report.md")) == read_text(dir.file("merged/report.md")));
  CHECK(a["family"] == "perturbed:dome");
  CHECK(a["amplitude"] == 0.2);
  CHECK(a["cells"][0]["alpha_star"].size() == 3);
  // another amplitude is another study: other keys, and its shards are refused in that folder
  const CommandResult other = run_command(base + " --amplitude 0.3 --shard 0/3 --out " + quoted(dir.file("shards")));
  CHECK(other.status == 2);
  CHECK(other.err.find("study: holds tasks of another study") != std::string::npos);
  // an unknown shape is one error line
  const CommandResult unknown = run_coons(
      "study --family perturbed:no_such_shape --count 2 --degrees 3 4 "
      "--out " +
      quoted(dir.file("x")));
  CHECK(unknown.status == 2);
  CHECK(unknown.err.rfind("error: command line: --family: 'no_such_shape' is neither", 0) == 0);
  CHECK_FALSE(fs::exists(dir.file("x")));
}

TEST_CASE("coons study --merge: a record's grid of finite 1e308 values prints no inf and no NaN", "[cli]") {
  // its losses (f(α) − f*)/f* overflowed: "| inf % |" in the table and "loses inf % on average"
  TempDir dir;
  const std::string shards = dir.file("shards");
  for (const char* shard : {"0/2", "1/2"})
    REQUIRE(run_coons(kFamily + " --shard " + shard + " --out " + quoted(shards)).status == 0);
  const std::string file = shards + "/shard-0-of-2.jsonl";
  std::vector<json> records = read_json_lines(file);
  REQUIRE(!records.empty());
  REQUIRE(records[0]["grid"].is_array());
  records[0]["grid"] = json(std::vector<double>(records[0]["grid"].size(), 1e308));
  write_json_lines(file, records);
  const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("report")));
  INFO(merged.err);
  REQUIRE(merged.status == 0);
  const std::string md = read_text(dir.file("report/report.md"));
  const std::regex not_finite(R"(\b(inf|nan)\b)", std::regex::icase);
  CHECK_FALSE(std::regex_search(md, not_finite));
  CHECK_FALSE(std::regex_search(merged.out, not_finite));
}

TEST_CASE("coons study --merge: a task twice with the same result merges and with different results is refused",
          "[cli]") {
  // Shards of different N mixed hold some tasks twice, with equal results (the searches are
  // deterministic); a second record of a task with another alpha* was accepted, the first read won.
  TempDir dir;
  const std::string shards = dir.file("shards");
  REQUIRE(run_coons(kFamily + " --shard 0/1 --out " + quoted(shards)).status == 0);
  const std::string file = shards + "/shard-0-of-1.jsonl";
  const std::vector<json> records = read_json_lines(file);
  std::size_t optimum = 0;
  while (optimum < records.size() && records[optimum]["status"] != "interior") ++optimum;
  REQUIRE(optimum < records.size());
  const std::string copy = shards + "/shard-0-of-2.jsonl";
  std::ofstream(copy, std::ios::binary | std::ios::trunc) << records[optimum].dump() << '\n';
  {
    const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("same")));
    INFO(merged.err);
    CHECK(merged.status == 0);
  }
  json edited = records[optimum];
  edited["alpha"] = edited["alpha"].get<double>() + 1e-3;
  std::ofstream(copy, std::ios::binary | std::ios::trunc) << edited.dump() << '\n';
  const CommandResult merged = run_coons("study --merge " + quoted(shards) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  CHECK(merged.status == 2);
  CHECK(merged.err.find("is in the shards twice with different results") != std::string::npos);
  CHECK(merged.out.empty());
  CHECK_FALSE(fs::exists(dir.file("merged")));
}
