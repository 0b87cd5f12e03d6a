// PNG plots through gnuplot (Debian's gnuplot-nox): line plots of curves with marked points,
// and 3-D views of a surface with its control net. Data go to files beside the PNG's temporary
// folder; nothing is left behind but the PNG.
#pragma once

#include <string>
#include <vector>

#include "coons/net/control_net.h"

namespace coons {

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  bool points = false;  //!< points only (markers), else lines
};

struct PlotOptions {
  std::string title, xlabel, ylabel;
  bool log_x = false, log_y = false;
  int width = 900, height = 600;
};

//! Writes `png`; returns an empty string, or why it could not (gnuplot missing or failed).
std::string plot_curves(const std::string& png, const std::vector<PlotSeries>& series, const PlotOptions& options);

//! Side-by-side 3-D views of several nets: each surface (sampled k × k) with its control net.
std::string plot_nets(const std::string& png, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                      const std::string& title);

//! A 3-D view of a surface sampled on a k × k grid (#k² by 3, row a·k + b = r(a/(k−1), b/(k−1)))
//! with, when given, a control net drawn over it. Used by `coons surface --png`.
std::string plot_surface(const std::string& png, const Eigen::MatrixX3d& grid, int k, const ControlNet* net,
                         const std::string& title);

}  // namespace coons
