#include "coons/io/shard_file.h"

#include <fstream>
#include <iterator>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons {

using nlohmann::json;

ShardFile parse_shard_lines(const std::string& text, const std::string& source) {
  ShardFile out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {  // no newline: the line a killed run was writing
      out.clean = false;
      break;
    }
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    // parse_json_text: a line nested beyond its depth limit (64; coons's records are at most 11
    // deep) is refused, not parsed: a line of 140,000 nested arrays overflowed the stack when the
    // merge copied it (exit 139, no message). Such a line, like a malformed one, is no record.
    json j;
    try {
      j = parse_json_text(line, source, {});
    } catch (const InputError&) {
      out.clean = false;
      continue;
    }
    if (!j.is_object() || !j.contains("key") || !j["key"].is_string()) {
      out.clean = false;
      continue;
    }
    out.records.push_back(std::move(j));
    out.lines.push_back(std::move(line));
  }
  return out;
}

ShardFile read_shard_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot be read");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_shard_lines(text, path.string());
}

}  // namespace coons
