#include "boundary_fit.h"


#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "coons/curves/bezier_fit.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/surface_io.h"

namespace coons {

FittedBoundary fit_boundary(const std::vector<Curve>& sides, int m, int n, const std::string& name,
                            const std::string& source) {
  FittedBoundary out;
  Boundary& b = out.boundary;
  b.name = name;
  b.m = m;
  b.n = n;
  Eigen::MatrixX3d* targets[] = {&b.bottom, &b.top, &b.left, &b.right};
  for (int k = 0; k < 4; ++k) {
    const BezierFit fit = fit_bezier(sides[k], k < 2 ? m : n);
    *targets[k] = fit.curve.points;
    out.max_deviation = std::max(out.max_deviation, fit.max_deviation);
  }
  const CornerGap gap = largest_corner_gap(b);
  const double size = std::max(bounding_box_diagonal(b), 1e-300);
  if (gap.gap > 1e-9 * size)
    throw InputError(source, gap.corner + " corner", fmt::format("the curves meet with a gap of {:.3g}", gap.gap));
  // make the shared corners bit-identical (bottom and top are canonical)
  b.left.row(0) = b.bottom.row(0);
  b.right.row(0) = b.bottom.row(m);
  b.left.row(n) = b.top.row(0);
  b.right.row(n) = b.top.row(m);
  return out;
}

std::optional<std::vector<Curve>> read_boundary_curves(const std::string& path) {
  const nlohmann::json doc = read_json_file(path);
  if (!doc.is_object() || !doc.contains("curves")) return std::nullopt;
  const nlohmann::json& c = doc["curves"];
  if (!c.is_object()) throw InputError(path, "curves", "must be an object with bottom, top, left and right");
  std::vector<Curve> sides;
  for (const char* side : {"bottom", "top", "left", "right"}) {
    if (!c.contains(side)) throw InputError(path, std::string("curves.") + side, "missing");
    sides.push_back(parse_curve(c[side], path, std::string("curves.") + side));
  }
  return sides;
}

}  // namespace coons
