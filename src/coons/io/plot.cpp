#include "plot.h"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>

#include "coons/net/bernstein.h"

namespace coons {

namespace fs = std::filesystem;

namespace {

// Okabe–Ito (without yellow) and five more, all readable on white and distinct from each other.
constexpr std::array<const char*, 12> kPalette = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9",
                                                  "#000000", "#882255", "#999933", "#6a3d9a", "#a6761d", "#7f7f7f"};
// gnuplot point types as (open, filled) pairs: square, circle, triangle up, triangle down, diamond, pentagon.
constexpr std::array<std::pair<int, int>, 6> kMarkers = {{{4, 5}, {6, 7}, {8, 9}, {10, 11}, {12, 13}, {14, 15}}};
constexpr int kDashTypes = 5;
constexpr int kSparseMarkers = 8;  // markers drawn along a line series

struct Style {
  const char* colour;
  int open_marker, filled_marker, dash;
};

// Series k: colour k mod 12; the marker shifts by one every 12 series and the dash pattern changes,
// so (colour, marker, dash) never repeats within a figure.
Style style_of(size_t k) {
  const size_t round = k / kPalette.size();
  const auto& marker = kMarkers[(k + round) % kMarkers.size()];
  return {kPalette[k % kPalette.size()], marker.first, marker.second, 1 + int(round % kDashTypes)};
}

struct Scratch {
  fs::path dir;
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "coons_plot_XXXXXX").string();
    dir = mkdtemp(pattern.data()) != nullptr ? fs::path(pattern) : fs::path();
  }
  ~Scratch() {
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
};

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {  // a line break would end the gnuplot command: labels stay on one line
    out += c == '\'' ? std::string("''") : c == '\n' || c == '\r' ? std::string(" ") : std::string(1, c);
  }
  return out + "'";
}

std::string partial_of(const std::string& png) { return png + ".part.png"; }

// gnuplot's message in its log: it echoes the script line and a caret, then
// `"plot.gp" line N: MESSAGE` and maybe `system error: WHY`; the message and the reason, else
// the first line that is not blank.
std::string gnuplot_error(const fs::path& log_file) {
  std::ifstream log(log_file);
  std::string first, message;
  for (std::string line; std::getline(log, line);) {
    if (first.empty() && line.find_first_not_of(" \t\r^") != std::string::npos) first = line;
    if (const auto at = line.find("\" line "); message.empty() && at != std::string::npos) {
      if (const auto colon = line.find(": ", at); colon != std::string::npos) message = line.substr(colon + 2);
    } else if (!message.empty() && line.rfind("system error: ", 0) == 0) {
      return message + " (" + line.substr(14) + ")";
    }
  }
  return message.empty() ? first : message;
}

}  // namespace

std::string run_gnuplot(const std::string& script, const std::string& png, double seconds) {
  if (!(seconds > 0) || !std::isfinite(seconds)) return fmt::format("bad gnuplot time limit {} s", seconds);
  // gnuplot's commands are lines: a line break in the name cannot be written (quote() makes it a
  // space, gnuplot wrote "a b.png…", and the file it wrote was left behind under that name)
  if (png.find_first_of("\n\r") != std::string::npos)
    return "gnuplot cannot write a file whose name holds a line break; choose another name";
  const Scratch scratch;
  if (scratch.dir.empty()) return "cannot create a temporary folder";
  const fs::path gp = scratch.dir / "plot.gp";
  std::ofstream(gp) << script;
  const std::string partial = partial_of(png);
  // coreutils' timeout runs gnuplot in its own process group and ends the group: TERM after
  // `seconds`, KILL 5 s later (exit status 124 or 137); gnuplot reads no terminal input.
  const std::string command = fmt::format("timeout -k 5 {} gnuplot {} </dev/null >{} 2>&1", seconds, quote(gp.string()),
                                          quote((scratch.dir / "log").string()));
  const int status = std::system(command.c_str());
  if (status != 0 || !fs::exists(partial)) {
    const std::string first = gnuplot_error(scratch.dir / "log");
    std::error_code ec;
    fs::remove(partial, ec);
    // the shell's 127: no gnuplot; 0 without the file: it could not write there (and may say nothing)
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return "gnuplot was not found (is gnuplot-nox installed?)";
    if (WIFEXITED(status) && (WEXITSTATUS(status) == 124 || WEXITSTATUS(status) == 137))
      return fmt::format("gnuplot did not finish within {} s and was stopped", seconds);
    if (status == 0)
      return "gnuplot could not write " + partial + (first.empty() ? " (is its folder writable?)" : ": " + first);
    const std::string how = WIFEXITED(status)     ? fmt::format("exit status {}", WEXITSTATUS(status))
                            : WIFSIGNALED(status) ? fmt::format("killed by signal {}", WTERMSIG(status))
                                                  : fmt::format("wait status {}", status);
    return "gnuplot failed" + (first.empty() ? " (" + how + ", no message)" : ": " + first);
  }
  std::error_code ec;
  fs::rename(partial, png, ec);
  return ec ? "cannot rename " + partial + ": " + ec.message() : "";
}

namespace {

// Literal text everywhere, UTF-8, sans-serif.
std::string terminal(int width, int height, int font_size, const std::string& output) {
  return fmt::format(
      "set encoding utf8\nset terminal pngcairo noenhanced size {},{} font 'DejaVu Sans,{}' linewidth 1.2\n"
      "set output {}\n",
      width, height, font_size, quote(output));
}

std::string number(double v, bool log) { return std::isfinite(v) && (!log || v > 0) ? fmt::format("{}", v) : "NaN"; }

std::string datablock(const std::string& name, const std::vector<double>& x, const std::vector<double>& y, bool log_x,
                      bool log_y, size_t first = 0, size_t step = 1) {
  std::string out = "$" + name + " << EOD\n";
  for (size_t r = first; r < x.size() && r < y.size(); r += step) {
    out += number(x[r], log_x) + " " + number(y[r], log_y) + "\n";
  }
  return out + "EOD\n";
}

struct Extent {
  double low = std::numeric_limits<double>::infinity(), high = -std::numeric_limits<double>::infinity();
  bool all_positive = true;
  std::vector<double> values;
  void add(double v) {
    if (!std::isfinite(v)) return;
    low = std::min(low, v);
    high = std::max(high, v);
    all_positive = all_positive && v > 0;
    values.push_back(v);
  }
  [[nodiscard]] bool empty() const { return low > high; }
  [[nodiscard]] double median() const {
    std::vector<double> v = values;
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  }
};

Extent extent_of(const std::vector<PlotSeries>& series, bool y, bool positive_only) {
  Extent e;
  const auto add = [&](const std::vector<double>& values) {
    for (double v : values) {
      if (!positive_only || v > 0) e.add(v);
    }
  };
  for (const PlotSeries& s : series) {
    add(y ? s.y : s.x);
    add(y ? s.marker_y : s.marker_x);
  }
  return e;
}

// kAuto: logarithmic when the positive values span more than `decades` decades and a linear axis would
// squash most of them: half of them lie below a tenth of the largest (one outlier above the rest). A
// curve that touches zero at one end (1e-31, say) keeps its linear axis.
bool use_log(bool forced, AxisScale scale, const Extent& e, double decades) {
  if (forced || scale == AxisScale::kLog) return true;
  if (scale == AxisScale::kLinear || e.empty() || !e.all_positive) return false;
  return std::log10(e.high / e.low) > decades && e.median() < 0.1 * e.high;
}

bool all_small_integers(const Extent& e) {
  return !e.empty() && e.high - e.low <= 30 &&
         std::all_of(e.values.begin(), e.values.end(), [](double v) { return v == std::round(v); });
}

// `set Xrange` fitted to the data with a small margin, and readable tics on short log axes.
std::string axis_commands(const char* axis, const Extent& e, bool log, double margin) {
  if (e.empty()) return "";
  std::string out;
  if (log) {
    const double a = std::log10(e.low), b = std::log10(e.high);
    const double pad = b > a ? margin * (b - a) : 0.1;
    const double low = std::pow(10.0, a - pad), high = std::pow(10.0, b + pad);
    out += fmt::format("set logscale {}\nset {}range [{}:{}]\nset format {} '%g'\n", axis, axis, low, high, axis);
    if (b - a < 3) {  // too few powers of ten: tics at 1, 2, 5 (or every digit) times a power of ten
      const std::vector<int> digits =
          b - a < 1 ? std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9} : std::vector<int>{1, 2, 5};
      std::string tics;
      for (int p = int(std::floor(a - pad)); p <= int(std::ceil(b + pad)); ++p) {
        for (int d : digits) {
          const double t = d * std::pow(10.0, p);
          if (t >= low && t <= high) tics += fmt::format("{}{:g}", tics.empty() ? "" : ", ", t);
        }
      }
      if (!tics.empty()) out += fmt::format("set {}tics ({})\n", axis, tics);
    }
    return out;
  }
  if (all_small_integers(e)) out += fmt::format("set {}tics 1\n", axis);  // degrees: no tic at 3.5
  const double span = e.high - e.low;
  const double pad = span > 0 ? margin * span : std::max(0.1 * std::abs(e.high), 1.0);
  return out + fmt::format("set {}range [{}:{}]\n", axis, e.low - pad, e.high + pad);
}

// Key below the plot in as many columns as fit the width.
std::string key_commands(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  size_t longest = o.marker_title.size();
  size_t entries = o.marker_title.empty() ? 0 : 1;
  for (const PlotSeries& s : series) {
    longest = std::max(longest, s.title.size());
    entries += s.title.empty() ? 0 : 1;
  }
  if (entries == 0) return "unset key\n";
  const double column = 6.5 * double(longest) + 60;  // pixels of one key column at font size 9
  const size_t columns = std::clamp<size_t>(size_t((o.width - 80) / column), 1, entries);
  return fmt::format(
      "set key outside below center horizontal Left reverse maxcols {} samplen 2.5 spacing 1.1 width 1 height 0.6 "
      "font ',9'\n",
      columns);
}

}  // namespace

bool PlotOptions::is_valid(std::string* why) const {
  std::string reason;
  if (width < 100 || width > 20000 || height < 100 || height > 20000) {
    reason = fmt::format("width and height must be in [100, 20000] pixels, got {}x{}", width, height);
  } else if (!(log_decades > 0)) {
    reason = "log_decades must be positive";
  }
  if (why != nullptr) *why = reason;
  return reason.empty();
}

std::pair<bool, bool> plot_log_axes(const std::vector<PlotSeries>& series, const PlotOptions& o) {
  return {use_log(o.log_x, o.x_scale, extent_of(series, false, false), o.log_decades),
          use_log(o.log_y, o.y_scale, extent_of(series, true, false), o.log_decades)};
}

std::string curves_script(const std::string& output, const std::vector<PlotSeries>& series, const PlotOptions& o) {
  const auto [log_x, log_y] = plot_log_axes(series, o);
  std::string script = terminal(o.width, o.height, 11, output);
  script += fmt::format("set title {} font ',12'\nset xlabel {}\nset ylabel {}\n", quote(o.title), quote(o.xlabel),
                        quote(o.ylabel));
  script += "set border 3\nset tics nomirror out\nset grid xtics ytics mxtics mytics lc rgb '#e0e0e0' lw 0.6\n";
  script += "set minussign\nset samples 2\n";  // NaN key samples need no resolution
  script += key_commands(series, o);
  script += axis_commands("x", extent_of(series, false, log_x), log_x, 0.015);
  script += axis_commands("y", extent_of(series, true, log_y), log_y, 0.05);

  std::vector<std::string> plots;
  for (size_t k = 0; k < series.size(); ++k) {
    const PlotSeries& s = series[k];
    const Style st = style_of(k);
    const std::string colour = fmt::format("lc rgb '{}'", st.colour);
    script += datablock(fmt::format("s{}", k), s.x, s.y, log_x, log_y);
    if (s.points) {
      plots.push_back(fmt::format("$s{} using 1:2 with points {} pt {} ps 1.4 notitle", k, colour, st.filled_marker));
    } else {
      plots.push_back(fmt::format("$s{} using 1:2 with lines {} lw 2 dt {} notitle", k, colour, st.dash));
      // a few open markers along the line, staggered between series so that coinciding curves stay apart
      const size_t step = std::max<size_t>(1, s.x.size() / kSparseMarkers);
      script += datablock(fmt::format("p{}", k), s.x, s.y, log_x, log_y, (k * step / 3) % step, step);
      plots.push_back(fmt::format("$p{} using 1:2 with points {} pt {} ps 1.1 notitle", k, colour, st.open_marker));
    }
    if (!s.marker_x.empty()) {
      script += datablock(fmt::format("m{}", k), s.marker_x, s.marker_y, log_x, log_y);
      plots.push_back(fmt::format("$m{} using 1:2 with points {} pt {} ps 2.3 notitle", k, colour, st.filled_marker));
      plots.push_back(
          fmt::format("$m{} using 1:2 with points lc rgb '#000000' pt {} ps 2.3 lw 0.8 notitle", k, st.open_marker));
    }
    if (!s.title.empty()) {  // the key entry: line and marker as drawn
      plots.push_back(
          s.points ? fmt::format("NaN with points {} pt {} ps 1.4 title {}", colour, st.filled_marker, quote(s.title))
                   : fmt::format("NaN with linespoints {} lw 2 dt {} pt {} ps 1.1 title {}", colour, st.dash,
                                 st.open_marker, quote(s.title)));
    }
  }
  if (!o.marker_title.empty()) {
    plots.push_back(fmt::format("NaN with points lc rgb '#000000' pt 6 ps 2.0 title {}", quote(o.marker_title)));
  }
  if (plots.empty()) plots.emplace_back("NaN notitle");
  script += "plot ";
  for (size_t k = 0; k < plots.size(); ++k) script += (k > 0 ? ", \\\n     " : "") + plots[k];
  return script + "\n";
}

std::string plot_curves(const std::string& png, const std::vector<PlotSeries>& series, const PlotOptions& o) {
  std::string why;
  if (!o.is_valid(&why)) return why;
  for (const PlotSeries& s : series) {
    if (s.x.size() != s.y.size() || s.marker_x.size() != s.marker_y.size()) {
      return "series '" + s.title + "': x and y differ in length";
    }
  }
  return run_gnuplot(curves_script(partial_of(png), series, o), png);
}

namespace {

std::string grid_block(const std::string& name, const Eigen::MatrixX3d& points, int rows, int columns) {
  std::string out = "$" + name + " << EOD\n";
  for (int a = 0; a < rows; ++a) {
    for (int b = 0; b < columns; ++b) {
      const auto p = points.row(a * columns + b);
      out += fmt::format("{} {} {}\n", p(0), p(1), p(2));
    }
    out += "\n";
  }
  return out + "EOD\n";
}

Eigen::MatrixX3d net_points(const ControlNet& net) {
  Eigen::MatrixX3d P((net.m + 1) * (net.n + 1), 3);
  for (int i = 0; i <= net.m; ++i) {
    for (int j = 0; j <= net.n; ++j) P.row(i * (net.n + 1) + j) = net.at(i, j);
  }
  return P;
}

// Ranges shared by every panel, so that the panels compare; x and y drawn to the same scale.
std::string box_commands(const std::vector<const Eigen::MatrixX3d*>& clouds) {
  Eigen::RowVector3d low = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::RowVector3d high = -low;
  for (const Eigen::MatrixX3d* c : clouds) {
    if (c->rows() == 0) continue;
    low = low.cwiseMin(c->colwise().minCoeff());
    high = high.cwiseMax(c->colwise().maxCoeff());
  }
  if (!low.allFinite() || !high.allFinite()) return "";
  std::string out;
  const char* axes[] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const double pad = high(a) > low(a) ? 0.02 * (high(a) - low(a)) : 0.5;
    out += fmt::format("set {}range [{}:{}]\n", axes[a], low(a) - pad, high(a) + pad);
  }
  return out + "set view equal xy\nset xyplane at " + fmt::format("{}\n", low(2) - 0.02 * (high(2) - low(2)));
}

constexpr const char* kSurfaceStyle = "with lines lc rgb '#0072b2' lw 0.7";
constexpr const char* kNetStyle = "with linespoints lc rgb '#d55e00' lw 1.4 pt 7 ps 0.7";

}  // namespace

std::string nets_script(const std::string& output, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                        const std::string& title) {
  const int count = std::max(1, int(nets.size()));
  std::vector<Eigen::MatrixX3d> surfaces, controls;
  for (const auto& entry : nets) {
    surfaces.push_back(sample_surface(entry.second, k, k));
    controls.push_back(net_points(entry.second));
  }
  std::vector<const Eigen::MatrixX3d*> clouds;
  for (size_t c = 0; c < nets.size(); ++c) clouds.insert(clouds.end(), {&surfaces[c], &controls[c]});
  std::string script = terminal(460 * count, 500, 10, output);
  script += fmt::format("set multiplot layout 1,{} title {} font ',12'\n", count, quote(title));
  script += "set view 60,30\nset tics font ',8'\n" + box_commands(clouds);
  for (size_t c = 0; c < nets.size(); ++c) {
    const ControlNet& net = nets[c].second;
    script += grid_block(fmt::format("surface{}", c), surfaces[c], k, k);
    script += grid_block(fmt::format("net{}", c), controls[c], net.m + 1, net.n + 1);
    script += c == 0 ? "set key at screen 0.01, screen 0.99 left top vertical Left reverse font ',9' samplen 2\n"
                     : "unset key\n";
    script +=
        fmt::format("set title {}\nsplot $surface{} {} title {}, $net{} {} title 'control net'\n", quote(nets[c].first),
                    c, kSurfaceStyle, quote(fmt::format("surface ({0}×{0} samples)", k)), c, kNetStyle);
  }
  return script + "unset multiplot\n";
}

std::string plot_nets(const std::string& png, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                      const std::string& title) {
  if (nets.empty()) return "no nets to draw";
  if (k < 2) return "a surface needs at least 2 samples per direction";
  return run_gnuplot(nets_script(partial_of(png), nets, k, title), png);
}

std::string plot_surface(const std::string& png, const Eigen::MatrixX3d& grid, int k, const ControlNet* net,
                         const std::string& title) {
  if (k < 2 || grid.rows() != Eigen::Index(k) * k) return "the surface grid is not k × k";
  std::string script = terminal(800, 640, 10, partial_of(png));
  const Eigen::MatrixX3d control = net != nullptr ? net_points(*net) : Eigen::MatrixX3d(0, 3);
  script += fmt::format("set title {} font ',12'\nset view 60,30\nset tics font ',8'\nset key top left Left reverse\n",
                        quote(title));
  script += box_commands({&grid, &control});
  script += grid_block("surface", grid, k, k);
  std::string plots = fmt::format("$surface {} title 'surface'", kSurfaceStyle);
  if (net != nullptr) {
    script += grid_block("net", control, net->m + 1, net->n + 1);
    plots += fmt::format(", $net {} title 'control net'", kNetStyle);
  }
  return run_gnuplot(script + "splot " + plots + "\n", png);
}

}  // namespace coons
