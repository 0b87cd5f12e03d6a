// The common form of every surface of the Coons family (LN0, LN1, LN4): a Boolean sum of
// blended curves and a tensor-product correction,
//
//   r(u, v) = Σ_k a_k(u)·X_k(v)  +  Σ_l Y_l(u)·b_l(v)  +  Σ_k Σ_l s_k(u)·t_l(v)·T_kl
//
// with polynomial blends a, b, s, t (1 − t and t; the Hermite cubics H₀₃, H₃₃, H₁₃, H₂₃), curves
// X (in v) and Y (in u), and constant vectors T. Ruled surfaces have only Y-terms, the Ferguson
// and 16-vector patches only the tensor term, the Coons patches all three (T = −the corner matrix).
// One evaluator gives the point and all partial derivatives up to order 2 of every member; one
// converter gives the exact Bézier net whenever every curve is a Bézier curve (the blends are
// polynomials, so the sum is a tensor-product polynomial: degree (max deg a/s/Y, max deg b/t/X)).
// Based on: S. A. Coons, Surfaces for computer-aided design of space forms, MIT MAC-TR-41 (1967);
// W. J. Gordon, Blending-function methods of bivariate and multivariate interpolation, SIAM J.
// Numer. Anal. 8 (1971); LN1 (the matrix forms of the six Coons patches).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "coons/curves/curve.h"
#include "coons/net/control_net.h"
#include "coons/net/surface_point.h"

namespace coons {

//! A polynomial blend function on [0, 1], stored by its Bernstein coefficients (#degree+1).
struct Blend {
  Eigen::VectorXd bernstein;

  [[nodiscard]] int degree() const { return int(bernstein.size()) - 1; }
  //! d^r a / dt^r (t).
  [[nodiscard]] double value(int r, double t) const;
  //! The Bernstein coefficients at degree k ≥ degree() (degree elevation).
  [[nodiscard]] Eigen::VectorXd bernstein_at(int k) const;
  //! From monomial coefficients c₀ + c₁t + … (degree = size − 1).
  static Blend from_monomial(const std::vector<double>& c);
};

//! 1 − t and t (bilinear blending).
Blend linear_blend(int i);
//! Hermite cubics (LN0): H₀₃ = 1 − 3t² + 2t³ (i = 0), H₃₃ = 3t² − 2t³ (1),
//! H₁₃ = t − 2t² + t³ (2), H₂₃ = −t² + t³ (3). F₀ = H₀₃ and F₁ = H₃₃ in LN1's notation.
Blend hermite_blend(int i);

struct BlendedCurve {
  Blend blend;
  Curve curve;
};

struct BooleanSum {
  std::vector<BlendedCurve> u_blended;                  //!< a_k(u)·X_k(v): blend in u, curve in v
  std::vector<BlendedCurve> v_blended;                  //!< Y_l(u)·b_l(v): curve in u, blend in v
  std::vector<Blend> tensor_u, tensor_v;                //!< s_k(u), t_l(v)
  std::vector<std::vector<Eigen::RowVector3d>> tensor;  //!< T_kl, #tensor_u by #tensor_v
};

//! r and its partial derivatives up to order 2 at (u, v).
SurfacePoint evaluate(const BooleanSum& sum, double u, double v);

//! The exact Bézier net when every curve is a Bézier curve; nullopt otherwise.
std::optional<ControlNet> bezier_net(const BooleanSum& sum);

}  // namespace coons
