// Meshes of a sampled surface (surfaces/sampling.h) for outside viewers:
//   OBJ  — vertices, normals, two triangles per grid cell (Blender, MeshLab, ParaView);
//   PLY  — ASCII, per-vertex normals and scalars (mean_curvature, gaussian_curvature, twist,
//          distance and parametric_distance when a reference was given, singular), quads
//          (MeshLab, ParaView, CloudCompare);
//   VTS  — ParaView's XML StructuredGrid (ASCII), the same fields as point data, "Normals" as a
//          vector; the grid keeps its (u, v) structure.
// Where the surface is singular (r_u ∥ r_v: a sectorial apex, a degenerate corner) normal and
// curvatures are undefined: they are written as 0 and the field "singular" is 1 there.
// Write them through write_file_atomically so that nothing half-written is left behind.
// Based on: the PLY format of G. Turk (Stanford, 1994); VTK File Formats (Kitware), "XML File
// Formats: StructuredGrid".
#pragma once

#include <ostream>
#include <string>

#include "coons/surfaces/sampling.h"

namespace coons {

//! x when finite, else 0: how the PLY and VTK writers print a sample without a value (the normal or
//! curvature of a singular point, which the `singular` field marks).
double finite_or_zero(double x);

//! One VTK XML point-data array of the square and triangular VTS/VTU writers: scalars eight to a
//! line, or three components per line (an empty `name` leaves the Name attribute out, as the
//! Points array has none), each value through finite_or_zero.
void write_vtk_scalars(std::ostream& out, const char* name, const Eigen::VectorXd& values);
void write_vtk_vectors(std::ostream& out, const char* name, const Eigen::MatrixX3d& v);

void write_grid_obj(std::ostream& out, const SurfaceSamples& s, const std::string& comment = {});
void write_grid_ply(std::ostream& out, const SurfaceSamples& s, const std::string& comment = {});
void write_grid_vts(std::ostream& out, const SurfaceSamples& s);

}  // namespace coons
