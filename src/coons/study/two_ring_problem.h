// The two-ring mask problem of a boundary file, for the C1 family's weight search (search-alpha
// --parameter weight, the study's C1 column): the 5×5 stencil needs two data rings, given as
// "ribbons" with the sides or as a net with "rings" ≥ 2. A file with one data ring has no such
// problem: the result then says which field is missing ("ribbons" for the sides form, "rings" for
// the net form) and why. Sizes: a copy of the net.
#pragma once

#include <optional>
#include <string>

#include "coons/io/boundary_io.h"
#include "coons/mask/stencil_problem.h"

namespace coons {

struct TwoRingProblem {
  std::optional<StencilProblem> problem;  //!< present when the file has two (or more) data rings
  std::string field;                      //!< otherwise: "ribbons" or "rings"
  std::string reason;                     //!< and why, one line, no trailing period
};

//! From the file's stencil_problem (boundary_io.h): its net, rings and free grid when it has two
//! data rings or more. Never throws.
TwoRingProblem two_ring_problem(const BoundaryFile& file);

}  // namespace coons
