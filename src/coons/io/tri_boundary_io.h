// Reading the triangular boundary JSON of docs/formats.md ("Triangular boundary files"):
//   {"name", "type": "triangle", "degree": n, "sides": [s0, s1, s2]}, each side n+1 points,
// s0 the side k = 0 from b[n][0][0] to b[0][n][0], s1 the side i = 0 from b[0][n][0] to b[0][0][n],
// s2 the side j = 0 from b[0][0][n] to b[n][0][0]; the last point of a side is the first of the next.
// Every violation throws InputError "FILE: FIELD: reason" (a corner names both copies and the gap).
// Also the JSON forms of a triangular net (the rows of the contract) and of its boundary.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "coons/tri/tri_net.h"

namespace coons {

struct TriBoundaryReadOptions {
  //! The copies of a corner must agree to this fraction of the sides' bounding-box diagonal.
  double corner_tolerance = 1e-9;
  //! 0: a model of any size; the searches ask for kMinModelSize (json_file.h).
  double min_model_size = 0;
};

//! True when `doc` is an object with "type": "triangle" (the one test of which reader applies).
bool is_triangle_document(const nlohmann::json& doc);
//! True when the file at `path` reads as JSON and is_triangle_document holds. Unreadable or
//! malformed files give false: the rectangular reader then reports them.
bool is_triangle_file(const std::string& path);

//! Parse and validate; `source` names the input in error messages.
tri::TriBoundary parse_tri_boundary(const nlohmann::json& doc, const std::string& source,
                                    const TriBoundaryReadOptions& options = {});
//! Read a file and parse it (unreadable files and malformed JSON are InputErrors too).
tri::TriBoundary read_tri_boundary_file(const std::string& path, const TriBoundaryReadOptions& options = {});

//! The contract's rows: net[k][j] = b[n−k−j][j][k], k = 0 … n, j = 0 … n−k.
nlohmann::json tri_net_to_json(const tri::TriNet& net);
//! A triangular boundary file holding the three sides (reads back with parse_tri_boundary).
nlohmann::json tri_boundary_to_json(const tri::TriBoundary& boundary);

}  // namespace coons
