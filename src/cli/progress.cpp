// Phases of a command: progress on a terminal, seconds for the report's "timing" block.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "common.h"

namespace coons::cli {

namespace {
double now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Phases::Phases(std::string command) : command_(std::move(command)), tty_(isatty(STDERR_FILENO) != 0) {}

Phases::~Phases() {
  if (tty_ && printed_) fmt::print(stderr, "\r\033[K");
}

void Phases::close() {
  if (current_.empty()) return;
  const double elapsed = now_seconds() - started_;
  for (auto& [name, seconds] : seconds_)
    if (name == current_) {
      seconds += elapsed;
      current_.clear();
      return;
    }
  seconds_.emplace_back(current_, elapsed);
  current_.clear();
}

void Phases::start(const std::string& phase, const std::string& detail) {
  close();
  current_ = phase;
  started_ = now_seconds();
  note(detail);
}

void Phases::note(const std::string& detail) {
  if (!tty_) return;
  fmt::print(stderr, "\r\033[Kcoons {}: {}{}", command_, current_, detail.empty() ? "" : " " + detail);
  std::fflush(stderr);
  printed_ = true;
}

nlohmann::json Phases::timing() {
  close();
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, seconds] : seconds_) out[name] = seconds;
  return out;
}

}  // namespace coons::cli
