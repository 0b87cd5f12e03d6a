#include "two_ring_problem.h"

namespace coons {

TwoRingProblem two_ring_problem(const BoundaryFile& file) {
  TwoRingProblem out;
  if (file.rings >= 2) {
    out.problem = stencil_problem(file);
    return out;
  }
  if (file.net) {
    out.field = "rings";
    out.reason = "the net has one data ring; the C1 family's 5x5 stencil needs two (\"rings\": 2)";
  } else {
    out.field = "ribbons";
    out.reason = "missing: the C1 family's 5x5 stencil needs the second ring of data";
  }
  return out;
}

}  // namespace coons
