#include "support/cli_support.h"

#include <catch2/catch.hpp>
#include <fstream>
#include <iterator>

namespace coons::test {

const std::string kCoons = COONS_BINARY;
const std::string kData = COONS_DATA_DIR;

std::string quoted(const std::string& text) { return "'" + text + "'"; }

CommandResult run_coons(const std::string& args) { return run_command(kCoons + " " + args); }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<nlohmann::json> read_json_lines(const std::string& path) {
  std::vector<nlohmann::json> out;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::json::parse(line));
  return out;
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
