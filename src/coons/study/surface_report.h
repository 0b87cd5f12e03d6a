// The report of `coons surface`: a surface of the continuous Coons family sampled on a K×K grid,
// its Bézier net (exact when the surface is polynomial, else over Bézier fits of its curves, with
// the deviations), the exact energies of that net, its distance to the closed-form discrete nets of
// its boundary, the corner twists, the compatibility diagnostics and, with a reference surface,
// the distance field (docs/formats.md "Curves and surfaces").
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "coons/io/surface_io.h"
#include "coons/surfaces/sampling.h"
#include "coons/surfaces/surface.h"

namespace coons {

struct SurfaceReportOptions {
  int samples = 21;                //!< K ≥ 2
  int fit_degree = 5;              //!< largest degree of the Bézier fits of non-Bézier curves
  double corner_tolerance = 1e-9;  //!< as read (reported with the compatibility diagnostics)
  double derivative_tolerance = 1e-7;
  std::string reference_file;  //!< named in the report when there is a reference
};

struct SurfaceReport {
  nlohmann::ordered_json report;     //!< everything but the net and the points, in reading order
  nlohmann::ordered_json net_block;  //!< "net": degree, exactness, fits, the net itself
  nlohmann::ordered_json points;     //!< K×K points
  SurfaceSamples samples;            //!< for meshes
  FittedNet fitted;                  //!< for the net file and the picture
};

//! `fitted` is fitted_net(input.surface, options.fit_degree), made by the caller so that it can
//! hold the net's size to a memory limit before its energies are taken (memory_estimate.h:
//! net_metrics_bytes).
SurfaceReport surface_report(const SurfaceFile& input, FittedNet fitted, const std::optional<SurfaceFile>& reference,
                             const SurfaceReportOptions& options);

//! The field of `s` that sets the degree of its net `fitted` (fitted_net(s, …)): "net" for a
//! Bézier surface, else the curve of the largest degree, a Bézier curve's own or a fit's (the first
//! such), else "type" (a surface given by corners and vectors: its type fixes the degree).
std::string net_degree_field(const Surface& s, const FittedNet& fitted);

//! A reference: a surface description, or any file holding "net" (a boundary file, a solve report)
//! read as a Bézier net. A B-spline net (knots_u, knots_v, degree_spline or a "bspline" block) is
//! an InputError naming that field.
SurfaceFile read_surface_reference(const std::string& path, const SurfaceReadOptions& options);

}  // namespace coons
