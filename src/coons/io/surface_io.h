// Reading the curve and surface descriptions of docs/formats.md ("Curves and surfaces (JSON)").
// Curves: {"bezier": [[x,y,z], …]} | {"expr": ["x(t)", "y(t)", "z(t)"], "interval": [t1, t2]}
// (extensions: {"point": [x,y,z]}, {"hermite": [p0, p1, d0, d1]} — a Ferguson cubic).
// Surfaces: {"type": T, …data…, "name"?, "comment"?, "source"?} with T one of ruled, sectorial,
// bilinear, conoid, bilinear-coons, hermite-coons, ferguson, hermite16, general-coons, bezier
// (fields in surface_fields() and docs/formats.md). Every violation — missing or unknown field, wrong
// count, non-finite number, an expression that does not parse or is not finite on its interval,
// corners that disagree, incompatible general-Coons data, a conoid line parallel to its plane —
// throws InputError naming the file, the field (e.g. "bottom.expr[1]", "corners[2]",
// "du_left") and the reason (with the corner, the condition and the gap where one applies).
// Based on: docs/formats.md ("Curves and surfaces", "Errors"); the compatibility conditions of LN1.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <utility>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/surfaces/surface.h"

namespace coons {

struct SurfaceReadOptions {
  //! Corners must agree to this fraction of the boundary's size (docs/formats.md: 1e-9).
  double corner_tolerance = 1e-9;
  //! Tangent and twist conditions of general-coons: this fraction of max(size, ‖vectors‖)
  //! (analytic curves have numerical derivatives, accurate to ≈ 1e-10).
  double derivative_tolerance = 1e-7;
  //! A model whose largest coordinate magnitude is below this (and not 0) is an InputError naming
  //! the point; 0 accepts any. `surface` and `join` use kMinModelSize (json_file.h): below it the
  //! curvatures and squared distances they report leave the doubles (a seam 1.4e-170 wide read as
  //! closed, a Gaussian curvature of 1e320 as 0).
  double min_model_size = 0;
};

struct SurfaceFile {
  std::string name;  //!< "name", else the file's stem
  Surface surface;
  //! Every compatibility condition checked (Coons types), with its gap: all within tolerance.
  std::vector<CompatibilityCondition> conditions;
  double size = 0;  //!< what the tolerances were relative to (the boundary's bounding-box diagonal)
};

//! One curve; `field` names it in errors.
Curve parse_curve(const nlohmann::json& j, const std::string& source, const std::string& field);

SurfaceFile parse_surface(const nlohmann::json& doc, const std::string& source, const SurfaceReadOptions& options = {});

//! Unreadable files and malformed JSON are InputErrors too.
SurfaceFile read_surface_file(const std::string& path, const SurfaceReadOptions& options = {});

//! The data fields of each type (besides "type", "name", "comment", "source").
std::vector<std::pair<std::string, std::vector<std::string>>> surface_fields();

}  // namespace coons
