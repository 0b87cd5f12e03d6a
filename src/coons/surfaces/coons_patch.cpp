#include "coons_patch.h"

#include <algorithm>

namespace coons {

const std::array<const char*, 4> kCornerNames = {"bottom-left (u = 0, v = 0)", "bottom-right (u = 1, v = 0)",
                                                 "top-left (u = 0, v = 1)", "top-right (u = 1, v = 1)"};

BooleanSum to_boolean_sum(const BoundaryCurves& b, CoonsBlending blending) {
  auto F = [blending](int i) { return blending == CoonsBlending::kLinear ? linear_blend(i) : hermite_blend(i); };
  BooleanSum sum;
  sum.u_blended = {{F(0), b.left}, {F(1), b.right}};
  sum.v_blended = {{F(0), b.bottom}, {F(1), b.top}};
  sum.tensor_u = sum.tensor_v = {F(0), F(1)};
  const Eigen::RowVector3d r[2][2] = {{b.bottom.at(0), b.top.at(0)}, {b.bottom.at(1), b.top.at(1)}};  // r[i][j]
  sum.tensor.assign(2, std::vector<Eigen::RowVector3d>(2));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) sum.tensor[i][j] = -r[i][j];
  return sum;
}

std::vector<CompatibilityCondition> corner_conditions(const BoundaryCurves& b) {
  std::vector<CompatibilityCondition> out;
  auto add = [&](const char* field, int corner, const char* condition, const Eigen::RowVector3d& x,
                 const Eigen::RowVector3d& y) {
    out.push_back({field, kCornerNames[corner], condition, (x - y).norm(), std::max(x.norm(), y.norm()), 0});
  };
  add("left", 0, "left(0) = bottom(0)", b.left.at(0), b.bottom.at(0));
  add("right", 1, "right(0) = bottom(1)", b.right.at(0), b.bottom.at(1));
  add("left", 2, "left(1) = top(0)", b.left.at(1), b.top.at(0));
  add("right", 3, "right(1) = top(1)", b.right.at(1), b.top.at(1));
  return out;
}

double boundary_size(const BoundaryCurves& b) {
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(1e300), hi = -lo;
  for (const Curve* c : {&b.bottom, &b.top, &b.left, &b.right})
    for (int k = 0; k <= 32; ++k) {
      const Eigen::RowVector3d p = c->at(k / 32.0);
      if (!p.allFinite()) continue;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return (hi.array() >= lo.array()).all() ? (hi - lo).norm() : 0.0;
}

}  // namespace coons
