// Test references for stencil problems, written from the definitions and independent of the
// assembly code: the dense system of the mask equations, its dense solve, random free sets, and
// the discrete energies whose Euler–Lagrange operators the 5×5 masks are.
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <random>
#include <vector>

#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"

namespace coons::test {

//! The free points of a problem from its definition: `free` or the inside of the rings.
inline FreeGrid reference_free(const StencilProblem& p) {
  FreeGrid f(p.net.m + 1, p.net.n + 1);
  for (int i = 0; i <= p.net.m; ++i)
    for (int j = 0; j <= p.net.n; ++j)
      f(i, j) = p.free.size() > 0 ? bool(p.free(i, j))
                                  : (i >= p.rings && j >= p.rings && i <= p.net.m - p.rings && j <= p.net.n - p.rings);
  return f;
}

//! The mask equations Σ W(a, b) b_{i+a, j+b} = 0 at every free point, densely: A (#free square)
//! and B (#free by 3), unknowns in row-major order of the free points.
inline void dense_stencil_system(const StencilProblem& p, const Stencil& s, Eigen::MatrixXd& A, Eigen::MatrixX3d& B) {
  const FreeGrid f = reference_free(p);
  Eigen::ArrayXXi id = Eigen::ArrayXXi::Constant(f.rows(), f.cols(), -1);
  int N = 0;
  for (int i = 0; i < f.rows(); ++i)
    for (int j = 0; j < f.cols(); ++j)
      if (f(i, j)) id(i, j) = N++;
  A = Eigen::MatrixXd::Zero(N, N);
  B = Eigen::MatrixX3d::Zero(N, 3);
  for (int i = 0; i < f.rows(); ++i)
    for (int j = 0; j < f.cols(); ++j) {
      if (!f(i, j)) continue;
      const int row = id(i, j);
      for (int a = -s.radius; a <= s.radius; ++a)
        for (int b = -s.radius; b <= s.radius; ++b) {
          const double w = s.weights(s.radius + a, s.radius + b);
          if (id(i + a, j + b) >= 0)
            A(row, id(i + a, j + b)) += w;
          else
            B.row(row) -= w * p.net.at(i + a, j + b);
        }
    }
}

//! The net with its free points from a dense LU solve of the mask equations.
inline ControlNet dense_stencil_solve(const StencilProblem& p, const Stencil& s) {
  Eigen::MatrixXd A;
  Eigen::MatrixX3d B;
  dense_stencil_system(p, s, A, B);
  const Eigen::MatrixX3d X = A.fullPivLu().solve(B);
  ControlNet net = p.net;
  const FreeGrid f = reference_free(p);
  int k = 0;
  for (int i = 0; i < f.rows(); ++i)
    for (int j = 0; j < f.cols(); ++j)
      if (f(i, j)) net.at(i, j) = X.row(k++);
  return net;
}

//! A random free set inside `rings` rings: each point free with probability `density`.
inline FreeGrid random_free(int m, int n, int rings, double density, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  FreeGrid f = FreeGrid::Constant(m + 1, n + 1, false);
  for (int i = rings; i <= m - rings; ++i)
    for (int j = rings; j <= n - rings; ++j) f(i, j) = u(rng) < density;
  return f;
}

//! Discrete energies of one coordinate column of a net (sums over every position where the
//! forward difference fits): Σ‖Δ^{p,q} b‖².
inline double difference_energy(const ControlNet& net, int p, int q) {
  static const double kCoeff[3][3] = {{1, 0, 0}, {-1, 1, 0}, {1, -2, 1}};
  double e = 0;
  for (int i = 0; i + p <= net.m; ++i)
    for (int j = 0; j + q <= net.n; ++j) {
      Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
      for (int a = 0; a <= p; ++a)
        for (int b = 0; b <= q; ++b) d += kCoeff[p][a] * kCoeff[q][b] * net.at(i + a, j + b);
      e += d.squaredNorm();
    }
  return e;
}

//! The discrete thin-plate energy Σ‖Δ^{2,0}b‖² + 2Σ‖Δ^{1,1}b‖² + Σ‖Δ^{0,2}b‖².
inline double reference_thin_plate_energy(const ControlNet& net) {
  return difference_energy(net, 2, 0) + 2 * difference_energy(net, 1, 1) + difference_energy(net, 0, 2);
}

//! w·Σ‖Δ^{2,2}b‖² + (1 − w)·thin plate.
inline double c1_family_energy(const ControlNet& net, double w) {
  return w * difference_energy(net, 2, 2) + (1 - w) * reference_thin_plate_energy(net);
}

}  // namespace coons::test
