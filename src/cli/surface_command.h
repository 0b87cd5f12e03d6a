// `coons surface SPEC.json --sample K`: build any surface of the continuous Coons family from its
// JSON description (docs/formats.md "Curves and surfaces"), print {"type", "points": K×K} with the
// Bézier net (exact when the surface is polynomial, else over Bézier fits of its curves, with the
// deviations), exact energies of that net, its distance to the closed-form discrete nets of its
// boundary, the corner twists and the compatibility diagnostics; optionally write meshes (OBJ,
// PLY with per-vertex scalars, ParaView .vts), a PNG of surface and net, and the net as a boundary
// file that `coons solve` reads.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace coons::cli {

struct SurfaceRequest {
  std::string spec;
  int samples = 21;
  std::string obj, ply, vts, png, net_out;
  std::string reference;  //!< a surface description, or a file with "net" (a boundary file, a solve report)
  int fit_degree = 5;
  double corner_tolerance = 1e-9;
  double derivative_tolerance = 1e-7;
};

//! Adds the `surface` subcommand with its options bound to r; returns it.
CLI::App* add_surface_command(CLI::App& app, SurfaceRequest& r);

int cmd_surface(const SurfaceRequest& r);

//! `coons join A.json SIDE B.json SIDE`: the C⁰ gap and the largest angle between the tangent
//! planes along the seam where side A of one surface meets side B of another (LN1, LN2).
struct JoinRequest {
  std::string first, first_side, second, second_side;
  bool reversed = false;
  int samples = 101;
};
CLI::App* add_join_command(CLI::App& app, JoinRequest& r);
int cmd_join(const JoinRequest& r);

}  // namespace coons::cli
