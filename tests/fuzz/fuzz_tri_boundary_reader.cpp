// libFuzzer target: the triangular boundary reader (docs/formats.md "Triangular boundary files")
// from raw bytes, as `coons tri-solve FILE` (and a study over a triangle file) reads it: bounded
// JSON parse, the dispatch test is_triangle_document, then parse_tri_boundary with the default
// options and with the searches' min_model_size. An InputError is the expected answer to bad
// bytes; anything else escaping (another exception, a crash, UB) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/tri_boundary_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json doc = coons::parse_json_text(text, "fuzz.json");
    (void)coons::is_triangle_document(doc);
    coons::TriBoundaryReadOptions options;
    const coons::tri::TriBoundary b = coons::parse_tri_boundary(doc, "fuzz.json", options);
    // what the writers do with an accepted boundary: it must read back
    (void)coons::parse_tri_boundary(coons::tri_boundary_to_json(b), "fuzz.json", options);
    options.min_model_size = coons::kMinModelSize;
    (void)coons::parse_tri_boundary(doc, "fuzz.json", options);
  } catch (const coons::InputError&) {
  }
  return 0;
}
