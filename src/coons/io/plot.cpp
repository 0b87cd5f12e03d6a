#include "plot.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include "coons/net/bernstein.h"

namespace coons {

namespace fs = std::filesystem;

namespace {

struct Scratch {
  fs::path dir;
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "coons_plot_XXXXXX").string();
    dir = mkdtemp(pattern.data()) ? fs::path(pattern) : fs::path();
  }
  ~Scratch() {
    std::error_code ec;
    if (!dir.empty()) fs::remove_all(dir, ec);
  }
};

std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string run_gnuplot(const Scratch& scratch, const std::string& script, const std::string& png) {
  const fs::path gp = scratch.dir / "plot.gp";
  std::ofstream(gp) << script;
  const std::string partial = png + ".part.png";
  const std::string command = "gnuplot " + quote(gp.string()) + " >" + quote((scratch.dir / "log").string()) + " 2>&1";
  if (std::system(command.c_str()) != 0 || !fs::exists(partial)) {
    std::ifstream log(scratch.dir / "log");
    std::string first;
    std::getline(log, first);
    std::error_code ec;
    fs::remove(partial, ec);
    return "gnuplot failed" + (first.empty() ? std::string(" (is gnuplot-nox installed?)") : ": " + first);
  }
  std::error_code ec;
  fs::rename(partial, png, ec);
  return ec ? "cannot rename " + partial + ": " + ec.message() : "";
}

}  // namespace

std::string plot_curves(const std::string& png, const std::vector<PlotSeries>& series, const PlotOptions& o) {
  Scratch scratch;
  if (scratch.dir.empty()) return "cannot create a temporary folder";
  std::string plots;
  for (size_t k = 0; k < series.size(); ++k) {
    const fs::path data = scratch.dir / fmt::format("s{}.dat", k);
    std::ofstream out(data);
    for (size_t r = 0; r < series[k].x.size(); ++r) fmt::print(out, "{} {}\n", series[k].x[r], series[k].y[r]);
    plots += fmt::format("{}{} using 1:2 with {} title {}", k ? ", " : "", quote(data.string()),
                         series[k].points ? "points pt 7 ps 1.6" : "lines lw 2", quote(series[k].title));
  }
  std::string script = fmt::format("set terminal pngcairo size {},{} enhanced font ',11'\nset output {}\n", o.width, o.height,
                                   quote(png + ".part.png"));
  script += fmt::format("set title {}\nset xlabel {}\nset ylabel {}\nset grid\nset key outside right\n", quote(o.title),
                        quote(o.xlabel), quote(o.ylabel));
  if (o.log_x) script += "set logscale x\n";
  if (o.log_y) script += "set logscale y\n";
  script += "plot " + plots + "\n";
  return run_gnuplot(scratch, script, png);
}

std::string plot_nets(const std::string& png, const std::vector<std::pair<std::string, ControlNet>>& nets, int k,
                      const std::string& title) {
  Scratch scratch;
  if (scratch.dir.empty()) return "cannot create a temporary folder";
  const int count = int(nets.size());
  std::string script = fmt::format("set terminal pngcairo size {},{} enhanced font ',10'\nset output {}\n", 420 * count, 460,
                                   quote(png + ".part.png"));
  script += fmt::format("set multiplot layout 1,{} title {}\nset view 60,30\nunset key\nset ticslevel 0\n", count,
                        quote(title));
  for (int c = 0; c < count; ++c) {
    const ControlNet& net = nets[c].second;
    const fs::path surface = scratch.dir / fmt::format("surface{}.dat", c), grid = scratch.dir / fmt::format("net{}.dat", c);
    {
      std::ofstream out(surface);
      const Eigen::MatrixX3d S = sample_surface(net, k, k);
      for (int s = 0; s < k; ++s) {
        for (int t = 0; t < k; ++t) fmt::print(out, "{} {} {}\n", S(s * k + t, 0), S(s * k + t, 1), S(s * k + t, 2));
        out << '\n';
      }
    }
    {
      std::ofstream out(grid);
      for (int i = 0; i <= net.m; ++i) {
        for (int j = 0; j <= net.n; ++j) fmt::print(out, "{} {} {}\n", net.at(i, j)(0), net.at(i, j)(1), net.at(i, j)(2));
        out << '\n';
      }
    }
    script += fmt::format("set title {}\nsplot {} with lines lc rgb '#3060c0', {} with linespoints lc rgb '#d04020' pt 7 ps 0.5\n",
                          quote(nets[c].first), quote(surface.string()), quote(grid.string()));
  }
  script += "unset multiplot\n";
  return run_gnuplot(scratch, script, png);
}

std::string plot_surface(const std::string& png, const Eigen::MatrixX3d& grid, int k, const ControlNet* net,
                         const std::string& title) {
  Scratch scratch;
  if (scratch.dir.empty()) return "cannot create a temporary folder";
  const fs::path surface = scratch.dir / "surface.dat", control = scratch.dir / "net.dat";
  {
    std::ofstream out(surface);
    for (int a = 0; a < k; ++a) {
      for (int b = 0; b < k; ++b) fmt::print(out, "{} {} {}\n", grid(a * k + b, 0), grid(a * k + b, 1), grid(a * k + b, 2));
      out << '\n';
    }
  }
  std::string plots = fmt::format("{} with lines lc rgb '#3060c0' title 'surface'", quote(surface.string()));
  if (net) {
    std::ofstream out(control);
    for (int i = 0; i <= net->m; ++i) {
      for (int j = 0; j <= net->n; ++j) fmt::print(out, "{} {} {}\n", net->at(i, j)(0), net->at(i, j)(1), net->at(i, j)(2));
      out << '\n';
    }
    plots += fmt::format(", {} with linespoints lc rgb '#d04020' pt 7 ps 0.6 title 'control net'", quote(control.string()));
  }
  std::string script = fmt::format("set terminal pngcairo size 800,640 enhanced font ',10'\nset output {}\n",
                                   quote(png + ".part.png"));
  script += fmt::format("set title {} noenhanced\nset view 60,30\nset ticslevel 0\nset view equal xy\nset key top left\n",
                        quote(title));
  script += "splot " + plots + "\n";
  return run_gnuplot(scratch, script, png);
}

}  // namespace coons
