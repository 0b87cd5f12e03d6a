#include "coons/io/bspline_boundary_io.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "coons/curves/bspline_curve.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"

namespace coons {

namespace {

constexpr double kMinKnotRange = 1e-290;  // well above the subnormal doubles (below 2.2e-308)

Eigen::VectorXd parse_knot_vector(const nlohmann::json& j, const std::string& source, const std::string& field,
                                  int degree, int count) {
  if (!j.is_array()) throw InputError(source, field, "must be an array of numbers (a clamped knot vector)");
  Eigen::VectorXd knots(Eigen::Index(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i)
    knots(Eigen::Index(i)) = json_coordinate(j[i], source, fmt::format("{}[{}]", field, i), "the knot");
  const std::vector<KnotProblem> problems = knot_vector_problems(knots, degree, count);
  if (!problems.empty()) {
    const KnotProblem& first = problems.front();
    throw InputError(source, first.index < 0 ? field : fmt::format("{}[{}]", field, first.index), first.reason);
  }
  // The net does not depend on the knots' scale, but a range of subnormal doubles (knots times
  // 1e-309) left the Greville spacings without precision: the solve overflowed (exit 3).
  // (the rules above hold, so the vector has at least 2(degree + 1) knots)
  if (const double range = knots(knots.size() - 1) - knots(0); range < kMinKnotRange)
    throw InputError(source, field,
                     fmt::format("the knots span {:.3g}, less than {:g}: rescale them (the net does not depend on "
                                 "their scale)",
                                 range, kMinKnotRange));
  return knots;
}

// knots_u / knots_v: one vector for both sides, or {"bottom": […], "top": […]} (u) and
// {"left": […], "right": […]} (v); `second` receives the second side's vector in that form.
Eigen::VectorXd parse_direction(const nlohmann::json& doc, const std::string& source, const std::string& field,
                                int degree, int count, const char* first_side, const char* second_side,
                                Eigen::VectorXd& second) {
  const nlohmann::json& j = doc.at(field);
  if (!j.is_object()) return parse_knot_vector(j, source, field, degree, count);
  for (const auto& [key, value] : j.items())
    if (key != first_side && key != second_side)
      throw InputError(
          source, fmt::format("{}.{}", field, key),
          fmt::format("unknown side (per-side knots of {} are \"{}\" and \"{}\")", field, first_side, second_side));
  for (const char* side : {first_side, second_side})
    if (!j.contains(side))
      throw InputError(source, fmt::format("{}.{}", field, side),
                       fmt::format("missing: per-side knots need both \"{}\" and \"{}\"", first_side, second_side));
  Eigen::VectorXd first =
      parse_knot_vector(j.at(first_side), source, fmt::format("{}.{}", field, first_side), degree, count);
  second = parse_knot_vector(j.at(second_side), source, fmt::format("{}.{}", field, second_side), degree, count);
  return first;
}

}  // namespace

std::optional<BSplineKnots> parse_bspline_knots(const nlohmann::json& doc, const std::string& source, int count_u,
                                                int count_v) {
  if (!doc.is_object()) return std::nullopt;
  const bool has_degree = doc.contains("degree_spline");
  const bool has_u = doc.contains("knots_u");
  const bool has_v = doc.contains("knots_v");
  if (!has_degree && !has_u && !has_v) return std::nullopt;
  for (const auto& [field, present] :
       {std::pair{"degree_spline", has_degree}, std::pair{"knots_u", has_u}, std::pair{"knots_v", has_v}})
    if (!present)
      throw InputError(source, field, "missing: a B-spline boundary needs all of degree_spline, knots_u and knots_v");
  const nlohmann::json& degrees = doc.at("degree_spline");
  if (!degrees.is_array() || degrees.size() != 2)
    throw InputError(source, "degree_spline", "must be [p, q], two integers (the degrees in u and v)");
  BSplineKnots out;
  out.degree_u = int(json_integer(degrees[0], source, "degree_spline[0]", 1, 64));
  out.degree_v = int(json_integer(degrees[1], source, "degree_spline[1]", 1, 64));
  out.knots_u = parse_direction(doc, source, "knots_u", out.degree_u, count_u, "bottom", "top", out.knots_top);
  out.knots_v = parse_direction(doc, source, "knots_v", out.degree_v, count_v, "left", "right", out.knots_right);
  return out;
}

BSplineBoundary bspline_boundary(const Boundary& b, const BSplineKnots& k) {
  const Eigen::VectorXd& top = k.knots_top.size() > 0 ? k.knots_top : k.knots_u;
  const Eigen::VectorXd& right = k.knots_right.size() > 0 ? k.knots_right : k.knots_v;
  return {BSplineCurve(k.degree_u, k.knots_u, b.bottom), BSplineCurve(k.degree_u, top, b.top),
          BSplineCurve(k.degree_v, k.knots_v, b.left), BSplineCurve(k.degree_v, right, b.right)};
}

BSplineInput bspline_input(const Boundary& b, const BSplineKnots& k, const std::string& source) {
  BSplineInput out;
  out.given = bspline_boundary(b, k);
  out.compatible = compatible_boundary(out.given, &out.notes);
  for (const int direction : {0, 1})
    if (const auto why = merged_span_problem(out.compatible, direction))
      throw InputError(source, direction == 0 ? "knots_u" : "knots_v", *why);
  return out;
}

}  // namespace coons
