#include "boundary_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/stencil_json.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/net/coons_net.h"

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

  //! doc[key] as a list of points; errors name `prefix` + key (e.g. "ribbons.left[2]").
  Eigen::MatrixX3d points(const json& doc, const std::string& key, const std::string& prefix = "") const {
    const std::string field = prefix + key;
    if (!doc.contains(key)) fail(field, "missing");
    const json& list = doc[key];
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

// The number of rings of an (m+1)×(n+1) net (the innermost may be a row, a column or a point).
int rings_of(int m, int n) { return std::min(m, n) / 2 + 1; }

int parse_rings(const Parser& p, const json& doc, int m, int n) {
  if (!doc.contains("rings")) return 1;
  const int most = rings_of(m, n);
  const auto rings = json_integer(doc["rings"], p.source(), "rings", 1, std::numeric_limits<int>::max());
  if (rings > most)
    p.fail("rings", fmt::format("{} data rings, but a net of degree ({}, {}) has only {}", rings, m, n, most));
  return int(rings);
}

double points_diagonal(const std::vector<const Eigen::MatrixX3d*>& lists) {
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::RowVector3d hi = -lo;
  for (const auto* list : lists)
    if (list->rows() > 0) {
      lo = lo.cwiseMin(list->colwise().minCoeff());
      hi = hi.cwiseMax(list->colwise().maxCoeff());
    }
  return (hi.array() >= lo.array()).all() ? scaled_norm(hi - lo) : 0.0;
}

Ribbons parse_ribbons(const Parser& p, const json& doc, const Boundary& b, double corner_tolerance) {
  const json& r = doc["ribbons"];
  if (!r.is_object())
    p.fail("ribbons", "must be an object with \"bottom\", \"top\", \"left\" and \"right\" (the second ring)");
  if (b.m < 4 || b.n < 4)
    p.fail("ribbons",
           fmt::format("need degree >= 4 in both directions (two data rings around at least one free point), the "
                       "sides give ({}, {}); write a smaller net in the \"net\" form with \"rings\"",
                       b.m, b.n));
  Ribbons out;
  out.bottom = p.points(r, "bottom", "ribbons.");
  out.top = p.points(r, "top", "ribbons.");
  out.left = p.points(r, "left", "ribbons.");
  out.right = p.points(r, "right", "ribbons.");
  const int m = b.m, n = b.n;
  const std::pair<const Eigen::MatrixX3d*, const char*> lists[] = {
      {&out.bottom, "bottom"}, {&out.top, "top"}, {&out.left, "left"}, {&out.right, "right"}};
  for (const auto& [list, name] : lists) {
    const int want = (name[0] == 'b' || name[0] == 't') ? m + 1 : n + 1;
    if (list->rows() != want)
      p.fail(fmt::format("ribbons.{}", name),
             fmt::format("has {} points, the {} side has {} (a ribbon runs along its side)", list->rows(),
                         name[0] == 'b' || name[0] == 't' ? "bottom" : "left", want));
  }
  // Every point two of the lists share: (field, its value, what else gives it, that value).
  struct Shared {
    std::string field;
    Eigen::RowVector3d value;
    std::string other;
    Eigen::RowVector3d other_value;
  };
  const Shared shared[] = {
      {"ribbons.bottom[0]", out.bottom.row(0), "left[1]", b.left.row(1)},
      {fmt::format("ribbons.bottom[{}]", m), out.bottom.row(m), "right[1]", b.right.row(1)},
      {"ribbons.top[0]", out.top.row(0), fmt::format("left[{}]", n - 1), b.left.row(n - 1)},
      {fmt::format("ribbons.top[{}]", m), out.top.row(m), fmt::format("right[{}]", n - 1), b.right.row(n - 1)},
      {"ribbons.left[0]", out.left.row(0), "bottom[1]", b.bottom.row(1)},
      {fmt::format("ribbons.left[{}]", n), out.left.row(n), "top[1]", b.top.row(1)},
      {"ribbons.right[0]", out.right.row(0), fmt::format("bottom[{}]", m - 1), b.bottom.row(m - 1)},
      {fmt::format("ribbons.right[{}]", n), out.right.row(n), fmt::format("top[{}]", m - 1), b.top.row(m - 1)},
      {"ribbons.left[1]", out.left.row(1), "ribbons.bottom[1]", out.bottom.row(1)},
      {fmt::format("ribbons.left[{}]", n - 1), out.left.row(n - 1), "ribbons.top[1]", out.top.row(1)},
      {"ribbons.right[1]", out.right.row(1), fmt::format("ribbons.bottom[{}]", m - 1), out.bottom.row(m - 1)},
      {fmt::format("ribbons.right[{}]", n - 1), out.right.row(n - 1), fmt::format("ribbons.top[{}]", m - 1),
       out.top.row(m - 1)},
  };
  const double diagonal =
      points_diagonal({&b.bottom, &b.top, &b.left, &b.right, &out.bottom, &out.top, &out.left, &out.right});
  const double tolerance = corner_tolerance * std::max(diagonal, 1e-300);
  for (const Shared& s : shared) {
    const double gap = scaled_norm(s.value - s.other_value);
    if (!(gap <= tolerance))
      p.fail(s.field, fmt::format("is the same net point as {}, but they disagree by {:.3g} (tolerance {:.3g})",
                                  s.other, gap, tolerance));
  }
  return out;
}

}  // namespace

void LargestPoint::add(const std::string& name, const Eigen::Ref<const Eigen::MatrixX3d>& list) {
  for (Eigen::Index k = 0; k < list.rows(); ++k)
    if (const double v = list.row(k).cwiseAbs().maxCoeff(); v > magnitude) {
      magnitude = v;
      field = fmt::format("{}[{}]", name, k);
    }
}

void LargestPoint::require(double min_size, const std::string& source) const {
  require_model_size(magnitude, min_size, source, field);
}

const std::vector<std::string>& boundary_file_fields() {
  static const std::vector<std::string> fields = {
      "name",    "degree", "bottom", "top",     "left",    "right", "net",         "rings",  "free",
      "ribbons", "curves", "target", "knots_u", "knots_v", "type",  "description", "source", "degree_spline"};
  return fields;
}

BoundaryFile parse_boundary(const json& doc, const std::string& source, const BoundaryReadOptions& options) {
  Parser p(source);
  if (!doc.is_object()) p.fail("", "the top level must be a JSON object");
  // A file of another kind would otherwise fail on its first missing side ("bottom: missing").
  // One with a "net" is still a net file (its other fields are ignored, docs/formats.md).
  const bool triangle = is_triangle_document(doc);
  if (const auto type = doc.find("type"); type != doc.end() && (triangle || !doc.contains("net"))) {
    if (triangle)
      p.fail("type",
             "\"triangle\": a triangular boundary, which this command does not take (rectangular boundaries "
             "only)");
    const std::string what = type->is_string() ? "\"" + type->get<std::string>().substr(0, 40) + "\""
                                               : std::string("a JSON ") + type->type_name();
    p.fail("type", fmt::format("{}: a rectangular boundary file has no \"type\" (a triangular one has \"triangle\"; "
                               "surface descriptions are read by `coons surface`)",
                               what));
  }
  BoundaryFile out;
  out.misspelt = misspelt_fields(doc, boundary_file_fields());
  // A misspelling of what the file lacks is the error itself ("NET" with no net and no sides was
  // reported as "bottom: missing", a field never meant), not a warning after another one.
  const bool has_net = doc.contains("net");
  for (const MisspeltField& m : out.misspelt) {
    const bool side = m.known == "bottom" || m.known == "top" || m.known == "left" || m.known == "right";
    if (!has_net && !doc.contains(m.known) && (m.known == "net" || side))
      p.fail(m.given, fmt::format("unknown field; did you mean \"{}\"? (the file has no \"{}\")", m.known, m.known));
  }
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
    LargestPoint largest;
    for (int i = 0; i <= m; ++i) largest.add(fmt::format("net[{}]", i), net.points.middleRows(net.index(i, 0), n + 1));
    largest.require(options.min_model_size, source);
    for (const char* field : {"knots_u", "knots_v", "degree_spline"})
      if (doc.contains(field))
        p.fail(field, "belongs to the sides form (B-spline boundary curves); a \"net\" file has no knots");
    if (doc.contains("bspline"))  // the solve report of a B-spline boundary: its net is not a Bézier net
      p.fail("bspline",
             "a B-spline solve report: its \"net\" is a B-spline control net, not a Bezier net; give the "
             "B-spline boundary file itself");
    if (doc.contains("ribbons"))
      p.fail("ribbons", "belongs to the sides form; a \"net\" holds its data rings itself (use \"rings\")");
    out.rings = parse_rings(p, doc, m, n);
    if (doc.contains("free")) {
      // (free points may lie in the data rings, as in the contract's example; the mask decides
      // later whether its stencil at each of them stays in the net: stencil_problem.h)
      out.free = free_grid_from_json(doc["free"], m, n, source);
    }
    out.boundary = boundary_of(net, name);
    out.net = std::move(net);
    return out;
  }
  for (const char* field : {"rings", "free"})
    if (doc.contains(field))
      p.fail(field, "belongs to the \"net\" form; the sides form has one data ring, or two with \"ribbons\"");

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
  if (doc.contains("ribbons")) {
    out.ribbons = parse_ribbons(p, doc, b, options.corner_tolerance);
    out.rings = 2;
  }
  LargestPoint largest;
  for (const auto& [side, list] :
       {std::pair{"bottom", &b.bottom}, {"top", &b.top}, {"left", &b.left}, {"right", &b.right}})
    largest.add(side, *list);
  if (out.ribbons)
    for (const auto& [side, list] : {std::pair{"ribbons.bottom", &out.ribbons->bottom},
                                     {"ribbons.top", &out.ribbons->top},
                                     {"ribbons.left", &out.ribbons->left},
                                     {"ribbons.right", &out.ribbons->right}})
      largest.add(side, *list);
  largest.require(options.min_model_size, source);
  if (const auto knots = parse_bspline_knots(doc, source, b.m + 1, b.n + 1)) {
    if (out.ribbons) p.fail("ribbons", "B-spline boundaries (knots_u, knots_v) take one data ring; drop \"ribbons\"");
    out.bspline = bspline_input(b, *knots, source);
  }
  return out;
}

BoundaryFile read_boundary_file(const std::string& path, const BoundaryReadOptions& options) {
  return parse_boundary(read_json_file(path), path, options);
}

StencilProblem stencil_problem(const BoundaryFile& file) {
  StencilProblem problem;
  problem.rings = file.rings;
  if (file.net) {
    problem.net = *file.net;
    problem.free = file.free;
    return problem;
  }
  const Boundary& b = file.boundary;
  if (!file.ribbons) {
    problem.net = discrete_coons_net(b);
    return problem;
  }
  // The ribbons as the boundary of the (m−2)×(n−2) net inside the frame: its discrete Coons net
  // holds them on its frame (shared points from the bottom/top ribbons, as frame_net takes
  // corners) and start values inside; the sides go around it.
  const Ribbons& r = *file.ribbons;
  const int m = b.m, n = b.n;
  Boundary inner;
  inner.m = m - 2;
  inner.n = n - 2;
  inner.bottom = r.bottom.middleRows(1, m - 1);
  inner.top = r.top.middleRows(1, m - 1);
  inner.left = r.left.middleRows(1, n - 1);
  inner.right = r.right.middleRows(1, n - 1);
  const ControlNet inside = discrete_coons_net(inner);
  ControlNet net = frame_net(b);
  for (int i = 1; i < m; ++i)
    for (int j = 1; j < n; ++j) net.at(i, j) = inside.at(i - 1, j - 1);
  problem.net = std::move(net);
  return problem;
}

bool is_classical(const BoundaryFile& file) { return file.rings == 1 && file.free.size() == 0; }

}  // namespace coons
