#include "coons/tri/tri_sampling.h"

#include <Eigen/Dense>
#include <cmath>

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
      const Eigen::RowVector3d px = directional_derivative(net, uvw, dx), py = directional_derivative(net, uvw, dy);
      const Eigen::RowVector3d cross = px.cross(py);
      const double length = cross.norm(), scale = std::max(px.norm() * py.norm(), 1e-300);
      if (!(length > 1e-12 * scale)) {
        out.singular(row) = 1;
        continue;
      }
      const Eigen::RowVector3d normal = cross / length;
      out.normals.row(row) = normal;
      const double e = px.dot(px), f = px.dot(py), g = py.dot(py);
      const double l = second_directional_derivative(net, uvw, dx, dx).dot(normal);
      const double m = second_directional_derivative(net, uvw, dx, dy).dot(normal);
      const double nn = second_directional_derivative(net, uvw, dy, dy).dot(normal);
      const double det = e * g - f * f;
      out.gaussian_curvature(row) = (l * nn - m * m) / det;
      out.mean_curvature(row) = (e * nn - 2 * f * m + g * l) / (2 * det);
    }
  out.triangles = tri_grid_triangles(k);
  return out;
}

}  // namespace coons::tri
