// PNG plots through gnuplot (Debian's gnuplot-nox): line plots of curves with marked points,
// and 3-D views of a surface with its control net. Each figure is one self-contained gnuplot
// script (data inline as datablocks), so nothing is left behind but the PNG. Every label is
// literal text (no gnuplot "enhanced" markup: `thin_plate` stays `thin_plate`, α and μ are UTF-8);
// every series of a figure has its own colour, marker and (past 12 series) dash pattern.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "coons/net/control_net.h"

namespace coons {

struct PlotSeries {
  std::string title;
  std::vector<double> x, y;
  bool points = false;  //!< points only (markers), else lines
  //! Marked points of this series (e.g. its minimum): large filled markers in the series' colour.
  std::vector<double> marker_x{}, marker_y{};
};

//! How an axis is scaled. kAuto: logarithmic when every value on it is positive, the values span more
//! than PlotOptions::log_decades decades and half of them lie below a tenth of the largest (a linear
//! axis would squash them under an outlier), else linear.
enum class AxisScale { kAuto, kLinear, kLog };

struct PlotOptions {
  std::string title, xlabel, ylabel;
  //! true forces a logarithmic axis; false leaves the choice to x_scale / y_scale (automatic by default).
  bool log_x = false, log_y = false;
  int width = 900, height = 600;
  AxisScale x_scale = AxisScale::kAuto, y_scale = AxisScale::kAuto;
  double log_decades = 1;      //!< kAuto turns logarithmic beyond this many decades
  std::string marker_title{};  //!< key entry explaining the series' marked points ("minimum"); none when empty

  [[nodiscard]] bool is_valid(std::string* why = nullptr) const;
};

//! How long a figure's gnuplot may run before it is stopped (a figure of the study takes well under 1 s).
inline constexpr double kGnuplotSeconds = 120;

//! Runs `script`, which must write `png`.part.png; renames that to `png` when gnuplot succeeded.
//! gnuplot is stopped after `seconds`. Returns an empty string, or why there is no PNG (gnuplot
//! missing, failed, stopped; its own message when it gave one). Nothing is left behind on failure.
std::string run_gnuplot(const std::string& script, const std::string& png, double seconds = kGnuplotSeconds);

//! The axis scales plot_curves uses for these series and options: {x is log, y is log}.
std::pair<bool, bool> plot_log_axes(const std::vector<PlotSeries>& series, const PlotOptions& options);

//! The gnuplot script plot_curves runs (writes `output`); exposed so its styling can be checked.
std::string curves_script(const std::string& output, const std::vector<PlotSeries>& series, const PlotOptions& options);

//! Writes `png`; returns an empty string, or why it could not (gnuplot missing or failed, bad options).
std::string plot_curves(const std::string& png, const std::vector<PlotSeries>& series, const PlotOptions& options);

//! The gnuplot script plot_nets runs: one panel per net, all on the same x, y, z ranges.
std::string nets_script(const std::string& output, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                        const std::string& title);

//! Side-by-side 3-D views of several nets: each surface (sampled k × k) with its control net.
std::string plot_nets(const std::string& png, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                      const std::string& title);

//! A 3-D view of a surface sampled on a k × k grid (#k² by 3, row a·k + b = r(a/(k−1), b/(k−1)))
//! with, when given, a control net drawn over it. Used by `coons surface --png`.
std::string plot_surface(const std::string& png, const Eigen::MatrixX3d& grid, int k, const ControlNet* net,
                         const std::string& title);

}  // namespace coons
