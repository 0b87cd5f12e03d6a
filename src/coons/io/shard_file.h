// The shard files of `coons study … --shard I/N` (JSON Lines, one record per finished task;
// docs/formats.md "Sharded studies"), read for resuming a shard and for `--merge`: the complete
// lines that are JSON objects with a string "key". A line that is not (malformed, nested deeper
// than parse_json_text allows, a key given twice) and a last line without its newline (the one a
// killed run was writing) are no records; `clean` then says the file held something else.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace coons {

struct ShardFile {
  std::vector<nlohmann::json> records;
  std::vector<std::string> lines;  //!< the text of each record, as written
  bool clean = true;
};

//! The records of the text of a shard file named `source` (a line is never an error: it is a
//! record or it is not).
ShardFile parse_shard_lines(const std::string& text, const std::string& source);

//! The records of the file at `path`; an InputError when it cannot be read.
ShardFile read_shard_file(const std::filesystem::path& path);

}  // namespace coons
