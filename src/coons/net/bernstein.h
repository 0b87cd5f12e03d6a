// Bernstein polynomials and tensor-product Bézier surfaces: basis values, Gram matrices,
// derivative nets, evaluation and sampling (conventions: docs/math.md §1, §5).
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed., Morgan Kaufmann (2002), ch. 5, 14.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "coons/net/control_net.h"

namespace coons {

//! Up to this degree bernstein_basis() runs the de Casteljau triangle, (k+1)k/2 steps; above it
//! (for t ∈ [0, 1]) the ratios of neighbouring values in O(k).
inline constexpr int kDeCasteljauMaxDegree = 100;

//! B_i^k(t), i = 0..k (#k+1). Up to kDeCasteljauMaxDegree (and outside [0, 1]) by the stable de
//! Casteljau triangle; above it in O(k): the values from the largest, at i* = ⌊(k+1)t⌋, outwards by
//! their ratios B_{i+1}/B_i = (k−i)/(i+1) · t/(1−t), divided by their sum, which is 1 (partition
//! of unity): no power of t or 1 − t is formed, so nothing under- or overflows at any k. A Bézier
//! surface of a degree-5000 side compared with a reference took 31 s with the triangle alone.
Eigen::VectorXd bernstein_basis(int k, double t);

//! G[i][l] = ∫₀¹ B_i^k B_l^k = C(k,i)·C(k,l) / ((2k+1)·C(2k,i+l)), (#k+1 by #k+1).
Eigen::MatrixXd bernstein_gram(int k);

//! Single entries of bernstein_gram(k), bit for bit, without forming the matrix (the binomials
//! are tabulated once: O(k²) additions up to k = 510, O(k) log-gamma calls beyond).
class BernsteinGramEntries {
 public:
  explicit BernsteinGramEntries(int k);
  //! G[i][l] = G[l][i], 0 ≤ i, l ≤ k.
  [[nodiscard]] double operator()(int i, int l) const;

 private:
  int k_;
  bool log_form_;
  std::vector<double> ck_, c2k_;  //!< C(k, i) and C(2k, r), or their logarithms beyond k = 510
};

//! Coordinate c (0, 1, 2) of the net as an (m+1) by (n+1) matrix.
Eigen::MatrixXd coordinate_grid(const ControlNet& net, int c);

//! The net of ∂^a_u ∂^b_v p: degree (m−a, n−b), coefficients [m!/(m−a)!][n!/(n−b)!]·Δ^{a,b} b.
//! When a > m or b > n the derivative vanishes: a single zero point, degree (0, 0).
ControlNet derivative_net(const ControlNet& net, int a, int b);

//! p(u, v).
Eigen::RowVector3d evaluate(const ControlNet& net, double u, double v);

//! ∂^a_u ∂^b_v p(u, v).
Eigen::RowVector3d evaluate_derivative(const ControlNet& net, int a, int b, double u, double v);

//! p on the ku × kv grid u = s/(ku−1), v = t/(kv−1): #ku·kv by 3, row s·kv + t. ku, kv ≥ 2.
Eigen::MatrixX3d sample_surface(const ControlNet& net, int ku, int kv);

}  // namespace coons
