// Reading a JSON file at the input edge: an unreadable file or malformed JSON is an InputError
// naming the file (and the byte where parsing stopped).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace coons {

nlohmann::json read_json_file(const std::string& path);

}  // namespace coons
