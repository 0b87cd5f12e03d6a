// CAD exchange on the command line (docs/cad.md): `coons import-step` and the --step/--iges
// options of `coons export`. Built with OpenCASCADE (COONS_HAVE_OCCT) they use coons_cad; without
// it the command and the options exist and refuse with an input error saying how to get them.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "coons/io/write_files.h"
#include "coons/net/control_net.h"
#include "coons/surfaces/bspline_surface.h"
#include "registry.h"

namespace coons::cli {

struct CadExportRequest {
  std::string step, iges;  //!< --step OUT.step, --iges OUT.iges (paths as given)
  [[nodiscard]] bool any() const { return !step.empty() || !iges.empty(); }
};
void add_cad_export_options(CLI::App& cmd, CadExportRequest& r);

//! Refuses (InputError) when OpenCASCADE is not built in, when a target exists without --force,
//! and when --step and --iges name one file. Called before anything is solved or written.
void check_cad_export(const CadExportRequest& r, bool force);
//! Stages the STEP and IGES files of `surface` in `out` (published with the other files); returns
//! their final paths. A B-spline boundary's surface keeps its knots; a Bézier net goes through
//! bezier_surface_for_cad first.
std::vector<std::string> write_cad_export(const CadExportRequest& r, const BSplineSurface& surface, OutputSet& out);
//! A Bézier net as the single-span clamped B-spline surface STEP and IGES carry.
BSplineSurface bezier_surface_for_cad(const ControlNet& net);

}  // namespace coons::cli
