#include "coons/tri/tri_extremal.h"

#include <Eigen/Dense>
#include <cmath>
#include <vector>

#include "coons/tri/tri_energy.h"

namespace coons::tri {

namespace {

// D_d as a (#degree n−1) by (#degree n) matrix: row β has n·d_l at column β + e_l.
Eigen::MatrixXd derivative_operator(int n, const Eigen::Vector3d& d) {
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(net_size(n - 1), net_size(n));
  for (int k = 0; k <= n - 1; ++k)
    for (int j = 0; j <= n - 1 - k; ++j) {
      const Eigen::Index row = net_index(n - 1, j, k);
      D(row, net_index(n, j, k)) += n * d(0);
      D(row, net_index(n, j + 1, k)) += n * d(1);
      D(row, net_index(n, j, k + 1)) += n * d(2);
    }
  return D;
}

Eigen::MatrixXd second_operator(int n, const Eigen::Vector3d& d1, const Eigen::Vector3d& d2) {
  return derivative_operator(n - 1, d2) * derivative_operator(n, d1);
}

}  // namespace

double TriDomain::area() const {
  const Eigen::Vector2d a = v1 - v3, b = v2 - v3;
  return 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
}

Eigen::Matrix<double, 3, 2> TriDomain::cartesian_directions() const {
  Eigen::Matrix3d M;  // (x, y, 1) = M λ
  M << v1.x(), v2.x(), v3.x(), v1.y(), v2.y(), v3.y(), 1, 1, 1;
  return M.inverse().leftCols<2>();
}

Eigen::MatrixXd tri_energy_hessian(int n, TriEnergy kind, const TriDomain& domain) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(net_size(n), net_size(n));
  const Eigen::Matrix<double, 3, 2> dxy = domain.cartesian_directions();
  const Eigen::Vector3d dx = dxy.col(0), dy = dxy.col(1);
  const double area_scale = 2 * domain.area();  // the Gram matrix is for area 1/2
  if (kind == TriEnergy::kDirichlet) {
    if (n < 1) return K;
    const Eigen::MatrixXd G = area_scale * tri_bernstein_gram(n - 1);
    for (const auto& d : {dx, dy}) {
      const Eigen::MatrixXd D = derivative_operator(n, d);
      K += D.transpose() * G * D;
    }
    return K;
  }
  if (n < 2) return K;
  const Eigen::MatrixXd G = area_scale * tri_bernstein_gram(n - 2);
  auto add = [&](const Eigen::MatrixXd& D, double weight) { K += weight * D.transpose() * G * D; };
  if (kind == TriEnergy::kThinPlate) {
    add(second_operator(n, dx, dx), 1);
    add(second_operator(n, dx, dy), 2);
    add(second_operator(n, dy, dy), 1);
  } else {
    const Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
    for (int m = 0; m < 3; ++m)
      add(second_operator(n, e.col((m + 1) % 3) - e.col(m), e.col((m + 2) % 3) - e.col(m)), 1.0 / 3);
  }
  return K;
}

TriNet minimize_tri_energy(const TriNet& frame, TriEnergy kind, const TriDomain& domain) {
  const int n = frame.n;
  const Eigen::Index m = interior_size(n);
  if (m == 0) return frame;
  const Eigen::MatrixXd K = tri_energy_hessian(n, kind, domain);
  std::vector<Eigen::Index> interior_rows;  // net row of each unknown, in unknown order
  interior_rows.reserve(m);
  for (int k = 1; k <= n - 2; ++k)
    for (int j = 1; j <= n - 1 - k; ++j) interior_rows.push_back(net_index(n, j, k));
  Eigen::MatrixXd KII(m, m);
  Eigen::MatrixX3d rhs = Eigen::MatrixX3d::Zero(m, 3);
  TriNet boundary_only = frame;
  for (const Eigen::Index r : interior_rows) boundary_only.points.row(r).setZero();
  const Eigen::MatrixX3d k_boundary = K * boundary_only.points;
  for (Eigen::Index a = 0; a < m; ++a) {
    rhs.row(a) = -k_boundary.row(interior_rows[a]);
    for (Eigen::Index b = 0; b < m; ++b) KII(a, b) = K(interior_rows[a], interior_rows[b]);
  }
  const Eigen::MatrixX3d X = KII.ldlt().solve(rhs);
  TriNet out = frame;
  for (Eigen::Index a = 0; a < m; ++a) out.points.row(interior_rows[a]) = X.row(a);
  return out;
}

}  // namespace coons::tri
