// Reading the boundary JSON of docs/formats.md: four sides (bottom/top: m+1 points, left/right: n+1)
// or a full "net" (m+1 rows of n+1 points). Every violation throws InputError naming the file,
// the field and the reason.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "coons/net/control_net.h"

namespace coons {

struct BoundaryReadOptions {
  //! Corners must agree to this fraction of the bounding-box diagonal (docs/formats.md: 1e-9).
  double corner_tolerance = 1e-9;
};

struct BoundaryFile {
  Boundary boundary;              //!< always present (from the sides or the net's frame)
  std::optional<ControlNet> net;  //!< present when the file held "net"
};

//! Parse and validate. `source` names the input in error messages (a path or "<stdin>").
BoundaryFile parse_boundary(const nlohmann::json& doc, const std::string& source,
                            const BoundaryReadOptions& options = {});

//! Read a file and parse it; unreadable files and malformed JSON are InputErrors too.
BoundaryFile read_boundary_file(const std::string& path, const BoundaryReadOptions& options = {});

}  // namespace coons
