#include "hermite_patch.h"

namespace coons {

HermitePatch ferguson_patch(const std::array<Eigen::RowVector3d, 4>& corners,
                            const std::array<Eigen::RowVector3d, 4>& du, const std::array<Eigen::RowVector3d, 4>& dv) {
  HermitePatch h{corners, du, dv, {}};
  for (auto& t : h.twist) t.setZero();
  return h;
}

BooleanSum to_boolean_sum(const HermitePatch& h) {
  BooleanSum sum;
  sum.tensor_u = sum.tensor_v = {hermite_blend(0), hermite_blend(1), hermite_blend(2), hermite_blend(3)};
  sum.tensor.assign(4, std::vector<Eigen::RowVector3d>(4));
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const int c = i + 2 * j;
      sum.tensor[i][j] = h.corners[c];
      sum.tensor[i][2 + j] = h.dv[c];
      sum.tensor[2 + i][j] = h.du[c];
      sum.tensor[2 + i][2 + j] = h.twist[c];
    }
  return sum;
}

}  // namespace coons
