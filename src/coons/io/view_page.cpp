#include "view_page.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace coons {

namespace {

// Inside <script>, "</" could end the element early (and "<!--" change how it is parsed). In JSON
// '<' occurs only inside strings, where "\u003c" means the same.
std::string json_script_safe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

// The same for a script: "</" as "<\/" (the same inside strings and regular expressions).
std::string script_safe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

void append_number(std::string& out, double x, bool round_trip) {
  if (!std::isfinite(x)) {
    out += round_trip ? "null" : "0";
    return;
  }
  out += round_trip ? fmt::format("{}", x) : fmt::format("{:.5g}", x);
}

// A #rows by 3 matrix as one flat array [x0,y0,z0,x1,...], each row minus `origin` (the page's
// origin for points, zero for normals): 5 significant digits of the coordinates themselves lost
// a patch of size 1 at 1e8 entirely (every sample 100000000.0), those of the offsets keep it.
// `round_trip`: in shortest round-trip form instead, for what the page solves with.
void append_flat(std::string& out, const Eigen::MatrixX3d& M, const Eigen::RowVector3d& origin,
                 bool round_trip = false) {
  out += '[';
  for (Eigen::Index r = 0; r < M.rows(); ++r)
    for (int c = 0; c < 3; ++c) {
      if (r > 0 || c > 0) out += ',';
      append_number(out, M(r, c) - origin(c), round_trip);
    }
  out += ']';
}

template <size_t N>
void append_indices(std::string& out, const std::vector<std::array<int, N>>& list) {
  out += '[';
  for (size_t k = 0; k < list.size(); ++k)
    for (size_t c = 0; c < N; ++c) {
      if (k > 0 || c > 0) out += ',';
      out += std::to_string(list[k][c]);
    }
  out += ']';
}

// Numbers in shortest round-trip form: the page solves with them.
void append_exact(std::string& out, const double* values, Eigen::Index count) {
  out += '[';
  for (Eigen::Index k = 0; k < count; ++k) {
    if (k > 0) out += ',';
    append_number(out, values[k], true);
  }
  out += ']';
}

// A sparse matrix as one flat array of (row, column, value) triples.
void append_triples(std::string& out, const Eigen::SparseMatrix<double>& A) {
  out += '[';
  bool first = true;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      if (!first) out += ',';
      first = false;
      out += fmt::format("{},{},", it.row(), it.col());
      append_number(out, it.value(), true);
    }
  out += ']';
}

// The system of ViewSystem. The page's coordinates are offsets from `origin`: the right-hand side
// stays in the net's own (the page moves it: A (x − o) = B − (A·1) o), the net is moved here.
void append_system(std::string& out, const ViewSystem& v, const Eigen::RowVector3d& origin) {
  static constexpr const char* kSamplers[] = {"bezier", "triangle", "tensor"};
  out += fmt::format(",\"system\":{{\"sampler\":\"{}\",\"m\":{},\"n\":{},\"samples\":{},\"free\":[",
                     kSamplers[int(v.sampler)], v.m, v.n, v.samples);
  for (size_t k = 0; k < v.free.size(); ++k) out += (k > 0 ? "," : "") + std::to_string(v.free[k]);
  out += "],\"A0\":";
  append_triples(out, v.A0);
  out += ",\"A1\":";
  append_triples(out, v.A1);
  out += ",\"B0\":";
  append_flat(out, v.B0, Eigen::RowVector3d::Zero(), true);
  out += ",\"B1\":";
  append_flat(out, v.B1, Eigen::RowVector3d::Zero(), true);
  out += ",\"net\":";
  append_flat(out, v.net, origin, true);
  if (v.sampler == ViewSystem::Sampler::kTensor) {
    const auto basis = [&out](const char* name, const Eigen::MatrixXd& B) {
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rows = B;
      out += fmt::format(",\"{}\":", name);
      append_exact(out, rows.data(), rows.size());
    };
    basis("basis_u", v.basis_u);
    basis("dbasis_u", v.dbasis_u);
    basis("basis_v", v.basis_v);
    basis("dbasis_v", v.dbasis_v);
    out += fmt::format(",\"count_u\":{},\"count_v\":{}", v.basis_u.cols(), v.basis_v.cols());
  }
  out += '}';
}

void append_slider(std::string& out, const ViewSlider& s, const Eigen::RowVector3d& origin) {
  nlohmann::json head = {{"parameter", s.parameter},
                         {"symbol", s.symbol},
                         {"label", s.label},
                         {"lower", s.lower},
                         {"upper", s.upper},
                         {"initial", s.initial},
                         {"marks", nlohmann::json::array()},
                         {"curves", nlohmann::json::array()}};
  for (const ViewMark& m : s.marks) head["marks"].push_back({{"name", m.name}, {"parameter", m.parameter}});
  for (const ViewCurve& c : s.curves) {
    nlohmann::json values = nlohmann::json::array();
    for (double v : c.values) values.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
    head["curves"].push_back({{"name", c.name},
                              {"values", values},
                              {"optimum", c.optimum ? nlohmann::json(*c.optimum) : nlohmann::json()},
                              {"status", c.status}});
  }
  std::string text = head.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  text.pop_back();  // the closing brace: the big arrays follow
  out += text;
  out += ",\"edges\":";
  append_indices(out, s.net_edges);
  out += ",\"faces\":";
  append_indices(out, s.faces);
  if (s.ring_m >= 2 && s.ring_n >= 2) {
    out += ",\"ring\":{\"m\":" + std::to_string(s.ring_m) + ",\"n\":" + std::to_string(s.ring_n) + ",\"net\":";
    append_flat(out, s.ring, origin, true);  // the family reproduces translations
    out += '}';
  }
  if (s.system) append_system(out, *s.system, origin);
  out += ",\"frames\":[";
  for (size_t k = 0; k < s.frames.size(); ++k) {
    const ViewFrame& f = s.frames[k];
    if (k > 0) out += ',';
    out += "{\"parameter\":";
    append_number(out, f.parameter, true);
    if (f.mu && std::isfinite(*f.mu)) {
      out += ",\"mu\":";
      append_number(out, *f.mu, true);
    }
    out += f.ok ? ",\"ok\":true,\"net\":" : ",\"ok\":false,\"net\":";
    append_flat(out, f.net, origin);
    out += ",\"points\":";
    append_flat(out, f.points, origin);
    out += ",\"normals\":";
    append_flat(out, f.normals, Eigen::RowVector3d::Zero());
    out += '}';
  }
  out += "]}";
}

std::string escape_html(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

}  // namespace

namespace {

bool system_is_valid(const ViewSystem& v, const ViewFrame& frame, std::string* why) {
  const Eigen::Index k = Eigen::Index(v.free.size()), points = frame.net.rows();
  const auto fail = [why](const char* reason) {
    *why = reason;
    return false;
  };
  if (k == 0 || k > ViewSystem::kMaxFree) return fail("the number of free points must be in [1, kMaxFree]");
  for (int f : v.free)
    if (f < 0 || f >= points) return fail("a free point outside the net");
  if (v.A0.rows() != k || v.A0.cols() != k || v.A1.rows() != k || v.A1.cols() != k || v.B0.rows() != k ||
      v.B1.rows() != k || v.net.rows() != points)
    return fail("A0, A1 must be #free square, B0, B1 #free by 3, net the frames' size");
  if (!v.net.allFinite() || !v.B0.allFinite() || !v.B1.allFinite()) return fail("not finite");
  if (v.samples < 2) return fail("samples must be >= 2");
  const Eigen::Index grid = Eigen::Index(v.samples) * v.samples;
  switch (v.sampler) {
    case ViewSystem::Sampler::kBezier:
      if (Eigen::Index(v.m + 1) * (v.n + 1) != points || frame.points.rows() != grid)
        return fail("a Bézier net and grid of the frames' sizes");
      break;
    case ViewSystem::Sampler::kTriangle:
      if (Eigen::Index(v.n + 1) * (v.n + 2) / 2 != points ||
          frame.points.rows() != Eigen::Index(v.samples) * (v.samples + 1) / 2)
        return fail("a triangular net and samples of the frames' sizes");
      break;
    case ViewSystem::Sampler::kTensor:
      if (v.basis_u.rows() != v.samples || v.basis_v.rows() != v.samples || v.dbasis_u.rows() != v.samples ||
          v.dbasis_v.rows() != v.samples || v.dbasis_u.cols() != v.basis_u.cols() ||
          v.dbasis_v.cols() != v.basis_v.cols() || v.basis_u.cols() * v.basis_v.cols() != points ||
          frame.points.rows() != grid)
        return fail("basis matrices of the samples by the net's sizes");
      break;
  }
  return true;
}

}  // namespace

bool ViewPage::is_valid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (sliders.empty()) return fail("no slider");
  for (const ViewSlider& s : sliders) {
    if (s.parameter.empty()) return fail("a slider without a parameter name");
    if (s.frames.empty()) return fail(s.parameter + ": no frames");
    if (!(s.lower < s.upper)) return fail(s.parameter + ": lower must be below upper");
    const ViewFrame& first = s.frames.front();
    for (size_t k = 0; k < s.frames.size(); ++k) {
      const ViewFrame& f = s.frames[k];
      if (f.net.rows() != first.net.rows() || f.points.rows() != first.points.rows() ||
          f.normals.rows() != f.points.rows())
        return fail(fmt::format("{}: frame {} has other sizes than frame 0", s.parameter, k));
      if (k > 0 && !(f.parameter > s.frames[k - 1].parameter))
        return fail(fmt::format("{}: frame {} does not increase the parameter", s.parameter, k));
    }
    for (const auto& e : s.net_edges)
      for (int i : e)
        if (i < 0 || i >= first.net.rows()) return fail(s.parameter + ": a net edge outside the net");
    for (const auto& t : s.faces)
      for (int i : t)
        if (i < 0 || i >= first.points.rows()) return fail(s.parameter + ": a face outside the samples");
    for (const ViewCurve& c : s.curves)
      if (c.values.size() != s.frames.size())
        return fail(s.parameter + ": curve " + c.name + " needs a value per frame");
    if (s.system) {
      std::string reason;
      if (!system_is_valid(*s.system, first, &reason)) return fail(s.parameter + ": system: " + reason);
    }
    if (s.ring_m != 0 || s.ring_n != 0) {
      const Eigen::Index points = Eigen::Index(s.ring_m + 1) * (s.ring_n + 1);
      if (s.ring_m < 2 || s.ring_n < 2 || s.ring.rows() != points || first.net.rows() != points || !s.ring.allFinite())
        return fail(s.parameter + ": the ring must be a finite net of degree >= (2, 2), the frames' size");
    }
  }
  return true;
}

std::vector<std::array<int, 2>> grid_edges(int rows, int cols) {
  std::vector<std::array<int, 2>> edges;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if (c + 1 < cols) edges.push_back({r * cols + c, r * cols + c + 1});
      if (r + 1 < rows) edges.push_back({r * cols + c, (r + 1) * cols + c});
    }
  return edges;
}

std::vector<std::array<int, 3>> grid_faces(int k) {
  std::vector<std::array<int, 3>> faces;
  for (int a = 0; a + 1 < k; ++a)
    for (int b = 0; b + 1 < k; ++b) {
      const int p = a * k + b;
      faces.push_back({p, p + k, p + k + 1});
      faces.push_back({p, p + k + 1, p + 1});
    }
  return faces;
}

// The centre of the box of every net point of every frame (finite ones): the page's coordinates
// are offsets from it.
Eigen::RowVector3d page_origin(const ViewPage& page) {
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(HUGE_VAL), hi = Eigen::RowVector3d::Constant(-HUGE_VAL);
  for (const ViewSlider& s : page.sliders)
    for (const ViewFrame& f : s.frames)
      for (Eigen::Index r = 0; r < f.net.rows(); ++r)
        if (f.net.row(r).allFinite()) {
          lo = lo.cwiseMin(f.net.row(r));
          hi = hi.cwiseMax(f.net.row(r));
        }
  if (!(lo.array() <= hi.array()).all()) return Eigen::RowVector3d::Zero();
  return lo + 0.5 * (hi - lo);
}

std::string view_page_json(const ViewPage& page) {
  const Eigen::RowVector3d origin = page_origin(page);
  std::string out = "{\"title\":";
  out += nlohmann::json(page.title).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  out += ",\"subtitle\":";
  out += nlohmann::json(page.subtitle).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  out += ",\"generator\":";
  out += nlohmann::json(page.generator).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  out += ",\"origin\":[";
  for (int c = 0; c < 3; ++c) {
    if (c > 0) out += ',';
    append_number(out, origin(c), true);
  }
  out += "],\"sliders\":[";
  for (size_t k = 0; k < page.sliders.size(); ++k) {
    if (k > 0) out += ',';
    append_slider(out, page.sliders[k], origin);
  }
  out += "]}";
  return json_script_safe(out);
}

std::string view_page_html(const ViewPage& page, std::string_view three_js) {
  std::string out;
  out.reserve(three_js.size() + 1024 * 1024);
  out += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"generator\" content=\"" + escape_html(page.generator) + "\">\n";
  out += "<title>" + escape_html(page.title) + " — coons view</title>\n<style>\n";
  out += view_page_style();
  // Errors are recorded before anything else runs, so that a failure of three.js itself is seen.
  out +=
      "</style>\n<script>window.addEventListener('error',function(e){document.documentElement."
      "setAttribute('data-error',String(e.message||e));if(document.body)document.body.setAttribute('data-error',"
      "String(e.message||e));});</script>\n";
  out += "<script>\n";
  out += script_safe(std::string(three_js));
  out += "\n</script>\n</head>\n<body>\n<header><h1>" + escape_html(page.title) + "</h1><p>" +
         escape_html(page.subtitle) + "</p></header>\n";
  out +=
      "<main><div id=\"view3d\"><canvas id=\"surface\"></canvas><div class=\"hint\">drag to turn, wheel to "
      "zoom</div></div>\n<div id=\"side\"><div id=\"controls\"></div><svg id=\"curves\" "
      "viewBox=\"0 0 520 320\"></svg><div id=\"legend\"></div></div></main>\n";
  out += "<footer>" + escape_html(page.generator) +
         ": the surface shaded with reflection lines of parallel light lines; the control net in blue. "
         "Nets precomputed for every slider value (nearest one shown).</footer>\n";
  out += "<script type=\"application/json\" id=\"coons-data\">";
  out += view_page_json(page);
  out += "</script>\n<script>\n";
  out += view_page_script();
  out += "\n</script>\n</body>\n</html>\n";
  return out;
}

}  // namespace coons
