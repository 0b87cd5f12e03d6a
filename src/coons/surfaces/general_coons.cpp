#include "general_coons.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace coons {

BooleanSum to_boolean_sum(const GeneralCoonsData& g) {
  const BoundaryCurves& b = g.boundary;
  const Blend a0 = hermite_blend(0), a1 = hermite_blend(1), b0 = hermite_blend(2), b1 = hermite_blend(3);
  BooleanSum sum;
  sum.u_blended = {{a0, b.left}, {a1, b.right}, {b0, g.du_left}, {b1, g.du_right}};
  sum.v_blended = {{a0, b.bottom}, {a1, b.top}, {b0, g.dv_bottom}, {b1, g.dv_top}};
  sum.tensor_u = sum.tensor_v = {a0, a1, b0, b1};
  const Curve* u_curve[2] = {&b.bottom, &b.top};  // r(·, j)
  const Curve* v_curve[2] = {&b.left, &b.right};  // r(i, ·)
  sum.tensor.assign(4, std::vector<Eigen::RowVector3d>(4));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      sum.tensor[i][j] = -u_curve[j]->at(i);                 // r(i, j)
      sum.tensor[i][2 + j] = -v_curve[i]->derivative(1, j);  // r_v(i, j)
      sum.tensor[2 + i][j] = -u_curve[j]->derivative(1, i);  // r_u(i, j)
      sum.tensor[2 + i][2 + j] = -g.twist[i + 2 * j];        // r_uv(i, j)
    }
  return sum;
}

std::vector<CompatibilityCondition> compatibility_conditions(const GeneralCoonsData& g) {
  const BoundaryCurves& b = g.boundary;
  std::vector<CompatibilityCondition> out = corner_conditions(b);
  auto add = [&](const std::string& field, int corner, const std::string& condition, const Eigen::RowVector3d& x,
                 const Eigen::RowVector3d& y, int order, double uncertainty) {
    // (max-norm bound of a 3-vector: its Euclidean norm is at most √3 times it)
    out.push_back({field, kCornerNames[corner], condition, (x - y).norm(), std::max(x.norm(), y.norm()), order,
                   std::sqrt(3.0) * uncertainty});
  };
  // Cross derivatives against the tangents of the transversal curves.
  const char* u_name[2] = {"bottom", "top"};
  const char* v_name[2] = {"left", "right"};
  const Curve* u_curve[2] = {&b.bottom, &b.top};
  const Curve* v_curve[2] = {&b.left, &b.right};
  const char* du_name[2] = {"du_left", "du_right"};
  const char* dv_name[2] = {"dv_bottom", "dv_top"};
  const Curve* du[2] = {&g.du_left, &g.du_right};
  const Curve* dv[2] = {&g.dv_bottom, &g.dv_top};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      add(du_name[i], i + 2 * j,
          std::string(du_name[i]) + "(" + std::to_string(j) + ") = " + u_name[j] + "'(" + std::to_string(i) + ")",
          du[i]->at(j), u_curve[j]->derivative(1, i), 1, u_curve[j]->derivative_error(1, i));
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i)
      add(dv_name[j], i + 2 * j,
          std::string(dv_name[j]) + "(" + std::to_string(i) + ") = " + v_name[i] + "'(" + std::to_string(j) + ")",
          dv[j]->at(i), v_curve[i]->derivative(1, j), 1, v_curve[i]->derivative_error(1, j));
  // Twists against the derivatives of the cross derivatives.
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int c = i + 2 * j;
      const std::string field = "twist[" + std::to_string(c) + "]";
      add(field, c, field + " = " + du_name[i] + "'(" + std::to_string(j) + ")", g.twist[c], du[i]->derivative(1, j), 2,
          du[i]->derivative_error(1, j));
      add(field, c, field + " = " + dv_name[j] + "'(" + std::to_string(i) + ")", g.twist[c], dv[j]->derivative(1, i), 2,
          dv[j]->derivative_error(1, i));
    }
  return out;
}

}  // namespace coons
