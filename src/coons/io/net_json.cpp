#include "net_json.h"

#include <fmt/compile.h>
#include <fmt/format.h>

#include <cmath>
#include <iterator>
#include <string>

namespace coons {

using nlohmann::json;

json number_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json optional_number(const std::optional<double>& x) { return x ? number_or_null(*x) : json(nullptr); }

namespace {
json point_json(const Eigen::RowVector3d& p) { return json::array({p(0), p(1), p(2)}); }
json points_json(const Eigen::MatrixX3d& P) {
  json out = json::array();
  for (Eigen::Index k = 0; k < P.rows(); ++k) out.push_back(point_json(P.row(k)));
  return out;
}
}  // namespace

json net_to_json(const ControlNet& net) {
  json rows = json::array();
  for (int i = 0; i <= net.m; ++i) {
    json row = json::array();
    for (int j = 0; j <= net.n; ++j) row.push_back(point_json(net.at(i, j)));
    rows.push_back(std::move(row));
  }
  return rows;
}

namespace {
// x as nlohmann's dump would print it, up to the choice among round-trip digit strings: the
// shortest (fmt), with ".0" added when that reads as an integer.
void append_number(fmt::memory_buffer& out, double x) {
  if (!std::isfinite(x)) {
    out.append(std::string_view("null"));
    return;
  }
  const std::size_t start = out.size();
  fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}"), x);
  const std::string_view digits(out.data() + start, out.size() - start);
  if (digits.find_first_of(".e") == std::string_view::npos) out.append(std::string_view(".0"));
}
}  // namespace

void write_net_json(const ControlNet& net, int level, const std::function<void(std::string_view)>& sink) {
  constexpr std::size_t kPiece = std::size_t(1) << 20;
  fmt::memory_buffer out;
  out.reserve(kPiece + 4096);
  const std::string outer(2 * std::size_t(level), ' '), row_indent = outer + "  ", point_indent = row_indent + "  ";
  auto put = [&out](std::string_view s) { out.append(s); };
  put("[\n");
  for (int i = 0; i <= net.m; ++i) {
    put(row_indent);
    put("[\n");
    for (int j = 0; j <= net.n; ++j) {
      const auto p = net.at(i, j);
      put(point_indent);
      put("[");
      append_number(out, p(0));
      put(", ");
      append_number(out, p(1));
      put(", ");
      append_number(out, p(2));
      put(j < net.n ? "],\n" : "]\n");
      if (out.size() >= kPiece) {
        sink(std::string_view(out.data(), out.size()));
        out.clear();
      }
    }
    put(row_indent);
    put(i < net.m ? "],\n" : "]\n");
  }
  put(outer);
  put("]");
  sink(std::string_view(out.data(), out.size()));
}

json boundary_to_json(const Boundary& b) {
  json out;
  if (!b.name.empty()) out["name"] = b.name;
  out["degree"] = {b.m, b.n};
  out["bottom"] = points_json(b.bottom);
  out["top"] = points_json(b.top);
  out["left"] = points_json(b.left);
  out["right"] = points_json(b.right);
  return out;
}

json metrics_to_json(const NetMetrics& m) {
  return {{"twist_energy", number_or_null(m.twist_energy)},
          {"thin_plate_energy", number_or_null(m.thin_plate_energy)},
          {"dirichlet_energy", number_or_null(m.dirichlet_energy)},
          {"e3_energy", number_or_null(m.e3_energy)},
          {"discrete_twist_energy", number_or_null(m.discrete_twist_energy)},
          {"discrete_dirichlet_energy", number_or_null(m.discrete_dirichlet_energy)},
          {"mask_residual", number_or_null(m.mask_residual)}};
}

json summary_to_json(const solvers::SolveSummary& s) {
  json out = {
      {"name", s.solver},
      {"status", solvers::to_string(s.status)},
      {"iterations", s.iterations},
      {"relative_residual", number_or_null(s.relative_residual)},
      {"seconds", {{"analyze", s.analyze_seconds}, {"factorize", s.factorize_seconds}, {"solve", s.solve_seconds}}}};
  if (!s.message.empty()) out["message"] = s.message;
  if (!s.ordering.empty()) out["ordering"] = s.ordering;
  if (s.factor_nnz > 0) out["factor_nnz"] = s.factor_nnz;
  if (s.condition_estimate > 0) {
    out["condition_estimate"] = number_or_null(s.condition_estimate);
    out["normwise_backward_error"] = number_or_null(s.normwise_backward_error);
    out["forward_error_bound"] = number_or_null(s.forward_error_bound());
  }
  return out;
}

}  // namespace coons
