// libFuzzer target: the boundary/net reader (docs/formats.md "Boundary (JSON)") from raw bytes, as
// `coons solve FILE` reads it: bounded JSON parse, then validation. An InputError is the expected
// answer to bad bytes; anything else escaping (another exception, a crash, UB) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const coons::BoundaryFile f = coons::parse_boundary(coons::parse_json_text(text, "fuzz.json"), "fuzz.json");
    (void)f;
  } catch (const coons::InputError&) {
  }
  return 0;
}
