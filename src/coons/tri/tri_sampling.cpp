#include "coons/tri/tri_sampling.h"

#include <Eigen/Dense>
#include <cmath>

#include "coons/net/surface_point.h"
#include "coons/tri/tri_energy.h"

namespace coons::tri {

Eigen::Vector3d tri_sample_uvw(int k, int r, int s) {
  const double d = k - 1;
  return {(k - 1 - r - s) / d, s / d, r / d};
}

std::vector<std::array<int, 3>> tri_grid_triangles(int k) {
  std::vector<std::array<int, 3>> out;
  const int n = k - 1;
  auto at = [n](int r, int s) { return int(net_index(n, s, r)); };
  for (int r = 0; r < n; ++r)
    for (int s = 0; s + r < n; ++s) {
      out.push_back({at(r, s), at(r, s + 1), at(r + 1, s)});
      if (s + r + 1 < n) out.push_back({at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  return out;
}

TriSurfaceSamples sample_tri_surface(const TriNet& net, int k) {
  TriSurfaceSamples out;
  out.k = k;
  const Eigen::Index size = net_size(k - 1);
  out.points.resize(size, 3);
  out.normals = Eigen::MatrixX3d::Zero(size, 3);
  out.mean_curvature = Eigen::VectorXd::Zero(size);
  out.gaussian_curvature = Eigen::VectorXd::Zero(size);
  out.singular = Eigen::VectorXi::Zero(size);
  const Eigen::Vector3d dx = direction_x(), dy = direction_y();
  for (int r = 0; r < k; ++r)
    for (int s = 0; s + r < k; ++s) {
      const Eigen::Index row = net_index(k - 1, s, r);
      const Eigen::Vector3d uvw = tri_sample_uvw(k, r, s);
      out.points.row(row) = evaluate(net, uvw);
      SurfacePoint point;
      point.du = directional_derivative(net, uvw, dx);
      point.dv = directional_derivative(net, uvw, dy);
      // (unit_cross and curvatures work in units of the derivatives: at a model size of 1e-100 the
      // cross product of the derivatives underflowed, and every normal came out 0 or (0, 0, 1))
      const Eigen::RowVector3d normal = unit_normal(point);
      if (!normal.allFinite()) {
        out.singular(row) = 1;
        continue;
      }
      out.normals.row(row) = normal;
      point.duu = second_directional_derivative(net, uvw, dx, dx);
      point.duv = second_directional_derivative(net, uvw, dx, dy);
      point.dvv = second_directional_derivative(net, uvw, dy, dy);
      const Curvatures c = curvatures(point);
      out.gaussian_curvature(row) = c.gaussian;
      out.mean_curvature(row) = c.mean;
    }
  out.triangles = tri_grid_triangles(k);
  return out;
}

}  // namespace coons::tri
