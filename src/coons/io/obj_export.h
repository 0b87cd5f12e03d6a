// Wavefront OBJ output (opens in Blender, MeshLab, ParaView): the sampled Bézier surface as a
// triangulated grid with normals, and the control net as a quad mesh.
#pragma once

#include <ostream>

#include "coons/net/control_net.h"

namespace coons {

//! The surface sampled on a k × k grid (k ≥ 2), two triangles per cell, per-vertex normals.
void write_surface_obj(std::ostream& out, const ControlNet& net, int k);

//! The control net: (m+1)(n+1) vertices and m·n quads.
void write_net_obj(std::ostream& out, const ControlNet& net);

}  // namespace coons
