// libFuzzer target: the inputs of `coons solve FILE --mask file:PATH`: a stencil file
// (docs/formats.md, {"weights": ...}, stencil_from_json) and a boundary file in any form ("net" with
// "rings" and "free", sides with "ribbons", B-spline knots), then the problem check the CLI runs
// with the two together (stencil_problem + require_valid_problem), and the file's "target" block
// (target_from_json) plus a "--target" string taken from the document's "spec" field
// (cli/search_inputs.h: resolve_target, for the sphere:/cylinder:/plane: forms). One document carries all of them: the
// boundary reader ignores "weights" and "spec". An InputError is the expected answer to bad bytes;
// anything else escaping (another exception, a crash, UB) is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "cli/search_inputs.h"
#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/stencil_json.h"
#include "coons/study/target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  nlohmann::json doc;
  try {
    doc = coons::parse_json_text(text, "fuzz.json");
  } catch (const coons::InputError&) {
    return 0;
  }
  std::optional<coons::Stencil> stencil;
  try {
    stencil = coons::stencil_from_json(doc, "stencil.json");
  } catch (const coons::InputError&) {
  }
  try {
    (void)coons::target_from_json(doc, "fuzz.json", 5);
  } catch (const coons::InputError&) {
  }
  std::optional<coons::BoundaryFile> file;
  try {
    file = coons::parse_boundary(doc, "fuzz.json");
  } catch (const coons::InputError&) {
  }
  if (!file) return 0;
  try {
    if (doc.is_object() && doc.contains("spec") && doc["spec"].is_string()) {
      const std::string spec = doc["spec"].get<std::string>();
      if (spec.rfind("sphere:", 0) == 0 || spec.rfind("cylinder:", 0) == 0 || spec.rfind("plane:", 0) == 0)
        (void)coons::cli::resolve_target(spec, "fuzz.json", file->boundary, 5);
    }
  } catch (const coons::InputError&) {
  }
  if (!stencil) return 0;
  try {
    const coons::StencilProblem problem = coons::stencil_problem(*file);
    coons::require_valid_problem(problem, *stencil, "fuzz.json");
  } catch (const coons::InputError&) {
  }
  return 0;
}
