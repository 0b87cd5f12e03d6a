#include "support/cli_support.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>
#include <sstream>

#include "coons/io/boundary_io.h"

namespace coons::test {

const std::string kCoons = COONS_BINARY;
const std::string kData = COONS_DATA_DIR;

std::string quoted(const std::string& text) { return "'" + text + "'"; }

CommandResult run_coons(const std::string& args) { return run_command(kCoons + " " + args); }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json report_of(const std::string& args) {
  const CommandResult r = run_coons(args);
  INFO("coons " << args << "\n" << r.err);
  REQUIRE(r.status == 0);
  return nlohmann::json::parse(r.out);
}

ControlNet net_of(const nlohmann::json& report) {
  return *parse_boundary(nlohmann::json{{"net", report.at("net")}}, "report").net;
}

const std::vector<std::string>& coons_commands() {
  static const std::vector<std::string> commands = [] {
    const CommandResult help = run_coons("--help");
    std::vector<std::string> out;
    std::istringstream lines(help.out);
    bool in_block = false;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("Subcommands:", 0) == 0 || line.rfind("SUBCOMMANDS:", 0) == 0) {
        in_block = true;
      } else if (in_block && line.empty()) {
        break;
      } else if (in_block && line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ') {
        std::istringstream words(line);
        std::string name;
        words >> name;
        out.push_back(name);
      }
    }
    return out;
  }();
  INFO("coons --help lists: " << commands.size() << " commands");
  REQUIRE(commands.size() >= 14);  // the parse found the block: solve ... import-step
  REQUIRE(std::find(commands.begin(), commands.end(), "solve") != commands.end());
  return commands;
}

std::vector<nlohmann::json> read_json_lines(const std::string& path) {
  std::vector<nlohmann::json> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
  return out;
}

void write_json_lines(const std::string& path, const std::vector<nlohmann::json>& records,
                      const std::function<void(nlohmann::json&)>& edit) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  for (nlohmann::json r : records) {
    if (edit) edit(r);
    out << r.dump() << '\n';
  }
  REQUIRE(out.good());
}

ShardedStudy run_sharded_study(const std::string& command, const TempDir& dir, int count) {
  const CommandResult whole = run_command(command + " --out " + quoted(dir.file("whole")));
  INFO(whole.err);
  REQUIRE(whole.status == 0);
  ShardedStudy out;
  for (int i = 0; i < count; ++i) {
    const std::string shard = std::to_string(i) + "/" + std::to_string(count);
    std::string line = command;
    line += " --shard " + shard + " --out " + quoted(dir.file("shards"));
    out.shards.push_back(run_command(line));
    INFO(shard << "\n" << out.shards.back().err);
    REQUIRE(out.shards.back().status == 0);
    out.records.push_back(
        read_json_lines(dir.file("shards/shard-" + std::to_string(i) + "-of-" + std::to_string(count) + ".jsonl")));
  }
  const CommandResult merged =
      run_coons("study --merge " + quoted(dir.file("shards")) + " --out " + quoted(dir.file("merged")));
  INFO(merged.err);
  REQUIRE(merged.status == 0);
  return out;
}

}  // namespace coons::test
