// The page of `coons view` (coons/io/view_page.h): its data, its checks and its HTML.
#include "coons/io/view_page.h"

#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

using namespace coons;

namespace {

// One slider of two frames over a 2 × 2 net and a 2 × 2 sample grid.
ViewPage small_page() {
  ViewPage page;
  page.title = "a </script><!-- title";
  page.generator = "coons test";
  ViewSlider s;
  s.parameter = "alpha";
  s.symbol = "α";
  s.label = "α (the family)";
  s.lower = -0.25;
  s.upper = 0.25;
  s.net_edges = grid_edges(2, 2);
  s.faces = grid_faces(2);
  for (double a : {-0.25, 0.0}) {
    ViewFrame f;
    f.parameter = a;
    f.net = Eigen::MatrixX3d::Random(4, 3);
    f.points = Eigen::MatrixX3d::Random(4, 3);
    f.normals = Eigen::MatrixX3d::Random(4, 3);
    f.normals(0, 0) = NAN;
    if (a < 0) f.mu = 3.0;
    s.frames.push_back(f);
  }
  s.curves.push_back({"thin_plate", {2.0, NAN}, -0.1, "success"});
  s.marks.push_back({"Coons", -0.25});
  page.sliders.push_back(s);
  return page;
}

}  // namespace

TEST_CASE("grid_edges: every neighbour pair of a rows x cols grid once", "[io][view]") {
  const auto edges = grid_edges(3, 4);
  CHECK(edges.size() == size_t(3 * 3 + 4 * 2));
  std::set<std::pair<int, int>> seen;
  for (const auto& e : edges) {
    const int a = std::min(e[0], e[1]), b = std::max(e[0], e[1]);
    CHECK((b - a == 1 || b - a == 4));
    if (b - a == 1) CHECK(a % 4 != 3);  // never from the end of a row to the next row
    seen.insert({a, b});
  }
  CHECK(seen.size() == edges.size());
}

TEST_CASE("grid_faces: two triangles per cell covering the grid", "[io][view]") {
  const auto faces = grid_faces(4);
  CHECK(faces.size() == size_t(2 * 3 * 3));
  std::set<int> used;
  for (const auto& t : faces) used.insert(t.begin(), t.end());
  CHECK(used.size() == 16);
}

TEST_CASE("ViewPage::is_valid: sizes, ranges and increasing frames are checked", "[io][view]") {
  std::string why;
  CHECK(small_page().is_valid(&why));
  ViewPage p = small_page();
  p.sliders[0].faces.push_back({0, 1, 4});
  CHECK_FALSE(p.is_valid(&why));
  CHECK(why.find("face") != std::string::npos);
  p = small_page();
  p.sliders[0].frames[1].parameter = -0.3;
  CHECK_FALSE(p.is_valid(&why));
  p = small_page();
  p.sliders[0].curves[0].values.pop_back();
  CHECK_FALSE(p.is_valid(&why));
  p = small_page();
  p.sliders[0].frames[1].net = Eigen::MatrixX3d::Zero(5, 3);
  CHECK_FALSE(p.is_valid(&why));
  CHECK_FALSE(ViewPage{}.is_valid(&why));
}

TEST_CASE("view_page_json: valid JSON that reads back, with no '<' to end its script element", "[io][view]") {
  const ViewPage page = small_page();
  const std::string text = view_page_json(page);
  CHECK(text.find('<') == std::string::npos);
  const nlohmann::json doc = nlohmann::json::parse(text);
  CHECK(doc["title"] == page.title);
  const auto& s = doc["sliders"][0];
  CHECK(s["parameter"] == "alpha");
  CHECK(s["symbol"] == "α");
  CHECK(s["frames"].size() == 2);
  CHECK(s["frames"][1]["parameter"].get<double>() == 0.0);
  CHECK(s["frames"][0]["mu"].get<double>() == 3.0);
  CHECK_FALSE(s["frames"][1].contains("mu"));
  CHECK(s["frames"][0]["net"].size() == 12);
  // coordinates are offsets from the page's origin, the centre of the nets' box (exactly, in
  // shortest round-trip form), written with 5 significant digits: exactly the value of that text
  // (a relative 1e-5 failed for 0.1783133695, written 0.17831, when Random() gave that value)
  Eigen::RowVector3d lo = page.sliders[0].frames[0].net.colwise().minCoeff(),
                     hi = page.sliders[0].frames[0].net.colwise().maxCoeff();
  for (const ViewFrame& f : page.sliders[0].frames) {
    lo = lo.cwiseMin(f.net.colwise().minCoeff());
    hi = hi.cwiseMax(f.net.colwise().maxCoeff());
  }
  const Eigen::RowVector3d origin = lo + 0.5 * (hi - lo);
  for (int c = 0; c < 3; ++c) CHECK(doc["origin"][c].get<double>() == origin(c));
  const double written = std::stod(fmt::format("{:.5g}", page.sliders[0].frames[0].net(1, 1) - origin(1)));
  CHECK(s["frames"][0]["net"][4].get<double>() == written);
  CHECK(s["frames"][0]["normals"][0].get<double>() == 0.0);  // the NaN normal
  CHECK(s["edges"].size() == 2 * page.sliders[0].net_edges.size());
  CHECK(s["faces"].size() == 3 * page.sliders[0].faces.size());
  CHECK(s["curves"][0]["values"][1].is_null());
  CHECK(s["curves"][0]["optimum"].get<double>() == -0.1);
  CHECK(s["marks"][0]["name"] == "Coons");
}

TEST_CASE("view_page_json: a patch far from the origin keeps its shape, written as offsets from its centre",
          "[io][view]") {
  // A patch of size 1 at 1e8: with 5 significant digits of the coordinates every point was
  // 100000000.0 (one point drawn, the slider without effect); as offsets they keep 5 digits of the
  // patch's own size.
  ViewPage page = small_page();
  for (ViewFrame& f : page.sliders[0].frames) {
    f.net.rowwise() += Eigen::RowVector3d(1e8, -1e8, 1e8);
    f.points.rowwise() += Eigen::RowVector3d(1e8, -1e8, 1e8);
  }
  const nlohmann::json doc = nlohmann::json::parse(view_page_json(page));
  const Eigen::RowVector3d origin(doc["origin"][0].get<double>(), doc["origin"][1].get<double>(),
                                  doc["origin"][2].get<double>());
  const ViewFrame& f = page.sliders[0].frames[0];
  const double size = (f.net.colwise().maxCoeff() - f.net.colwise().minCoeff()).maxCoeff();
  REQUIRE(size > 0.1);
  double worst = 0;
  for (Eigen::Index r = 0; r < f.net.rows(); ++r)
    for (int c = 0; c < 3; ++c) {
      const double read = doc["sliders"][0]["frames"][0]["net"][3 * r + c].get<double>() + origin(c);
      worst = std::max(worst, std::abs(read - f.net(r, c)));
    }
  CHECK(worst <= 1e-4 * size);  // 5 significant digits of offsets no larger than the size
  const double normal = doc["sliders"][0]["frames"][0]["normals"][3].get<double>();
  CHECK(std::abs(normal - f.normals(1, 0)) <= 1e-5);  // normals are not moved
}

TEST_CASE("view_page_html: three.js, the data and the page's script inlined, nothing fetched", "[io][view]") {
  const std::string html = view_page_html(small_page(), "/* three */ var REVISION=\"111\";");
  CHECK(html.find("var REVISION=\"111\"") != std::string::npos);
  CHECK(html.find("id=\"coons-data\"") != std::string::npos);
  CHECK(html.find("window.coonsView") != std::string::npos);
  CHECK(html.find("data-ready") != std::string::npos);
  CHECK(html.find("a &lt;/script&gt;&lt;!-- title") != std::string::npos);
  for (const char* remote : {"src=\"http", "src=\"//", "href=\"http", "import("})
    CHECK(html.find(remote) == std::string::npos);
  // one closing tag per script element: the three scripts and the data
  size_t closing = 0;
  for (size_t at = html.find("</script"); at != std::string::npos; at = html.find("</script", at + 1)) ++closing;
  size_t opening = 0;
  for (size_t at = html.find("<script"); at != std::string::npos; at = html.find("<script", at + 1)) ++opening;
  CHECK(opening == 4);
  CHECK(closing == opening);
}
