#include "sampling.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace coons {

SurfaceSamples sample_grid(const Surface& s, int k) {
  return sample_grid([&s](double u, double v) { return s.evaluate(u, v); }, k);
}

SurfaceSamples sample_grid(const std::function<SurfacePoint(double, double)>& point, int k) {
  assert(k >= 2);
  SurfaceSamples out;
  out.k = k;
  const int count = k * k;
  out.points.resize(count, 3);
  out.normals.resize(count, 3);
  out.mean_curvature.resize(count);
  out.gaussian_curvature.resize(count);
  out.twist.resize(count);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const int row = a * k + b;
      const SurfacePoint p = point(double(a) / (k - 1), double(b) / (k - 1));
      const Curvatures c = curvatures(p);
      out.points.row(row) = p.p;
      out.normals.row(row) = unit_normal(p);
      out.mean_curvature(row) = c.mean;
      out.gaussian_curvature(row) = c.gaussian;
      out.twist(row) = p.duv.stableNorm();  // (norm() underflows below about 1e-154)
    }
  return out;
}

namespace {

// Grid of the reference for starting points, computed once per call of add_reference_distance.
struct StartGrid {
  int k = 33;
  Eigen::MatrixX3d points;
  explicit StartGrid(const Surface& s) : points(k * k, 3) {
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) points.row(a * k + b) = s.at(double(a) / (k - 1), double(b) / (k - 1));
  }
};

ClosestPoint closest_from(const Surface& s, const StartGrid& grid, const Eigen::RowVector3d& p) {
  Eigen::Index best = 0;
  (grid.points.rowwise() - p).rowwise().squaredNorm().minCoeff(&best);
  const Eigen::Index row = best / grid.k, col = best % grid.k;  // the grid point's indices a, b
  double u = double(row) / (grid.k - 1), v = double(col) / (grid.k - 1);
  for (int it = 0; it < 30; ++it) {
    const SurfacePoint x = s.evaluate(u, v);
    const Eigen::RowVector3d d = x.p - p;
    const Eigen::Vector2d g(x.du.dot(d), x.dv.dot(d));
    Eigen::Matrix2d H;  // (positive diagonal either way, unless a partial derivative vanishes)
    H << x.du.dot(x.du) + x.duu.dot(d), x.du.dot(x.dv) + x.duv.dot(d), x.du.dot(x.dv) + x.duv.dot(d),
        x.dv.dot(x.dv) + x.dvv.dot(d);
    if (!(H.determinant() > 0 && H(0, 0) > 0)) {  // not convex here: Gauss–Newton
      H << x.du.dot(x.du), x.du.dot(x.dv), x.du.dot(x.dv), x.dv.dot(x.dv);
    }
    // A parameter on its bound whose gradient points out of the square stays there, and Newton
    // runs on the other one alone (projected Newton): the full step, clamped, moved the free one
    // by almost nothing from (0, 0.34375) towards the nearest point (0, 0.1464) of the test.
    const bool fix_u = (u <= 0 && g(0) > 0) || (u >= 1 && g(0) < 0);
    const bool fix_v = (v <= 0 && g(1) > 0) || (v >= 1 && g(1) < 0);
    if (fix_u && fix_v) break;  // a corner where both point out: a minimum on the square
    Eigen::Vector2d step = Eigen::Vector2d::Zero();
    if (fix_u)
      step(1) = -g(1) / H(1, 1);
    else if (fix_v)
      step(0) = -g(0) / H(0, 0);
    else
      step = -H.ldlt().solve(g);
    if (!step.allFinite()) break;
    // Accept only steps that do not increase the distance, halving one that would (a full step
    // that overshoots used to end the search there: 0.433228 for the exact sqrt(3)/4 = 0.433013).
    double nu = u, nv = v;
    bool accepted = false;
    for (double t = 1; t > 1e-12 && !accepted; t /= 2) {
      nu = std::clamp(u + t * step(0), 0.0, 1.0);
      nv = std::clamp(v + t * step(1), 0.0, 1.0);
      accepted = (s.at(nu, nv) - p).squaredNorm() <= d.squaredNorm();
    }
    if (!accepted) break;
    const bool small = std::abs(nu - u) < 1e-13 && std::abs(nv - v) < 1e-13;
    u = nu;
    v = nv;
    if (small) break;
  }
  return {u, v, (s.at(u, v) - p).norm()};
}

}  // namespace

ClosestPoint closest_point(const Surface& s, const Eigen::RowVector3d& p) { return closest_from(s, StartGrid(s), p); }

void add_reference_distance(SurfaceSamples& samples, const Surface& reference) {
  const StartGrid grid(reference);
  const int k = samples.k;
  Eigen::VectorXd distance(k * k), parametric(k * k);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      const int row = a * k + b;
      const Eigen::RowVector3d p = samples.points.row(row);
      distance(row) = closest_from(reference, grid, p).distance;
      parametric(row) = (reference.at(double(a) / (k - 1), double(b) / (k - 1)) - p).norm();
    }
  samples.distance = std::move(distance);
  samples.parametric_distance = std::move(parametric);
}

}  // namespace coons
