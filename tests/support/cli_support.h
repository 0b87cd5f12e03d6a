// Driving the real `coons` binary from the CLI tests: where it and the data are, quoting a path
// for the shell, running it with stdout, stderr and the exit status captured, reading a file back.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/fixtures.h"

namespace coons::test {

extern const std::string kCoons;  //!< the binary built with the tests (COONS_BINARY)
extern const std::string kData;   //!< the repository's data/ folder (COONS_DATA_DIR)

//! 'text' for the shell (paths here hold no single quote).
std::string quoted(const std::string& text);

//! `coons ARGS` through the shell: exit status, standard output and standard error.
CommandResult run_coons(const std::string& args);

//! The whole of a file, byte for byte ("" when it cannot be read).
std::string read_text(const std::string& path);

//! The commands of `coons`, as `coons --help` lists them (its "Subcommands:" block), in that order:
//! the one list the tests that cover every command iterate, so that a new command is not missed.
const std::vector<std::string>& coons_commands();

//! The JSON report of `coons ARGS`, which is REQUIREd to exit 0 (its stderr shown when it does not).
nlohmann::json report_of(const std::string& args);

//! The "net" of a solve report (or of any JSON object holding one), as a control net.
ControlNet net_of(const nlohmann::json& report);

//! The lines of a JSON Lines file, parsed.
std::vector<nlohmann::json> read_json_lines(const std::string& path);
//! `records` written to `path` as JSON Lines (replacing it), each after `edit` when one is given.
void write_json_lines(const std::string& path, const std::vector<nlohmann::json>& records,
                      const std::function<void(nlohmann::json&)>& edit = {});

//! A study run whole and in shards: `COMMAND --out DIR/whole`, `COMMAND --shard i/N --out DIR/shards`
//! for i < N, then `coons study --merge DIR/shards --out DIR/merged`, each REQUIREd to exit 0.
//! COMMAND is the whole `coons study …` command line (kCoons first, or after a `cd`).
struct ShardedStudy {
  std::vector<CommandResult> shards;                 //!< each `--shard i/N` run
  std::vector<std::vector<nlohmann::json>> records;  //!< each shard file's records
};
ShardedStudy run_sharded_study(const std::string& command, const TempDir& dir, int count);

}  // namespace coons::test
