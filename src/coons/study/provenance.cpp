#include "provenance.h"

#include <ceres/version.h>
#include <fmt/format.h>

#include <Eigen/Core>
#include <ctime>

#include "coons/config.h"
#include "coons/study/build_info.h"

namespace coons {

std::string utc_iso8601(std::chrono::system_clock::time_point t) {
  const std::time_t seconds = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  return fmt::format("{:04d}-{:02d}-{:02d}T{:02d}:{:02d}:{:02d}Z", utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday,
                     utc.tm_hour, utc.tm_min, utc.tm_sec);
}

Provenance current_provenance(const std::string& command_line) {
  Provenance p;
  p.command_line = command_line;
  p.date = utc_iso8601(std::chrono::system_clock::now());
  p.version = COONS_VERSION;
  p.git_revision = std::string(COONS_GIT_REVISION) == "unknown" ? "" : COONS_GIT_REVISION;
  p.eigen_version = fmt::format("{}.{}.{}", EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION);
  p.ceres_version = CERES_VERSION_STRING;
  return p;
}

}  // namespace coons
