#include "support/cli_support.h"

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

}  // namespace coons::test
