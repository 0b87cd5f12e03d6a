// libFuzzer target: the curve and surface reader (docs/formats.md "Curves and surfaces (JSON)"),
// including analytic expressions, from raw bytes. An InputError is the expected answer to bad
// bytes; anything else escaping (another exception, a crash, UB) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/surface_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const coons::SurfaceFile f = coons::parse_surface(coons::parse_json_text(text, "fuzz.json"), "fuzz.json");
    (void)f;
  } catch (const coons::InputError&) {
  }
  return 0;
}
