#include "coons/study/task_key.h"

#include <fmt/format.h>

#include <cstdint>

namespace coons {

std::string fnv1a_hex(const std::string& text) {
  std::uint64_t h = 14695981039346656037ULL;
  for (const unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", h);
}

std::string task_key(const nlohmann::json& inputs) { return fnv1a_hex(inputs.dump()); }

std::string files_task_key(const nlohmann::json& study, std::size_t index, const std::string& content_hash) {
  nlohmann::json inputs = study;
  inputs.erase("files");
  inputs["file"] = study.at("files").at(index);
  inputs["content"] = content_hash;
  return task_key(inputs);
}

}  // namespace coons
