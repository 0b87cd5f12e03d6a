#include "surface_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "coons/curves/pole_scan.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/surfaces/coons_patch.h"

namespace coons {

namespace {

using nlohmann::json;
using Vec = Eigen::RowVector3d;

const std::vector<std::string> kDocumentationFields = {"name", "comment", "source"};

const std::vector<std::pair<std::string, std::vector<std::string>>>& fields_by_type() {
  static const std::vector<std::pair<std::string, std::vector<std::string>>> fields = {
      {"ruled", {"curves"}},
      {"sectorial", {"curve", "point"}},
      {"bilinear", {"corners"}},
      {"conoid", {"directrix", "line", "plane_normal"}},
      {"bilinear-coons", {"bottom", "top", "left", "right"}},
      {"hermite-coons", {"bottom", "top", "left", "right"}},
      {"ferguson", {"corners", "du", "dv"}},
      {"hermite16", {"corners", "du", "dv", "twist"}},
      {"general-coons", {"bottom", "top", "left", "right", "du_left", "du_right", "dv_bottom", "dv_top", "twist"}},
      {"bezier", {"net"}},
  };
  return fields;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& reason) const {
    throw InputError(source_, field, reason);
  }

  const json& require(const json& doc, const std::string& key, const std::string& field) const {
    if (!doc.contains(key)) fail(field, "missing");
    return doc[key];
  }

  double number(const json& j, const std::string& field) const {
    if (!j.is_number()) fail(field, "must be a number");
    const double x = j.get<double>();
    if (!std::isfinite(x)) fail(field, "is not finite");
    return x;
  }

  Vec point(const json& p, const std::string& field) const {
    if (!p.is_array()) fail(field, "a point must be an array of 3 numbers");
    if (p.size() != 3) fail(field, fmt::format("a point must have 3 coordinates, not {}", p.size()));
    Vec out;
    for (int c = 0; c < 3; ++c) out(c) = json_coordinate(p[c], source_, field, fmt::format("coordinate {}", c));
    note_magnitude(out, field);
    return out;
  }

  //! The largest coordinate magnitude read so far and the field that holds it (require_size).
  void note_magnitude(const Vec& p, const std::string& field) const {
    const double m = p.cwiseAbs().maxCoeff();
    if (m > largest_) {
      largest_ = m;
      largest_field_ = field;
    }
  }

  //! An InputError at the field of the largest coordinate when 0 < largest < min_size.
  void require_size(double min_size) const {
    if (largest_ > 0 && largest_ < min_size)
      fail(largest_field_,
           fmt::format("the largest coordinate magnitude of the model is {:.3g}, below {:g}: its curvatures "
                       "(1/x) and squared distances (x^2) would leave the range of doubles; scale the model up",
                       largest_, min_size));
  }

  //! An array of exactly `count` points (count < 0: at least 1).
  std::vector<Vec> points(const json& j, const std::string& field, int count) const {
    if (!j.is_array())
      fail(field,
           count > 0 ? fmt::format("must be an array of {} points", count) : std::string("must be an array of points"));
    if (count > 0 && int(j.size()) != count)
      fail(field, fmt::format("must hold exactly {} points, not {}", count, j.size()));
    if (j.empty()) fail(field, "must hold at least one point");
    std::vector<Vec> out;
    for (size_t k = 0; k < j.size(); ++k) out.push_back(point(j[k], fmt::format("{}[{}]", field, k)));
    return out;
  }

  std::array<Vec, 4> four(const json& doc, const std::string& key) const {
    const std::vector<Vec> p = points(require(doc, key, key), key, 4);
    return {p[0], p[1], p[2], p[3]};
  }

  Curve curve(const json& j, const std::string& field) const {
    if (!j.is_object())
      fail(field, "a curve must be an object: {\"bezier\": [points]} or {\"expr\": [x, y, z], \"interval\": [t1, t2]}");
    static const std::vector<std::string> forms = {"bezier", "expr", "point", "hermite"};
    std::vector<std::string> present;
    for (const auto& f : forms)
      if (j.contains(f)) present.push_back(f);
    if (present.size() != 1)
      fail(field, present.empty()
                      ? "a curve needs one of \"bezier\", \"expr\" (or \"point\", \"hermite\")"
                      : fmt::format("a curve has exactly one of \"bezier\", \"expr\", \"point\", \"hermite\" "
                                    "(found {})",
                                    fmt::join(present, ", ")));
    const std::string form = present[0];
    for (const auto& [key, value] : j.items()) {
      (void)value;
      if (key != form && !(form == "expr" && key == "interval"))
        fail(fmt::format("{}.{}", field, key), fmt::format("unknown field in a \"{}\" curve", form));
    }
    const std::string sub = field + "." + form;
    if (form == "bezier") {
      const std::vector<Vec> P = points(j[form], sub, -1);
      Eigen::MatrixX3d M(P.size(), 3);
      for (size_t k = 0; k < P.size(); ++k) M.row(k) = P[k];
      return BezierCurve(M);
    }
    if (form == "point") return Curve::constant(point(j[form], sub));
    if (form == "hermite") {
      const std::vector<Vec> P = points(j[form], sub, 4);
      return Curve::hermite_cubic(P[0], P[1], P[2], P[3]);
    }
    // expr
    const json& e = j[form];
    if (!e.is_array() || e.size() != 3)
      fail(sub, fmt::format("must be 3 expressions [\"x(t)\", \"y(t)\", \"z(t)\"]{}",
                            e.is_array() ? fmt::format(", not {}", e.size()) : ""));
    std::array<std::string, 3> expressions;
    for (int c = 0; c < 3; ++c) {
      if (e[c].is_number())
        expressions[c] = fmt::format("{}", e[c].get<double>());
      else if (e[c].is_string())
        expressions[c] = e[c].get<std::string>();
      else
        fail(fmt::format("{}[{}]", sub, c), "must be a string (an expression in t) or a number");
    }
    double t1 = 0, t2 = 1;
    if (j.contains("interval")) {
      const json& iv = j["interval"];
      const std::string f = field + ".interval";
      if (!iv.is_array() || iv.size() != 2) fail(f, "must be [t1, t2]");
      t1 = number(iv[0], f + "[0]");
      t2 = number(iv[1], f + "[1]");
      if (t1 == t2) fail(f, "t1 and t2 must differ");
      // c(s) = x(t1 + s(t2 − t1)): an infinite width made every t NaN, blamed on the expression
      if (!std::isfinite(t2 - t1)) fail(f, "t2 - t1 overflows a double; give a narrower interval");
    }
    try {
      AnalyticCurve c(expressions, t1, t2);
      for (int k = 0; k <= 64; ++k) {
        const double s = k / 64.0;
        const Vec p = c.at(s);
        for (int comp = 0; comp < 3; ++comp)
          if (const std::string why = coordinate_problem(p(comp)); !why.empty())
            fail(fmt::format("{}[{}]", sub, comp),
                 fmt::format("'{}' at t = {:.6g} {}", expressions[comp], t1 + s * (t2 - t1), why));
        note_magnitude(p, sub);
      }
      // between those samples: a pole (0.001 t(1 - t)/(t - 0.50390625) was accepted) or a NaN
      if (const auto pole = find_singularity(c)) {
        const double t = t1 + pole->s * (t2 - t1);
        fail(fmt::format("{}[{}]", sub, pole->component),
             fmt::format("'{}' has a pole or is not finite near t = {:.9g}, between the samples checked (value {:.3g} "
                         "there)",
                         expressions[std::size_t(pole->component)], t, pole->value));
      }
      return c;
    } catch (const ExpressionError& x) {
      fail(fmt::format("{}[{}]", sub, x.component()), x.what());
    }
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
  mutable double largest_ = 0;  // (note_magnitude: the reads are const)
  mutable std::string largest_field_;
};

// The tolerance checks shared by the Coons types.
void check_conditions(const Reader& r, const std::vector<CompatibilityCondition>& conditions, double size,
                      const SurfaceReadOptions& o) {
  for (const auto& c : conditions) {
    // (plus the numerical derivatives' own error bound: a curve at x = 1e8 has tangents good to
    // about 1e-5, and exact data were refused "by 1.18e-05 (tolerance 1.41e-07)")
    const double given = c.order == 0 ? o.corner_tolerance * std::max(size, 1e-300)
                                      : o.derivative_tolerance * std::max({size, c.scale, 1e-300});
    const double tolerance = given + c.uncertainty;
    if (std::isnan(c.uncertainty) || std::isnan(c.gap))
      r.fail(c.field, fmt::format("{} cannot be checked at corner {}: a numerical derivative in it does not settle "
                                  "(the curve's values round too coarsely there, or the derivative is infinite)",
                                  c.condition, c.corner));
    if (!(c.gap <= tolerance)) {
      const char* what = c.order == 0   ? "the curves do not meet"
                         : c.order == 1 ? "cross derivative and tangent disagree"
                                        : "twist and cross derivative disagree";
      r.fail(c.field,
             fmt::format("{} at corner {}: {} fails by {:.3g} (tolerance {:.3g}{})", what, c.corner, c.condition, c.gap,
                         tolerance,
                         c.uncertainty > 0
                             ? fmt::format(", of which {:.3g} the numerical derivative's error bound", c.uncertainty)
                             : std::string()));
    }
  }
}

BoundaryCurves boundary_curves(const Reader& r, const json& doc) {
  return BoundaryCurves{r.curve(r.require(doc, "bottom", "bottom"), "bottom"),
                        r.curve(r.require(doc, "top", "top"), "top"), r.curve(r.require(doc, "left", "left"), "left"),
                        r.curve(r.require(doc, "right", "right"), "right")};
}

}  // namespace

std::vector<std::pair<std::string, std::vector<std::string>>> surface_fields() { return fields_by_type(); }

Curve parse_curve(const json& j, const std::string& source, const std::string& field) {
  return Reader(source).curve(j, field);
}

SurfaceFile parse_surface(const json& doc, const std::string& source, const SurfaceReadOptions& options) {
  const Reader r(source);
  if (!doc.is_object()) r.fail("", "the top level must be a JSON object");
  std::string name = std::filesystem::path(source).stem().string();
  if (doc.contains("name")) {
    if (!doc["name"].is_string()) r.fail("name", "must be a string");
    name = doc["name"].get<std::string>();
  }
  std::vector<std::string> known;
  for (const auto& [t, f] : fields_by_type()) known.push_back(t);
  if (!doc.contains("type")) r.fail("type", fmt::format("missing (one of {})", fmt::join(known, ", ")));
  if (!doc["type"].is_string()) r.fail("type", "must be a string");
  const std::string type_name = doc["type"].get<std::string>();
  const auto entry = std::find_if(fields_by_type().begin(), fields_by_type().end(),
                                  [&](const auto& e) { return e.first == type_name; });
  if (entry == fields_by_type().end())
    r.fail("type", fmt::format("unknown type '{}' (known: {})", type_name, fmt::join(known, ", ")));
  for (const auto& [key, value] : doc.items()) {
    (void)value;
    if (key == "type" || std::count(kDocumentationFields.begin(), kDocumentationFields.end(), key) ||
        std::count(entry->second.begin(), entry->second.end(), key))
      continue;
    r.fail(key, fmt::format("unknown field for type '{}' (its fields: {})", type_name, fmt::join(entry->second, ", ")));
  }

  const SurfaceType type = *surface_type_from_string(type_name);
  std::optional<Surface> surface;
  std::vector<CompatibilityCondition> conditions;
  double size = 0;
  switch (type) {
    case SurfaceType::kRuled: {
      const json& c = r.require(doc, "curves", "curves");
      if (!c.is_array() || c.size() != 2)
        r.fail("curves", fmt::format("must hold exactly 2 curves [c0, c1]{}",
                                     c.is_array() ? fmt::format(", not {}", c.size()) : ""));
      surface = make_ruled(r.curve(c[0], "curves[0]"), r.curve(c[1], "curves[1]"));
      break;
    }
    case SurfaceType::kSectorial:
      surface = make_sectorial(r.curve(r.require(doc, "curve", "curve"), "curve"),
                               r.point(r.require(doc, "point", "point"), "point"));
      break;
    case SurfaceType::kBilinear:
      surface = make_bilinear(r.four(doc, "corners"));
      break;
    case SurfaceType::kConoid: {
      const Curve directrix = r.curve(r.require(doc, "directrix", "directrix"), "directrix");
      const std::vector<Vec> line = r.points(r.require(doc, "line", "line"), "line", 2);
      Conoid c{directrix, line[0], line[1], r.point(r.require(doc, "plane_normal", "plane_normal"), "plane_normal")};
      if (!(line[1].cwiseAbs().maxCoeff() > 0)) r.fail("line[1]", "the line's direction is the zero vector");
      if (const std::string why = conoid_problem(c); !why.empty()) r.fail("plane_normal", why);
      surface = make_conoid(std::move(c));
      break;
    }
    case SurfaceType::kBilinearCoons:
    case SurfaceType::kHermiteCoons: {
      BoundaryCurves b = boundary_curves(r, doc);
      size = boundary_size(b);
      conditions = corner_conditions(b);
      check_conditions(r, conditions, size, options);
      surface = make_coons(std::move(b),
                           type == SurfaceType::kBilinearCoons ? CoonsBlending::kLinear : CoonsBlending::kHermite);
      break;
    }
    case SurfaceType::kFerguson:
      surface = make_ferguson(r.four(doc, "corners"), r.four(doc, "du"), r.four(doc, "dv"));
      break;
    case SurfaceType::kHermite16:
      surface = make_hermite16(
          HermitePatch{r.four(doc, "corners"), r.four(doc, "du"), r.four(doc, "dv"), r.four(doc, "twist")});
      break;
    case SurfaceType::kGeneralCoons: {
      BoundaryCurves b = boundary_curves(r, doc);
      auto cross = [&](const char* key) { return r.curve(r.require(doc, key, key), key); };
      GeneralCoonsData g{std::move(b),       cross("du_left"), cross("du_right"),
                         cross("dv_bottom"), cross("dv_top"),  r.four(doc, "twist")};
      size = boundary_size(g.boundary);
      conditions = compatibility_conditions(g);
      check_conditions(r, conditions, size, options);
      surface = make_general_coons(std::move(g));
      break;
    }
    case SurfaceType::kBezier: {
      const json& rows = r.require(doc, "net", "net");
      if (!rows.is_array() || rows.size() < 2) r.fail("net", "must hold at least 2 rows of points (m >= 1)");
      if (!rows[0].is_array() || rows[0].size() < 2) r.fail("net[0]", "must hold at least 2 points (n >= 1)");
      const int m = int(rows.size()) - 1, n = int(rows[0].size()) - 1;
      ControlNet net(m, n);
      for (int i = 0; i <= m; ++i) {
        const std::string field = fmt::format("net[{}]", i);
        if (!rows[i].is_array()) r.fail(field, "must be an array of points");
        if (int(rows[i].size()) != n + 1)
          r.fail(field, fmt::format("has {} points, row 0 has {}", rows[i].size(), n + 1));
        for (int j = 0; j <= n; ++j) net.at(i, j) = r.point(rows[i][j], fmt::format("net[{}][{}]", i, j));
      }
      surface = make_bezier_surface(std::move(net));
      break;
    }
  }
  r.require_size(options.min_model_size);
  return SurfaceFile{name, std::move(*surface), std::move(conditions), size};
}

SurfaceFile read_surface_file(const std::string& path, const SurfaceReadOptions& options) {
  return parse_surface(read_json_file(path), path, options);
}

}  // namespace coons
