// Where a report comes from: the command line, the date (UTC, ISO 8601), coons's version and the
// git revision it was configured from (captured by CMake, no `git` at run time), and the versions
// of Eigen and Ceres. Nothing here runs a program.
#pragma once

#include <chrono>
#include <string>

namespace coons {

struct Provenance {
  std::string command_line;
  std::string date;          //!< e.g. 2026-11-22T16:17:09Z
  std::string version;       //!< coons's version
  std::string git_revision;  //!< empty when the build was configured outside a git checkout
  std::string eigen_version, ceres_version;
};

//! YYYY-MM-DDTHH:MM:SSZ of a time point.
std::string utc_iso8601(std::chrono::system_clock::time_point t);

//! The provenance of a report made now by this binary.
Provenance current_provenance(const std::string& command_line);

}  // namespace coons
