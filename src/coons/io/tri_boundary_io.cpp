#include "tri_boundary_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons {

using nlohmann::json;

namespace {

Eigen::RowVector3d read_point(const json& p, const std::string& source, const std::string& field) {
  if (!p.is_array()) throw InputError(source, field, "a point must be an array of 3 numbers");
  if (p.size() != 3) throw InputError(source, field, fmt::format("a point must have 3 coordinates, not {}", p.size()));
  Eigen::RowVector3d out;
  for (int c = 0; c < 3; ++c) out(c) = json_coordinate(p[c], source, field, fmt::format("coordinate {}", c));
  return out;
}

std::string index_triple(int i, int j, int k) { return fmt::format("({},{},{})", i, j, k); }

}  // namespace

bool is_triangle_document(const json& doc) {
  if (!doc.is_object()) return false;
  const auto type = doc.find("type");
  return type != doc.end() && type->is_string() && type->get<std::string>() == "triangle";
}

bool is_triangle_file(const std::string& path) {
  try {
    return is_triangle_document(read_json_file(path));
  } catch (const InputError&) {
    return false;
  }
}

tri::TriBoundary parse_tri_boundary(const json& doc, const std::string& source, const TriBoundaryReadOptions& options) {
  auto fail = [&](const std::string& field, const std::string& reason) { throw InputError(source, field, reason); };
  if (!doc.is_object()) fail("", "the top level must be a JSON object");
  if (!is_triangle_document(doc)) fail("type", "must be \"triangle\" for a triangular boundary");
  tri::TriBoundary b;
  b.name = std::filesystem::path(source).stem().string();
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) fail("name", "must be a string");
    b.name = doc["name"].get<std::string>();
  }
  // The fields of the rectangular forms mean something there (a B-spline's knots, a whole net, a
  // second data ring): here they were ignored, and a triangle with knots solved as a Bézier one.
  // A triangle's solve report has "net" (its rows) and no "sides": it is not read back.
  if (doc.contains("net") && !doc.contains("sides"))
    fail("net", "a triangular net (a solve report?) is not read back; give the boundary file with \"sides\"");
  for (const char* field : {"knots_u", "knots_v", "degree_spline", "bspline", "net", "rings", "free", "ribbons",
                            "bottom", "top", "left", "right", "curves"})
    if (doc.contains(field))
      fail(field, "belongs to a rectangular boundary; a triangular one has \"sides\" only (docs/formats.md)");
  if (!doc.contains("sides")) fail("sides", "missing");
  const json& sides = doc["sides"];
  if (!sides.is_array() || sides.size() != 3) fail("sides", "must be an array of 3 sides (arrays of points)");
  for (int s = 0; s < 3; ++s) {
    const std::string field = fmt::format("sides[{}]", s);
    if (!sides[s].is_array()) fail(field, "must be an array of points");
    if (sides[s].size() < 2) fail(field, "needs at least 2 points (degree >= 1)");
    if (s > 0 && sides[s].size() != sides[0].size())
      fail(field, fmt::format("has {} points, sides[0] has {} (every side needs degree + 1)", sides[s].size(),
                              sides[0].size()));
  }
  b.n = int(sides[0].size()) - 1;
  if (b.n > tri::kMaxTriDegree)
    fail(doc.contains("degree") ? "degree" : "sides[0]",
         fmt::format("degree {} is above {}, the largest for a triangular boundary (its exact energies use dense "
                     "Gram matrices that grow as the degree^4)",
                     b.n, tri::kMaxTriDegree));
  if (doc.contains("degree")) {
    const auto degree = json_integer(doc["degree"], source, "degree", 1, tri::kMaxTriDegree);
    if (degree != b.n)
      fail("degree", fmt::format("says {} but the sides have {} points (degree {})", degree, b.n + 1, b.n));
  }
  for (int s = 0; s < 3; ++s) {
    b.sides[s].resize(b.n + 1, 3);
    for (int q = 0; q <= b.n; ++q)
      b.sides[s].row(q) = read_point(sides[s][q], source, fmt::format("sides[{}][{}]", s, q));
  }
  LargestPoint largest;
  for (int s = 0; s < 3; ++s) largest.add(fmt::format("sides[{}]", s), b.sides[s]);
  largest.require(options.min_model_size, source);
  // The corners: side s starts where side s − 1 ends.
  Eigen::RowVector3d lo = b.sides[0].colwise().minCoeff(), hi = b.sides[0].colwise().maxCoeff();
  for (int s = 1; s < 3; ++s) {
    lo = lo.cwiseMin(b.sides[s].colwise().minCoeff());
    hi = hi.cwiseMax(b.sides[s].colwise().maxCoeff());
  }
  const double tolerance = options.corner_tolerance * std::max((hi - lo).norm(), 1e-300);
  const int n = b.n;
  const std::string corners[3] = {index_triple(n, 0, 0), index_triple(0, n, 0), index_triple(0, 0, n)};
  for (int s = 0; s < 3; ++s) {
    const int before = (s + 2) % 3;
    const double gap = (b.sides[s].row(0) - b.sides[before].row(n)).norm();
    if (gap > tolerance)
      fail(fmt::format("sides[{}][0]", s),
           fmt::format("corner {} differs from sides[{}][{}] by {:.3g} (tolerance {:.3g})", corners[s], before, n, gap,
                       tolerance));
  }
  return b;
}

tri::TriBoundary read_tri_boundary_file(const std::string& path, const TriBoundaryReadOptions& options) {
  return parse_tri_boundary(read_json_file(path), path, options);
}

json tri_net_to_json(const tri::TriNet& net) {
  json rows = json::array();
  for (int k = 0; k <= net.n; ++k) {
    json row = json::array();
    const Eigen::MatrixX3d points = tri::net_row(net, k);
    for (Eigen::Index j = 0; j < points.rows(); ++j) row.push_back({points(j, 0), points(j, 1), points(j, 2)});
    rows.push_back(std::move(row));
  }
  return rows;
}

json tri_boundary_to_json(const tri::TriBoundary& boundary) {
  json sides = json::array();
  for (const auto& side : boundary.sides) {
    json points = json::array();
    for (Eigen::Index q = 0; q < side.rows(); ++q) points.push_back({side(q, 0), side(q, 1), side(q, 2)});
    sides.push_back(std::move(points));
  }
  return {{"name", boundary.name}, {"type", "triangle"}, {"degree", boundary.n}, {"sides", sides}};
}

}  // namespace coons
