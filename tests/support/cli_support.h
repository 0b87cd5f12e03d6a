// Driving the real `coons` binary from the CLI tests: where it and the data are, quoting a path
// for the shell, running it with stdout, stderr and the exit status captured, reading a file back.
#pragma once

#include <string>

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

}  // namespace coons::test
