#include "boundary_curves.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/surface_io.h"

namespace coons {

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

FittedBoundary fit_boundary_or_throw(const std::vector<Curve>& sides, int m, int n, const std::string& name,
                                     const std::string& source) {
  FittedBoundary f = fit_boundary(sides, m, n, name);
  // The reader checked 65 samples of each curve; a pole between them shows in the fit's samples.
  const Eigen::MatrixX3d* fitted[] = {&f.boundary.bottom, &f.boundary.top, &f.boundary.left, &f.boundary.right};
  const char* names[] = {"bottom", "top", "left", "right"};
  for (int k = 0; k < 4; ++k)
    if (!fitted[k]->allFinite())
      throw InputError(source, std::string("curves.") + names[k],
                       fmt::format("is not finite between the samples the reader checks (a pole?): its Bezier fit "
                                   "of degree {} is not finite",
                                   k < 2 ? m : n));
  if (!std::isfinite(f.max_deviation))
    throw InputError(source, "curves",
                     "a curve is not finite between the samples the reader checks (a pole?): the deviation of its "
                     "Bezier fit is not finite");
  if (!f.corners_meet)
    throw InputError(source, f.corner_gap.corner + " corner",
                     fmt::format("the curves meet with a gap of {:.3g}", f.corner_gap.gap));
  return f;
}

}  // namespace coons
