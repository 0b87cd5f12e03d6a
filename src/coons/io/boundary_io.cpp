#include "boundary_io.h"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons {

namespace {

using nlohmann::json;

class Parser {
 public:
  explicit Parser(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw InputError(source_, field, reason);
  }

  Eigen::RowVector3d point(const json& p, const std::string& field) const {
    if (!p.is_array()) fail(field, "a point must be an array of 3 numbers");
    if (p.size() != 3) fail(field, fmt::format("a point must have 3 coordinates, not {}", p.size()));
    Eigen::RowVector3d out;
    for (int c = 0; c < 3; ++c) out(c) = json_coordinate(p[c], source_, field, fmt::format("coordinate {}", c));
    return out;
  }

  Eigen::MatrixX3d points(const json& doc, const std::string& field) const {
    if (!doc.contains(field)) fail(field, "missing");
    const json& list = doc[field];
    if (!list.is_array()) fail(field, "must be an array of points");
    Eigen::MatrixX3d out(list.size(), 3);
    for (size_t k = 0; k < list.size(); ++k) out.row(k) = point(list[k], fmt::format("{}[{}]", field, k));
    return out;
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

void check_degree(const Parser& p, const json& doc, int m, int n) {
  if (!doc.contains("degree")) return;
  const json& d = doc["degree"];
  if (!d.is_array() || d.size() != 2) p.fail("degree", "must be [m, n] with two integers");
  // Range-checked before narrowing: 4294967299 must not read as 3.
  const auto dm = json_integer(d[0], p.source(), "degree[0]", 1, std::numeric_limits<int>::max());
  const auto dn = json_integer(d[1], p.source(), "degree[1]", 1, std::numeric_limits<int>::max());
  if (dm != m || dn != n) p.fail("degree", fmt::format("says [{}, {}] but the points give [{}, {}]", dm, dn, m, n));
}

}  // namespace

BoundaryFile parse_boundary(const json& doc, const std::string& source, const BoundaryReadOptions& options) {
  Parser p(source);
  if (!doc.is_object()) p.fail("", "the top level must be a JSON object");
  BoundaryFile out;
  std::string name = std::filesystem::path(source).stem().string();
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) p.fail("name", "must be a string");
    name = doc["name"].get<std::string>();
  }

  if (doc.contains("net")) {
    const json& rows = doc["net"];
    if (!rows.is_array() || rows.size() < 2) p.fail("net", "must hold at least 2 rows of points (m >= 1)");
    const int m = int(rows.size()) - 1;
    if (!rows[0].is_array() || rows[0].size() < 2) p.fail("net[0]", "must hold at least 2 points (n >= 1)");
    const int n = int(rows[0].size()) - 1;
    ControlNet net(m, n);
    for (int i = 0; i <= m; ++i) {
      const std::string field = fmt::format("net[{}]", i);
      if (!rows[i].is_array()) p.fail(field, "must be an array of points");
      if (int(rows[i].size()) != n + 1)
        p.fail(field, fmt::format("has {} points, row 0 has {}", rows[i].size(), n + 1));
      for (int j = 0; j <= n; ++j) net.at(i, j) = p.point(rows[i][j], fmt::format("net[{}][{}]", i, j));
    }
    check_degree(p, doc, m, n);
    out.boundary = boundary_of(net, name);
    out.net = std::move(net);
    return out;
  }

  Boundary& b = out.boundary;
  b.name = name;
  b.bottom = p.points(doc, "bottom");
  b.top = p.points(doc, "top");
  b.left = p.points(doc, "left");
  b.right = p.points(doc, "right");
  if (b.bottom.rows() < 2) p.fail("bottom", "needs at least 2 points (m >= 1)");
  if (b.left.rows() < 2) p.fail("left", "needs at least 2 points (n >= 1)");
  b.m = int(b.bottom.rows()) - 1;
  b.n = int(b.left.rows()) - 1;
  if (b.top.rows() != b.bottom.rows())
    p.fail("top", fmt::format("has {} points, bottom has {} (both need m+1)", b.top.rows(), b.bottom.rows()));
  if (b.right.rows() != b.left.rows())
    p.fail("right", fmt::format("has {} points, left has {} (both need n+1)", b.right.rows(), b.left.rows()));
  check_degree(p, doc, b.m, b.n);

  const CornerGap gap = largest_corner_gap(b);
  const double tolerance = options.corner_tolerance * std::max(bounding_box_diagonal(b), 1e-300);
  if (gap.gap > tolerance)
    p.fail(gap.corner + " corner",
           fmt::format("the two sides meeting there disagree by {:.3g} (tolerance {:.3g})", gap.gap, tolerance));
  return out;
}

BoundaryFile read_boundary_file(const std::string& path, const BoundaryReadOptions& options) {
  return parse_boundary(read_json_file(path), path, options);
}

}  // namespace coons
