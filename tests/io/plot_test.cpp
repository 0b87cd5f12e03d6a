#include "coons/io/plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <tuple>

#include "coons/io/boundary_io.h"
#include "coons/mask/solve_mask_net.h"
#include "coons/metrics/energies.h"
#include "coons/net/bernstein.h"
#include "coons/net/coons_net.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;

namespace {

bool have_gnuplot() { return run_command("gnuplot --version").status == 0; }

// A PNG of the expected size with real content: signature, IHDR width and height, more than a few KB.
void check_png(const std::string& path, int width, int height) {
  REQUIRE(std::filesystem::exists(path));
  CHECK(std::filesystem::file_size(path) > 8000);
  std::ifstream in(path, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  CHECK(head.substr(0, 8) == std::string("\x89PNG\r\n\x1a\n", 8));
  CHECK(head.substr(12, 4) == "IHDR");
  const auto be32 = [&](int at) {
    int v = 0;
    for (int b = 0; b < 4; ++b) v = v * 256 + static_cast<unsigned char>(head[at + b]);
    return v;
  };
  CHECK(be32(16) == width);
  CHECK(be32(20) == height);
  CHECK_FALSE(std::filesystem::exists(path + ".part.png"));
}

// Key entries of a curves script: (colour, point type, dash type or 0 for points, title).
std::vector<std::tuple<std::string, int, int, std::string>> key_entries(const std::string& script) {
  std::vector<std::tuple<std::string, int, int, std::string>> out;
  const std::regex entry(
      R"(NaN with (lines)?points lc rgb '(#[0-9a-f]{6})'(?: lw \S+ dt (\d+))? pt (\d+) ps \S+ title '([^']*)')");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), entry); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    out.emplace_back(m[2], std::stoi(m[4]), m[3].matched ? std::stoi(m[3]) : 0, m[5]);
  }
  return out;
}

std::pair<double, double> range_of(const std::string& script, const std::string& axis) {
  const std::regex r("set " + axis + R"(range \[(\S+):(\S+)\])");
  std::smatch m;
  REQUIRE(std::regex_search(script, m, r));
  return {std::stod(m[1]), std::stod(m[2])};
}

PlotSeries line(const std::string& title, std::vector<double> x, std::vector<double> y) {
  PlotSeries s{title, std::move(x), std::move(y), false};
  return s;
}

}  // namespace

TEST_CASE("plot_curves: every series has its own colour, marker and line", "[io][plot]") {
  std::vector<PlotSeries> series;
  for (int k = 0; k < 30; ++k) {
    series.push_back(line(fmt::format("series {}", k), {0, 1, 2}, {double(k), k + 1.0, k + 0.5}));
    series.back().points = k % 3 == 2;
  }
  const auto entries = key_entries(curves_script("out.png", series, PlotOptions{}));
  REQUIRE(entries.size() == series.size());
  std::set<std::string> first_colours;
  std::set<std::pair<std::string, int>> styles;  // (colour, marker shape: open and filled count as one)
  for (size_t k = 0; k < entries.size(); ++k) {
    const auto& [colour, marker, dash, title] = entries[k];
    CHECK(title == series[k].title);
    if (k < 12) first_colours.insert(colour);
    CHECK(dash == (series[k].points ? 0 : int(k / 12) + 1));  // past 12 lines, a new dash pattern
    styles.emplace(colour, marker % 2 == 0 ? marker : marker - 1);
  }
  CHECK(first_colours.size() == 12);
  CHECK(styles.size() == series.size());
}

TEST_CASE("plot_curves: labels are literal text, not gnuplot markup", "[io][plot]") {
  PlotOptions o;
  o.title = "thin_plate optimum μ* (it's α*)";
  o.xlabel = "degree n";
  o.ylabel = "α* + 1/4";
  const std::string script = curves_script("out.png", {line("dome thin_plate", {3, 4}, {1, 2})}, o);
  CHECK(script.find("pngcairo noenhanced") != std::string::npos);
  CHECK(script.find("set encoding utf8") != std::string::npos);
  CHECK(script.find("set title 'thin_plate optimum μ* (it''s α*)'") != std::string::npos);
  CHECK(script.find("title 'dome thin_plate'") != std::string::npos);
  CHECK(curves_script("out.png", {line("two\nlines", {3, 4}, {1, 2})}, o).find("title 'two lines'") !=
        std::string::npos);
  CHECK(script.find("enhanced") == script.find("noenhanced") + 2);  // no other mention of enhanced text
}

TEST_CASE("plot_log_axes: positive data spanning decades under an outlier get a log axis", "[io][plot]") {
  const PlotSeries degrees = line("mu", {3, 4, 6, 8}, {0.5, 0.6, 0.55, 400});  // one outlier, 3 decades
  CHECK(plot_log_axes({degrees}, PlotOptions{}) == std::make_pair(false, true));
  // μ* of several shapes by degree, one of them far above the others (less than two decades)
  const std::vector<PlotSeries> mu = {line("dome", {3, 4, 6}, {595, 20, 15}), line("conoid", {3, 4, 6}, {47, 15, 12}),
                                      line("pillow", {3, 4, 6}, {45, 16, 11})};
  CHECK(plot_log_axes(mu, PlotOptions{}) == std::make_pair(false, true));
  PlotOptions two_decades;
  two_decades.log_decades = 2;
  CHECK_FALSE(plot_log_axes(mu, two_decades).second);
  PlotOptions linear;
  linear.y_scale = AxisScale::kLinear;
  CHECK(plot_log_axes({degrees}, linear) == std::make_pair(false, false));
  CHECK(plot_log_axes({line("narrow", {1, 2}, {0.5, 40})}, PlotOptions{}) == std::make_pair(false, false));
  CHECK(plot_log_axes({line("signed", {1, 2}, {-1e-3, 40})}, PlotOptions{}) == std::make_pair(false, false));
  // a curve that reaches zero at one end (1e-31 in floating point) keeps its linear axis
  CHECK(plot_log_axes({line("touches zero", {1, 2, 3, 4}, {1e-31, 0.4, 0.7, 1})}, PlotOptions{}).second == false);
  CHECK(plot_log_axes({line("decays", {1, 2, 3, 4}, {1, 1e-2, 1e-4, 1e-6})}, PlotOptions{}).second);
  PlotOptions forced;
  forced.log_x = true;
  CHECK(plot_log_axes({line("narrow", {1, 2}, {0.5, 40})}, forced) == std::make_pair(true, false));
  // marked points count: a marker three decades above the curve makes the axis logarithmic
  PlotSeries marked = line("curve", {1, 2}, {1, 2});
  marked.marker_x = {1.5};
  marked.marker_y = {1e3};
  CHECK(plot_log_axes({marked}, PlotOptions{}).second);
  const std::string script = curves_script("out.png", {degrees}, PlotOptions{});
  CHECK(script.find("set logscale y") != std::string::npos);
  CHECK(script.find("set logscale x") == std::string::npos);
  CHECK(script.find("set xtics 1\n") != std::string::npos);  // integer degrees: integer tics
}

TEST_CASE("plot_curves: axis ranges fit the data with a small margin", "[io][plot]") {
  const std::string script = curves_script(
      "out.png", {line("a", {-0.25, 0, 0.25}, {0.2, 0.1, 1}), line("b", {-0.25, 0.25}, {0.5, 0.6})}, PlotOptions{});
  const auto [x0, x1] = range_of(script, "x");
  CHECK(x0 < -0.25);
  CHECK(x0 > -0.26);
  CHECK(x1 > 0.25);
  CHECK(x1 < 0.26);
  const auto [y0, y1] = range_of(script, "y");
  CHECK(y0 < 0.1);
  CHECK(y0 > 0.05);
  CHECK(y1 > 1);
  CHECK(y1 < 1.05);
}

TEST_CASE("plot_curves: marked points are drawn in their series' colour", "[io][plot]") {
  std::vector<PlotSeries> series = {line("a", {0, 1, 2}, {2, 1, 2}), line("b", {0, 1, 2}, {3, 2.5, 3})};
  series[1].marker_x = {1};
  series[1].marker_y = {2.5};
  PlotOptions o;
  o.marker_title = "minimum";
  const std::string script = curves_script("out.png", series, o);
  const auto entries = key_entries(script);
  REQUIRE(entries.size() == 3);
  CHECK(std::get<3>(entries[2]) == "minimum");
  std::smatch m;
  REQUIRE(std::regex_search(script, m, std::regex(R"(\$m1 using 1:2 with points lc rgb '(#[0-9a-f]{6})')")));
  CHECK(m[1] == std::get<0>(entries[1]));
  CHECK(m[1] != std::get<0>(entries[0]));
  CHECK(script.find("$m0") == std::string::npos);
}

TEST_CASE("plot_curves: the dome's sweep energies render to a PNG", "[io][plot]") {
  REQUIRE(have_gnuplot());  // tests/CMakeLists.txt requires gnuplot for the tests
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/dome.json").boundary;
  using Energy = double (*)(const ControlNet&);
  const std::vector<std::pair<std::string, Energy>> energies = {
      {"thin_plate", thin_plate_energy}, {"E3", e3_energy}, {"twist", twist_energy}, {"Dirichlet", dirichlet_energy}};
  std::vector<PlotSeries> series;
  for (const auto& [name, energy] : energies) {
    PlotSeries s{name, {}, {}, false};
    for (int k = 0; k <= 20; ++k) {
      const double alpha = -0.25 + 0.025 * k;
      s.x.push_back(alpha);
      s.y.push_back(energy(solve_mask_net(b, alpha_mask(alpha), backend("eigen-ldlt")).net));
    }
    const auto best = std::min_element(s.y.begin(), s.y.end()) - s.y.begin();
    s.marker_x = {s.x[best]};
    s.marker_y = {s.y[best]};
    series.push_back(s);
  }
  PlotOptions o;
  o.title = "dome: energies against α";
  o.xlabel = "α";
  o.ylabel = "energy";
  o.marker_title = "minimum";
  const TempDir dir;
  const std::string png = dir.file("dome_energies.png");
  CHECK(plot_curves(png, series, o).empty());
  check_png(png, o.width, o.height);
  PlotOptions bad = o;
  bad.width = 10;
  CHECK_FALSE(bad.is_valid());
  CHECK_FALSE(plot_curves(dir.file("bad.png"), series, bad).empty());
  CHECK_FALSE(std::filesystem::exists(dir.file("bad.png")));
}

TEST_CASE("plot_nets: the dome's nets render side by side on shared ranges", "[io][plot]") {
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/dome.json").boundary;
  const std::vector<std::pair<std::string, ControlNet>> nets = {
      {"Coons (α = −1/4)", discrete_coons_net(b)},
      {"Laplace (α = 0)", solve_mask_net(b, alpha_mask(0), backend("eigen-ldlt")).net}};
  const std::string script = nets_script("out.png", nets, 9, "dome_shape");
  CHECK(script.find("noenhanced") != std::string::npos);
  CHECK(script.find("'dome_shape'") != std::string::npos);
  // one set of ranges for every panel, covering the taller (Coons) net
  const auto [z0, z1] = range_of(script, "z");
  const Eigen::MatrixX3d coons = sample_surface(nets[0].second, 9, 9);
  CHECK(z1 >= coons.col(2).maxCoeff());
  CHECK(z0 <= coons.col(2).minCoeff());
  CHECK(script.find("set zrange", script.find("set zrange") + 1) == std::string::npos);
  REQUIRE(have_gnuplot());  // tests/CMakeLists.txt requires gnuplot for the tests
  const TempDir dir;
  const std::string png = dir.file("dome_nets.png");
  CHECK(plot_nets(png, nets, 25, "dome").empty());
  check_png(png, 920, 500);
  CHECK_FALSE(plot_nets(dir.file("none.png"), {}, 25, "dome").empty());
}

TEST_CASE("plot_surface: a sampled surface with its control net renders to a PNG", "[io][plot]") {
  REQUIRE(have_gnuplot());  // tests/CMakeLists.txt requires gnuplot for the tests
  const Boundary b = read_boundary_file(COONS_DATA_DIR "/boundaries/saddle.json").boundary;
  const ControlNet net = discrete_coons_net(b);
  const TempDir dir;
  const std::string png = dir.file("saddle.png");
  CHECK(plot_surface(png, sample_surface(net, 20, 20), 20, &net, "saddle_surface").empty());
  check_png(png, 800, 640);
  CHECK_FALSE(plot_surface(dir.file("bad.png"), sample_surface(net, 20, 20), 19, &net, "bad").empty());
}

TEST_CASE("plot_curves: an output gnuplot cannot open says so, not that gnuplot is missing", "[io][plot]") {
  REQUIRE(have_gnuplot());
  const TempDir dir;
  const std::string png = dir.file("no_such_folder/plot.png");
  const std::vector<PlotSeries> series = {PlotSeries{"line", {0, 1}, {0, 1}, false}};
  const std::string why = plot_curves(png, series, PlotOptions{});
  INFO(why);
  // gnuplot's log opens with a blank line; its first line was taken as "no message" before
  CHECK_THAT(why, Catch::Contains("cannot open file"));
  CHECK_THAT(why, !Catch::Contains("installed"));
  CHECK_FALSE(std::filesystem::exists(png));
}

TEST_CASE("plot_curves: a name with a line break is refused, and nothing is left in its folder", "[io][plot]") {
  // gnuplot wrote "a b.png.part.png" (the break made a space), which was left behind
  REQUIRE(have_gnuplot());
  const TempDir dir;
  const std::vector<PlotSeries> series = {PlotSeries{"line", {0, 1}, {0, 1}, false}};
  for (const char* name : {"a\nb.png", "a\rb.png"}) {
    const std::string why = plot_curves(dir.file(name), series, PlotOptions{});
    CHECK(why == "gnuplot cannot write a file whose name holds a line break; choose another name");
  }
  CHECK(std::filesystem::is_empty(dir.path));
}

TEST_CASE("run_gnuplot: a gnuplot that never finishes is stopped and named, and leaves no file", "[io][plot]") {
  const TempDir dir;
  const std::string fake = dir.file("gnuplot");
  std::ofstream(fake) << "#!/bin/sh\nexec sleep 600\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const std::string old_path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  ::setenv("PATH", (dir.file("") + ":" + old_path).c_str(), 1);  // the fake is found first
  const std::string png = dir.file("hung.png");
  const std::string why = run_gnuplot("plot x\n", png, 0.5);
  ::setenv("PATH", old_path.c_str(), 1);
  INFO(why);
  CHECK(why == "gnuplot did not finish within 0.5 s and was stopped");
  CHECK_FALSE(std::filesystem::exists(png));
  CHECK_FALSE(std::filesystem::exists(png + ".part.png"));
  CHECK_THAT(run_gnuplot("plot x\n", png, 0), Catch::Contains("bad gnuplot time limit"));
}
