#include "target.h"

#include <fmt/format.h>

#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/net/control_net.h"

namespace coons {

using nlohmann::json;

namespace {

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

}  // namespace

bool normalise_target_direction(Target& t) {
  if (t.kind == Target::Kind::kSphere || t.kind == Target::Kind::kNet) return true;
  // (a direction of 1e-161 came out 1.006 long when normalised as it was, one of 1e-162 had length 0)
  if (!(t.direction.cwiseAbs().maxCoeff() > 0)) return false;
  t.direction = unit_scaled(t.direction);
  return true;
}

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
  if (!normalise_target_direction(out))
    throw InputError(source, out.kind == Target::Kind::kPlane ? "target.plane.normal" : "target.cylinder.axis",
                     kNoTargetDirection);
  return out;
}

std::optional<Target> read_boundary_target(const std::string& path, int samples) {
  return target_from_json(read_json_file(path), path, samples);
}

}  // namespace coons
