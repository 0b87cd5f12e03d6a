// Control nets and boundaries of tensor-product Bézier surfaces (conventions: docs/math.md §1).
#pragma once

#include <Eigen/Core>
#include <string>

namespace coons {

//! An (m+1)×(n+1) net of points b[i][j] ∈ R³, stored row-major: row i·(n+1)+j of `points`.
struct ControlNet {
  int m = 0;                //!< degree in u (index i)
  int n = 0;                //!< degree in v (index j)
  Eigen::MatrixX3d points;  //!< #(m+1)(n+1) by 3

  ControlNet() = default;
  ControlNet(int degree_u, int degree_v)
      : m(degree_u), n(degree_v), points(Eigen::MatrixX3d::Zero((degree_u + 1) * (degree_v + 1), 3)) {}

  [[nodiscard]] Eigen::Index index(int i, int j) const { return Eigen::Index(i) * (n + 1) + j; }
  auto at(int i, int j) { return points.row(index(i, j)); }
  [[nodiscard]] auto at(int i, int j) const { return points.row(index(i, j)); }
};

//! The four sides of a net, each in increasing index order: bottom = b[i][0], top = b[i][n]
//! (#m+1 by 3), left = b[0][j], right = b[m][j] (#n+1 by 3). Corners are shared.
struct Boundary {
  std::string name;
  int m = 0, n = 0;
  Eigen::MatrixX3d bottom, top, left, right;
};

//! The boundary of a net.
Boundary boundary_of(const ControlNet& net, std::string name = {});

//! A net holding the boundary on its frame and zeros inside. Sides are taken as given; the
//! corners come from bottom and top.
ControlNet frame_net(const Boundary& boundary);

//! Largest distance between the two copies of a corner, and which corner it is
//! ("bottom-left" = b[0][0], "bottom-right" = b[m][0], "top-left" = b[0][n], "top-right" = b[m][n]).
struct CornerGap {
  std::string corner;
  double gap = 0;
};
CornerGap largest_corner_gap(const Boundary& boundary);

//! Length of the diagonal of the bounding box of all boundary points.
double bounding_box_diagonal(const Boundary& boundary);

//! The centre of the bounding box of the rows of `points` (zero when there are none or one is not
//! finite): where a computation that only differences see (masks that reproduce constants,
//! energies) moves its data to keep their digits.
Eigen::RowVector3d bounding_box_centre(const Eigen::MatrixX3d& points);
//! The same for the points of the four sides.
Eigen::RowVector3d bounding_box_centre(const Boundary& boundary);

//! v times the power of two that puts its largest |coordinate| in [1, 2), exactly (v itself when it
//! is zero or not finite): a direction whose norm(), squares or cross products would underflow or
//! overflow (coordinates of 1e-170), with the same digits.
Eigen::RowVector3d unit_scaled(const Eigen::RowVector3d& v);

//! |v| without underflow or overflow: v scaled by a power of two first, so that the result is bit
//! for bit norm()'s wherever norm() neither underflows nor overflows (coordinates of 1e-170).
double scaled_norm(const Eigen::RowVector3d& v);

}  // namespace coons
