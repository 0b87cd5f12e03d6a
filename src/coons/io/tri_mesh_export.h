// Files of a triangular Bézier surface for outside viewers (the triangular counterparts of
// obj_export.h and mesh_export.h), all from tri_sampling.h's samples (K points per side, row order):
//   OBJ  — the sampled surface: vertices, unit normals, (K−1)² triangles; and the control net:
//          (n+1)(n+2)/2 vertices in the row order of docs/formats.md, its n² triangles;
//   PLY  — ASCII, x y z nx ny nz and the scalars mean_curvature, gaussian_curvature, singular,
//          the (K−1)² triangles;
//   VTU  — ParaView's XML UnstructuredGrid (ASCII Float64), cells of type 5 (VTK_TRIANGLE), the same
//          scalars as point data and "Normals" as a vector.
// Undefined values (at a degenerate point, `singular` = 1) are written as 0 (the OBJ normal as
// (0, 0, 1)). Write them through the OutputSet of write_files.h.
// Based on: the Wavefront OBJ format; the PLY format of G. Turk (Stanford, 1994); VTK File Formats
// (Kitware), "XML File Formats: UnstructuredGrid".
#pragma once

#include <ostream>

#include "coons/tri/tri_net.h"
#include "coons/tri/tri_sampling.h"

namespace coons {

void write_tri_surface_obj(std::ostream& out, const tri::TriSurfaceSamples& s, int degree);
//! Vertex r + 1 is row r of the net (row order); faces are the upward triangles b_{β+e1},
//! b_{β+e2}, b_{β+e3} (|β| = n − 1) and the downward ones between them.
void write_tri_net_obj(std::ostream& out, const tri::TriNet& net);
void write_tri_surface_ply(std::ostream& out, const tri::TriSurfaceSamples& s, int degree);
void write_tri_surface_vtu(std::ostream& out, const tri::TriSurfaceSamples& s);

}  // namespace coons
