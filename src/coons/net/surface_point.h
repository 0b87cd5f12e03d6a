// A point of a parametric surface r(u, v) with its first and second partial derivatives, and the
// differential geometry read from them: unit normal, mean and Gaussian curvature, twist ‖r_uv‖.
// Based on: M. P. do Carmo, Differential Geometry of Curves and Surfaces (1976), §3-3
// (K = (LN − M²)/(EG − F²), H = (EN − 2FM + GL)/(2(EG − F²))); LN0, the twist vector.
#pragma once

#include <Eigen/Core>

namespace coons {

struct SurfacePoint {
  Eigen::RowVector3d p = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d du = Eigen::RowVector3d::Zero(), dv = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d duu = Eigen::RowVector3d::Zero(), duv = Eigen::RowVector3d::Zero(),
                     dvv = Eigen::RowVector3d::Zero();

  //! ∂^a_u ∂^b_v r for a + b ≤ 2 (zero row for anything higher).
  [[nodiscard]] Eigen::RowVector3d derivative(int a, int b) const;
};

//! The unit vector of a × b, both divided by their norms first (no underflow or overflow of the
//! product at any scale); NaN when either vanishes or they are parallel (|â × b̂| ≤ 1e-14).
Eigen::RowVector3d unit_cross(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b);

//! unit_cross(r_u, r_v); NaN where the surface is singular (r_u ∥ r_v).
Eigen::RowVector3d unit_normal(const SurfacePoint& s);

struct Curvatures {
  double mean = 0;      //!< H, sign relative to the normal r_u × r_v (a sphere with outward normal: H < 0)
  double gaussian = 0;  //!< K
};

//! NaN where the surface is singular.
Curvatures curvatures(const SurfacePoint& s);

}  // namespace coons
