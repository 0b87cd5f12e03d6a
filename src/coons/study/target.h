// What a surface should be close to: the `target` of a boundary file ({"sphere": {"center",
// "radius"}} | {"cylinder": {"point", "axis", "radius"}} | {"plane": {"point", "normal"}}) and the
// `--target` specification of the commands (hermite-coons | coons | NET.json | sphere:cx,cy,cz,r |
// cylinder:px,py,pz,dx,dy,dz,r | plane:px,py,pz,nx,ny,nz), both checked field by field.
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

//! A --target specification; an empty one means the boundary file's own target (or none).
std::optional<Target> resolve_target(const std::string& spec, const std::string& boundary_path,
                                     const Boundary& boundary, int samples);

}  // namespace coons
