// CAD exchange on the command line (docs/cad.md): `coons import-step` and the --step/--iges
// options of `coons export`. Built with OpenCASCADE (COONS_HAVE_OCCT) they use coons_cad; without
// it the command and the options exist and refuse with an input error saying how to get them.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "coons/io/write_files.h"
#include "coons/net/control_net.h"
#include "registry.h"

namespace coons::cli {

struct CadExportRequest {
  std::string step, iges;  //!< --step OUT.step, --iges OUT.iges (paths as given)
  [[nodiscard]] bool any() const { return !step.empty() || !iges.empty(); }
};
void add_cad_export_options(CLI::App& cmd, CadExportRequest& r);

//! What export writes to STEP/IGES: checked before anything is solved.
struct CadExportPlan {
  bool bspline = false;  //!< the file has knots_u/knots_v/degree_spline: the Greville net is written
};
//! Refuses (InputError) when OpenCASCADE is not built in, when a target exists without --force,
//! and for a B-spline boundary file (knots_u …) asked for another method than coons.
CadExportPlan check_cad_export(const CadExportRequest& r, const std::string& boundary_path, const Boundary& b,
                               Method method, bool classical, bool force);
//! Stages the STEP and IGES files of the net in `out` (published with the other files); returns
//! their final paths. For a B-spline boundary the net written is the Greville Coons net with the
//! file's knots (coons' Bézier net otherwise, as a single-span B-spline).
std::vector<std::string> write_cad_export(const CadExportRequest& r, const CadExportPlan& plan,
                                          const std::string& boundary_path, const Boundary& b, const ControlNet& net,
                                          OutputSet& out);

}  // namespace coons::cli
