// The data of a `coons view` page (view_page.h) for a rectangular boundary: the α family solved at
// `frames` values over the search interval (run_sweep, one factorisation per value where the
// backend needs one) plus the optima and α = −1/4, 0; per value the net, the Bézier surface
// sampled on samples × samples points with its unit normals (sample_grid) and the exact energies
// (net_metrics); per energy its optimum by the α search (search_alpha). Sizes: frames · (#net +
// 2·samples²) points.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <string>
#include <vector>

#include "coons/io/view_page.h"
#include "coons/net/control_net.h"
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

//! The α slider of a boundary (m, n ≥ 1); `initial` is the α shown first (nearest frame).
ViewSlider alpha_view_slider(const Boundary& boundary, const ViewOptions& options, const solvers::SolverInfo& solver,
                             double initial);

//! A surface sampled for the page: the points and unit normals of the Bézier surface of `net`.
void sample_view_frame(const ControlNet& net, int samples, ViewFrame& frame);

}  // namespace coons
