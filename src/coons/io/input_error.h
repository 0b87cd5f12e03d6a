// The one exception type of coons: bad input at the edge (files, command-line values).
// what() is the one-line message the CLI prints after "error: ": "FILE: FIELD: REASON".
#pragma once

#include <stdexcept>
#include <string>

namespace coons {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string field, std::string reason)
      : std::runtime_error(file + ": " + (field.empty() ? "" : field + ": ") + reason),
        file_(std::move(file)),
        field_(std::move(field)),
        reason_(std::move(reason)) {}

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] const std::string& field() const { return field_; }
  [[nodiscard]] const std::string& reason() const { return reason_; }

 private:
  std::string file_, field_, reason_;
};

}  // namespace coons
