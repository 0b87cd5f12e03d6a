// The data of a `coons view` page (view_page.h) for a rectangular boundary: the α family solved at
// `frames` values over the search interval (run_sweep, one factorisation per value where the
// backend needs one) plus the optima and α = −1/4, 0; per value the net, the Bézier surface
// sampled on samples × samples points with its unit normals (sample_grid) and the exact energies
// (net_metrics); per energy its optimum by the α search (search_alpha). For boundaries with two
// data rings also the C1 family's weight w (family_search.h), the same way. Sizes: frames · (#net +
// 2·samples²) points.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "coons/io/view_page.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"
#include "coons/surfaces/bspline_surface.h"
#include "coons/tri/tri_net.h"
#include "solvers/registry.h"

namespace coons {

struct ViewOptions {
  int frames = 101;                    //!< α values on an even grid over [lower, upper] (≥ 2)
  int samples = 33;                    //!< surface samples per direction (≥ 2)
  double lower = -0.25, upper = 0.25;  //!< the search interval of search-alpha
  //! the energy curves, each with its optimum: any name parse_objective knows without a target
  std::vector<std::string> objectives = {"thin_plate", "e3", "dirichlet", "twist"};

  bool is_valid(std::string* why) const;
};

//! The member of ViewOptions at fault (kInterval: lower and upper together), so that a caller can
//! name what set it.
enum class ViewOptionsField { kNone, kFrames, kSamples, kInterval, kObjectives };

struct ViewOptionsProblem {
  ViewOptionsField field = ViewOptionsField::kNone;
  std::string reason;  //!< with the values at fault
};

//! The first rule of ViewOptions::is_valid that `options` breaks (field kNone: none).
ViewOptionsProblem options_problem(const ViewOptions& options);

//! The α slider of a boundary (m, n ≥ 1); `initial` is the α shown first (nearest frame).
ViewSlider alpha_view_slider(const Boundary& boundary, const ViewOptions& options, const solvers::SolverInfo& solver,
                             double initial);

//! The C1-weight slider of a problem with two data rings (ribbons): the 5×5 family
//! c1_family_stencil(w) at `options.frames` values of w ∈ [0, 1] plus the optima (search_weight);
//! `solver` must work from the matrix (weight_search_backend). The net shown is the whole net,
//! ribbons included.
ViewSlider weight_view_slider(const StencilProblem& problem, const ViewOptions& options,
                              const solvers::SolverInfo& solver, double initial);

//! The α slider of a B-spline boundary (its compatible form): the non-uniform mask family
//! (docs/math.md §10) at `options.frames` values of [options.lower, options.upper] plus the optima
//! (search_bspline_alpha) and α = −1/4 (the Greville Coons net), 0; per value the B-spline
//! surface's control net, its samples and normals (sample_bspline_grid) and its exact energies
//! (bspline_metrics). `solver_name`: a backend that takes an assembled matrix, definite-only ones
//! only where the bounds lie in [−1/4, bspline_definite_upper]. The page solves the values between
//! the frames itself (bspline_view_system).
ViewSlider bspline_view_slider(const BSplineBoundary& compatible, const ViewOptions& options,
                               const std::string& solver_name, double initial);

//! The slider of a triangular boundary (n ≥ 1): the triangular mask family over c ∈ [lower,
//! upper] (default_tri_bounds when lower ≥ upper) at `options.frames` values plus the optima of
//! thin_plate, e3, dirichlet and twist (search_tri_c) and c = −1/6, 0; samples per side
//! `options.samples` (sample_tri_surface). The parameter is called "alpha" on the page, as
//! `coons solve T.json --alpha c` calls it.
ViewSlider tri_view_slider(const tri::TriBoundary& boundary, const ViewOptions& options,
                           const solvers::SolverInfo& solver, double initial);

//! The systems the page solves between the frames (ViewSystem: A(t) = A0 + t·A1, B(t) = B0 + t·B1),
//! none where the family has no free point or more than ViewSystem::kMaxFree. The triangular family
//! over c on `frame` (tri::assemble_tri_mask_system, affine in c); the non-uniform α family of a
//! B-spline boundary (assemble_nonuniform_mask_system's A and dA), sampled with the knots of its
//! surfaces (bspline_surface_on);
//! the C1 family over w on `problem`, whose normalised stencil W_w = (w·C + (1 − w)·T)/(20 + 16w)
//! (stencil.h) gives the system times 20 + 16w, affine in w.
std::optional<ViewSystem> tri_view_system(const tri::TriNet& frame, int samples);
std::optional<ViewSystem> bspline_view_system(const BSplineBoundary& compatible, int samples);
std::optional<ViewSystem> weight_view_system(const StencilProblem& problem, int samples);

//! The edges of a triangular net of degree n (row order of tri_net.h): each point to its
//! neighbours in the three directions.
std::vector<std::array<int, 2>> tri_net_edges(int n);

//! Opens the slider at the optimum of its thin-plate curve, when that curve has one (else its
//! `initial` stays).
void open_at_thin_plate_optimum(ViewSlider& slider);

//! A surface sampled for the page: the points and unit normals of the Bézier surface of `net`.
void sample_view_frame(const ControlNet& net, int samples, ViewFrame& frame);

}  // namespace coons
