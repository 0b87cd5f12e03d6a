// Output files are written whole or not at all: each goes to a temporary name beside its target
// and is renamed into place when complete, so a failure never leaves a half-written file.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace coons {

//! Calls write(stream) on a temporary file, then renames it to `path`. Throws InputError
//! (naming `path`) when the file cannot be written.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace coons
