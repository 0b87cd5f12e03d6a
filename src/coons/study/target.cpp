#include "target.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/net/control_net.h"
#include "coons/net/coons_net.h"

namespace coons {

using nlohmann::json;

namespace {

std::vector<double> numbers_after_colon(const std::string& spec, size_t count, const std::string& field) {
  std::vector<double> out;
  std::stringstream in(spec.substr(spec.find(':') + 1));
  for (std::string item; std::getline(in, item, ',');) {
    // strtod, not stod: stod refuses a value that underflows (1e-320, a subnormal) as out of range
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(x))
      throw InputError("command line", field, "'" + item + "' is not a finite number");
    // (but one that reads as 0 without being written as 0 lies below the smallest double)
    if (x == 0 && !zero_digits(item))
      throw InputError("command line", field, "'" + item + "' is below the smallest double and would be read as 0");
    if (const std::string why = coordinate_problem(x); !why.empty())
      throw InputError("command line", field, fmt::format("'{}' {}", item, why));
    out.push_back(x);
  }
  if (out.size() != count)
    throw InputError("command line", field, fmt::format("'{}' needs {} numbers after the colon", spec, count));
  return out;
}

const json& member(const json& object, const char* key, const std::string& source, const std::string& field) {
  if (!object.is_object()) throw InputError(source, field, "must be an object");
  const auto it = object.find(key);
  if (it == object.end()) throw InputError(source, field + "." + key, "missing");
  return *it;
}

Eigen::RowVector3d vec3(const json& j, const std::string& source, const std::string& field) {
  if (!j.is_array() || j.size() != 3) throw InputError(source, field, "must be [x, y, z]");
  Eigen::RowVector3d p;
  // (json_coordinate names the coordinate that is not a number, not finite or beyond the bound)
  for (int k = 0; k < 3; ++k) p(k) = json_coordinate(j[k], source, field, fmt::format("coordinate {}", k));
  return p;
}

double positive(const json& j, const std::string& source, const std::string& field) {
  const double r = json_coordinate(j, source, field, "the radius");
  if (!(r > 0)) throw InputError(source, field, "must be a positive finite number");
  return r;
}

constexpr const char* kNoDirection = "axis/normal must not be the zero vector";

// An axis or normal as unit_scaled (control_net.h) makes it: the distances normalise it with
// norm(), whose square underflows below about 1e-154 (a normal of 1e-161 came out 1.006 long, and
// one of 1e-162 had length 0). A power of two changes no digit, so a direction of ordinary size
// normalises to the same bits as before. false for the zero vector.
bool rescale_direction(Eigen::RowVector3d& d) {
  if (!(d.cwiseAbs().maxCoeff() > 0)) return false;
  d = unit_scaled(d);
  return true;
}

}  // namespace

std::optional<Target> target_from_json(const json& doc, const std::string& source, int samples) {
  if (!doc.is_object() || !doc.contains("target")) return std::nullopt;
  const json& t = doc["target"];
  if (!t.is_object()) throw InputError(source, "target", "must be an object holding sphere, cylinder or plane");
  Target out;
  out.samples = samples;
  if (t.contains("sphere")) {
    const json& s = t["sphere"];
    out.kind = Target::Kind::kSphere;
    out.point = vec3(member(s, "center", source, "target.sphere"), source, "target.sphere.center");
    out.radius = positive(member(s, "radius", source, "target.sphere"), source, "target.sphere.radius");
  } else if (t.contains("cylinder")) {
    const json& c = t["cylinder"];
    out.kind = Target::Kind::kCylinder;
    out.point = vec3(member(c, "point", source, "target.cylinder"), source, "target.cylinder.point");
    out.direction = vec3(member(c, "axis", source, "target.cylinder"), source, "target.cylinder.axis");
    out.radius = positive(member(c, "radius", source, "target.cylinder"), source, "target.cylinder.radius");
  } else if (t.contains("plane")) {
    const json& p = t["plane"];
    out.kind = Target::Kind::kPlane;
    out.point = vec3(member(p, "point", source, "target.plane"), source, "target.plane.point");
    out.direction = vec3(member(p, "normal", source, "target.plane"), source, "target.plane.normal");
  } else {
    throw InputError(source, "target", "must hold sphere, cylinder or plane");
  }
  if (out.kind != Target::Kind::kSphere && !rescale_direction(out.direction))
    throw InputError(source, out.kind == Target::Kind::kPlane ? "target.plane.normal" : "target.cylinder.axis",
                     kNoDirection);
  return out;
}

std::optional<Target> read_boundary_target(const std::string& path, int samples) {
  return target_from_json(read_json_file(path), path, samples);
}

std::optional<Target> resolve_target(const std::string& spec, const std::string& boundary_path, const Boundary& b,
                                     int samples) {
  std::optional<Target> t;
  if (spec.empty()) {
    t = read_boundary_target(boundary_path, samples);
  } else if (spec == "hermite-coons" || spec == "coons") {
    if (spec == "hermite-coons" && (b.m < 3 || b.n < 3))
      throw InputError(boundary_path, "degree", "--target hermite-coons needs degree >= 3 in both directions");
    t = Target{};
    t->net = spec == "coons" ? discrete_coons_net(b) : hermite_coons_net(b);
  } else if (spec.rfind("sphere:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 4, "--target");
    t = Target{Target::Kind::kSphere, {}, {v[0], v[1], v[2]}, {0, 0, 1}, v[3], samples};
  } else if (spec.rfind("cylinder:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 7, "--target");
    t = Target{Target::Kind::kCylinder, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, v[6], samples};
  } else if (spec.rfind("plane:", 0) == 0) {
    const auto v = numbers_after_colon(spec, 6, "--target");
    t = Target{Target::Kind::kPlane, {}, {v[0], v[1], v[2]}, {v[3], v[4], v[5]}, 1, samples};
  } else {
    const BoundaryFile f = read_boundary_file(spec);
    if (!f.net) throw InputError(spec, "net", "a target file must hold a \"net\"");
    t = Target{};
    t->net = *f.net;
  }
  if (t && !spec.empty()) {  // the numbers of --target (a file's were checked as they were read)
    if (t->kind != Target::Kind::kNet && !rescale_direction(t->direction))
      throw InputError("command line", "--target", kNoDirection);
    if ((t->kind == Target::Kind::kSphere || t->kind == Target::Kind::kCylinder) && !(t->radius > 0))
      throw InputError("command line", "--target", "radius must be positive");
  }
  if (t) t->samples = samples;
  return t;
}

}  // namespace coons
