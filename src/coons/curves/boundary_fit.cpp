#include "boundary_fit.h"

#include <algorithm>

#include "coons/curves/bezier_fit.h"

namespace coons {

FittedBoundary fit_boundary(const std::vector<Curve>& sides, int m, int n, const std::string& name) {
  FittedBoundary out;
  Boundary& b = out.boundary;
  b.name = name;
  b.m = m;
  b.n = n;
  Eigen::MatrixX3d* targets[] = {&b.bottom, &b.top, &b.left, &b.right};
  for (int k = 0; k < 4; ++k) {
    const BezierFit fit = fit_bezier(sides[k], k < 2 ? m : n);
    *targets[k] = fit.curve.points;
    if (!(fit.max_deviation <= out.max_deviation)) out.max_deviation = fit.max_deviation;  // NaN too
  }
  out.corner_gap = largest_corner_gap(b);
  const double size = std::max(bounding_box_diagonal(b), 1e-300);
  out.corners_meet = out.corner_gap.gap <= 1e-9 * size;
  if (!out.corners_meet) return out;
  // make the shared corners bit-identical (bottom and top are canonical)
  b.left.row(0) = b.bottom.row(0);
  b.right.row(0) = b.bottom.row(m);
  b.left.row(n) = b.top.row(0);
  b.right.row(n) = b.top.row(m);
  return out;
}

}  // namespace coons
