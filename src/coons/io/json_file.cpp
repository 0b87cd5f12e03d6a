#include "json_file.h"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "coons/io/input_error.h"

namespace coons {

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  try {
    return nlohmann::json::parse(buffer.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(path, "", fmt::format("malformed JSON at byte {}", e.byte));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "", fmt::format("unreadable JSON ({})", e.what()));
  }
}

}  // namespace coons
