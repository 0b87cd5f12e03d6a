// A Coons boundary from four edges of a STEP file (coons import-step): the outer wire of face K or
// four edges chosen by index, in any order and orientation, chained into a loop by OpenCASCADE's
// ShapeAnalysis_WireOrder; each edge's 3D curve trimmed to its parameter range and converted to a
// B-spline (GeomConvert), then made compatible (bottom/top and left/right: same degree and knots
// over [0, 1], by exact degree elevation and knot insertion). Corner gaps (end of one edge to the
// start of the next) are reported and, when within the tolerance, closed at their midpoints.
// Sides: bottom = the first of --edges in its own direction, or for a face the edge along v = v_min
// of the face's parameter rectangle running towards increasing u (the first edge of the wire when
// no edge lies there), right = the next edge of the chain, top and left the last two, reversed, so that
// bottom(1) = right(0), right(1) = top(1), top(0) = left(1), left(0) = bottom(0) (docs/math.md §1).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coons/surfaces/bspline_surface.h"

namespace coons::cad {

struct StepImportOptions {
  int face = -1;                //!< 0-based, in OpenCASCADE's order of the file's faces (-1: not given)
  std::vector<int> edges;       //!< a, b, c, d: 0-based, in OpenCASCADE's order of the file's edges
  double gap_tolerance = 1e-6;  //!< largest corner gap, as a fraction of the bounding-box diagonal of the poles
  //! Exactly one of face and edges (four distinct indices ≥ 0), tolerance finite and ≥ 0.
  [[nodiscard]] bool is_valid(std::string* why) const;
};

//! The member of StepImportOptions at fault, so that a caller can name what set it; kFaceOrEdges:
//! both or neither of face and edges are given.
enum class StepImportOptionsField { kNone, kFace, kEdges, kFaceOrEdges, kGapTolerance };

struct StepImportOptionsProblem {
  StepImportOptionsField field = StepImportOptionsField::kNone;
  std::string reason;  //!< without the member's name: "must be finite and >= 0"
};

//! The first rule of StepImportOptions::is_valid that `options` breaks (field kNone: none).
StepImportOptionsProblem options_problem(const StepImportOptions& options);

struct CornerGapNote {
  std::string corner;  //!< "bottom-left", "bottom-right", "top-left", "top-right"
  std::string edges;   //!< e.g. "edge 3 -> edge 0"
  double gap = 0;      //!< distance between the two curve ends, in model units
};

struct StepImport {
  BSplineBoundary boundary;  //!< compatible, over [0, 1], corners shared exactly
  std::vector<CornerGapNote> gaps;
  double max_gap = 0;
  double diagonal = 0;                   //!< bounding-box diagonal of the poles (the gap tolerance's unit)
  std::vector<int> edge_indices;         //!< the file's edge index of bottom, right, top, left
  std::vector<bool> edge_reversed;       //!< whether that side runs against the edge's curve
  std::vector<CompatibilityNote> notes;  //!< what compatible_boundary changed
  int file_faces = 0, file_edges = 0;
  std::string unit;  //!< the file's length unit, in which the points are given (read_step_shape)
  //! Every side a single span (knots only at 0 and 1): the boundary is a Bézier boundary.
  [[nodiscard]] bool is_bezier() const;
};

//! Reads `path` and builds the boundary. Throws InputError(path, field, reason) for an unreadable
//! file, a face or edge index out of range (field "face K", "edge K"), a face whose outer wire has
//! other than 4 edges, an edge without a 3D curve, a rational edge (not supported), and a corner
//! gap above the tolerance (field names the corner); std::invalid_argument unless
//! options.is_valid() (the caller checks them first, naming what set them: options_problem).
StepImport import_step_boundary(const std::string& path, const StepImportOptions& options);

//! The boundary file (docs/formats.md): the Bézier form ("degree", four sides) when is_bezier(),
//! else the B-spline form with "degree_spline", "knots_u" and "knots_v"; "name", "source" and a
//! "import" note with the corner gaps and the chain.
nlohmann::json boundary_document(const StepImport& import, const std::string& name, const std::string& source);

//! The import's note for a report: file counts, chain, gaps, compatibility notes.
nlohmann::json import_note(const StepImport& import);

}  // namespace coons::cad
