#include "ruled_surface.h"

namespace coons {

RuledSurface sectorial_surface(Curve c, const Eigen::RowVector3d& apex) {
  return RuledSurface{std::move(c), Curve::constant(apex)};
}

BooleanSum to_boolean_sum(const RuledSurface& s) {
  BooleanSum sum;
  sum.v_blended.push_back({linear_blend(0), s.c0});
  sum.v_blended.push_back({linear_blend(1), s.c1});
  return sum;
}

BooleanSum to_boolean_sum(const BilinearSurface& s) {
  BooleanSum sum;
  sum.tensor_u = sum.tensor_v = {linear_blend(0), linear_blend(1)};
  sum.tensor.assign(2, std::vector<Eigen::RowVector3d>(2));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) sum.tensor[i][j] = s.corners[i + 2 * j];
  return sum;
}

}  // namespace coons
