// What a surface should be close to: the `target` of a boundary file ({"sphere": {"center",
// "radius"}} | {"cylinder": {"point", "axis", "radius"}} | {"plane": {"point", "normal"}}), checked
// field by field. (The commands' `--target` specification is read by the CLI: cli/search_inputs.h.)
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "coons/alpha/objective.h"
#include "coons/net/control_net.h"

namespace coons {

//! The "target" of a parsed boundary document, or nullopt when it has none. Throws InputError
//! (naming `source` and the field) for a target of the wrong shape or type.
std::optional<Target> target_from_json(const nlohmann::json& doc, const std::string& source, int samples = 41);

//! The "target" of a boundary file (read again; bad files throw InputError).
std::optional<Target> read_boundary_target(const std::string& path, int samples = 41);

//! Scales a cylinder's axis or a plane's normal as unit_scaled (control_net.h) does: the distances
//! normalise it with norm(), whose square underflows below about 1e-154, and a power of two changes
//! no digit. false for the zero vector (no direction); true, unchanged, for a sphere or a net.
bool normalise_target_direction(Target& target);

//! The reason a target without a direction is refused.
inline constexpr const char* kNoTargetDirection = "axis/normal must not be the zero vector";

}  // namespace coons
