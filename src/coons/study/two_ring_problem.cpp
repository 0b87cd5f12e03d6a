#include "two_ring_problem.h"

#include <algorithm>

#include "coons/io/json_file.h"

namespace coons {

// The boundary reader of this version ignores "rings": the net form's "rings" is read here, and the
// sides form has no second ring.
TwoRingProblem two_ring_problem(const std::string& path, const BoundaryFile& file) {
  TwoRingProblem out;
  if (!file.net) {
    out.field = "ribbons";
    out.reason = "missing: the C1 family's 5x5 stencil needs a second ring of data (or a net with \"rings\": 2)";
    return out;
  }
  const nlohmann::json doc = read_json_file(path);
  const int most = std::min(file.net->m, file.net->n) / 2 + 1;
  const int rings = doc.contains("rings") ? int(json_integer(doc.at("rings"), path, "rings", 1, most)) : 1;
  if (rings < 2) {
    out.field = "rings";
    out.reason = "the net has one data ring; the C1 family's 5x5 stencil needs two (\"rings\": 2)";
    return out;
  }
  out.problem = rings_problem(*file.net, rings);
  return out;
}

}  // namespace coons
