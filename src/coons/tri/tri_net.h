// Triangular Bézier nets of degree n: points b_ijk, i + j + k = n, #(n+1)(n+2)/2 by 3, stored in the
// row order of docs/formats.md "Triangular nets": row k = 0 … n, within a row j = 0 … n−k,
// i = n−k−j. Three sides (k = 0 from (n,0,0) to (0,n,0); i = 0 from (0,n,0) to (0,0,n); j = 0 from
// (0,0,n) to (n,0,0)), corners shared, (n−1)(n−2)/2 interior points (i, j, k ≥ 1).
// The surface is p(u,v,w) = Σ b_ijk n!/(i!j!k!) u^i v^j w^k; u weights (n,0,0), v (0,n,0), w (0,0,n).
// Based on: G. Farin, Curves and Surfaces for CAGD, 5th ed. (2002), ch. 17 (triangular patches:
// de Casteljau, derivatives, degree elevation, subdivision).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <utility>

namespace coons::tri {

//! Number of points of a degree-n net: (n+1)(n+2)/2.
inline Eigen::Index net_size(int n) { return Eigen::Index(n + 1) * (n + 2) / 2; }
//! Number of interior points (i, j, k ≥ 1): (n−1)(n−2)/2, 0 for n < 3.
inline Eigen::Index interior_size(int n) { return n < 3 ? 0 : Eigen::Index(n - 1) * (n - 2) / 2; }
//! Row of b[n−k−j][j][k] in the row order: k(n+1) − k(k−1)/2 + j.
inline Eigen::Index net_index(int n, int j, int k) {
  return Eigen::Index(k) * (n + 1) - Eigen::Index(k) * (k - 1) / 2 + j;
}
//! Unknown number of interior point b[n−k−j][j][k] (j, k ≥ 1, j + k ≤ n − 1), in the same row order.
inline Eigen::Index interior_index(int n, int j, int k) {
  return Eigen::Index(k - 1) * (n - 1) - Eigen::Index(k - 1) * k / 2 + (j - 1);
}

struct TriNet {
  int n = 0;                //!< degree
  Eigen::MatrixX3d points;  //!< #(n+1)(n+2)/2 by 3, row order

  TriNet() : points(Eigen::MatrixX3d::Zero(1, 3)) {}
  explicit TriNet(int degree) : n(degree), points(Eigen::MatrixX3d::Zero(net_size(degree), 3)) {}

  //! Row of b_ijk (i + j + k must be n).
  [[nodiscard]] Eigen::Index index(int /*i*/, int j, int k) const { return net_index(n, j, k); }
  auto at(int i, int j, int k) { return points.row(index(i, j, k)); }
  [[nodiscard]] auto at(int i, int j, int k) const { return points.row(index(i, j, k)); }
};

//! Row k of the contract's `net` report: b[n−k−j][j][k] for j = 0 … n−k (#n−k+1 by 3).
inline Eigen::MatrixX3d net_row(const TriNet& net, int k) {
  return net.points.middleRows(net_index(net.n, 0, k), net.n - k + 1);
}

//! The largest degree of a triangular boundary that the readers and the study accept. The exact
//! energies use the dense triangular Bernstein Gram matrix, #(n+1)(n+2)/2 square, built entry by
//! entry: measured (2026-11-29, 2 cores) a `coons solve` took 0.7 s at degree 30, 1.8 s at 40,
//! 5.2 s at 50 and 11 s at 60 (almost all of it energies), and at 400 the Gram matrices (52 GB)
//! ran out of memory. 40 keeps a solve within about 2 s and a search within about 5 s. (Since
//! 2026-11-30 the Gram matrices are built once per degree for a net's metrics: 0.46 s at 40.)
inline constexpr int kMaxTriDegree = 40;

//! The three sides, each #n+1 by 3 and running as in the contract: sides[0] = k = 0 from b[n][0][0]
//! to b[0][n][0]; sides[1] = i = 0 from b[0][n][0] to b[0][0][n]; sides[2] = j = 0 from b[0][0][n]
//! to b[n][0][0]. The last point of each side is the first of the next.
struct TriBoundary {
  std::string name;
  int n = 0;
  std::array<Eigen::MatrixX3d, 3> sides;
};

//! The boundary of a net.
TriBoundary boundary_of(const TriNet& net, std::string name = {});

//! The centre of the bounding box of a net's boundary points (lo/2 + hi/2: no overflow). The mask
//! family is affine (its weights sum to 1), so a net solved about this centre and moved back is the
//! same net, without the rounding of coordinates far from the origin (a boundary moved by 2^45
//! gave a thin plate energy of 11.8746 for 11.8125 at c = 0).
Eigen::RowVector3d boundary_centre(const TriNet& net);
//! The bounding box of a net's boundary points: {lo, hi}.
std::pair<Eigen::RowVector3d, Eigen::RowVector3d> boundary_box(const TriNet& net);

//! A net with the boundary on its sides and zeros inside. Each side is written in order 0, 1, 2,
//! so a corner takes the value of the later side (corners are expected to agree; see corner_gap).
TriNet frame_net(const TriBoundary& boundary);

//! Largest distance between the two copies of a corner, and which: "b[n][0][0]" (end of side 2,
//! start of side 0), "b[0][n][0]" (sides 0 and 1) or "b[0][0][n]" (sides 1 and 2).
struct TriCornerGap {
  std::string corner;
  double gap = 0;
};
TriCornerGap largest_corner_gap(const TriBoundary& boundary);

//! True when (i, j, k) is an interior index of degree n.
inline bool is_interior(int n, int i, int j, int k) { return i >= 1 && j >= 1 && k >= 1 && i + j + k == n; }

//! The point at barycentric (u, v, w) by de Casteljau (any affine (u, v, w), usually u+v+w = 1).
Eigen::RowVector3d evaluate(const TriNet& net, const Eigen::Vector3d& uvw);

//! The net of D_d p for a direction d = (d1, d2, d3) with d1 + d2 + d3 = 0: degree n−1, points
//! n·(d1 b_{β+e1} + d2 b_{β+e2} + d3 b_{β+e3}), |β| = n−1. A degree-0 net gives a zero degree-0 net.
TriNet derivative_net(const TriNet& net, const Eigen::Vector3d& d);

//! D_d p(u, v, w) and D_d1 D_d2 p(u, v, w).
Eigen::RowVector3d directional_derivative(const TriNet& net, const Eigen::Vector3d& uvw, const Eigen::Vector3d& d);
Eigen::RowVector3d second_directional_derivative(const TriNet& net, const Eigen::Vector3d& uvw,
                                                 const Eigen::Vector3d& d1, const Eigen::Vector3d& d2);

//! The same surface at degree n + times: b'_α = (i b_{α−e1} + j b_{α−e2} + k b_{α−e3}) / (n+1), repeated.
TriNet elevate_degree(const TriNet& net, int times = 1);

//! Subdivision at a point P = (u, v, w) of the domain into three triangles: part[0] has vertices
//! (P, V2, V3), part[1] (V1, P, V3), part[2] (V1, V2, P), where V1, V2, V3 are the corners of
//! (n,0,0), (0,n,0), (0,0,n). Each is a degree-n net of the same surface over its sub-triangle:
//! part[0] at barycentric (s1, s2, s3) is the surface at s1·P + s2·e2 + s3·e3, and so on.
std::array<TriNet, 3> subdivide_at(const TriNet& net, const Eigen::Vector3d& uvw);

//! The sub-net b[i0+i'][j0+j'][k0+k'], i'+j'+k' = n − i0 − j0 − k0 (the index sub-triangle i ≥ i0,
//! j ≥ j0, k ≥ k0), as a net of that degree. Requires i0, j0, k0 ≥ 0 and i0+j0+k0 ≤ n.
TriNet sub_net(const TriNet& net, int i0, int j0, int k0);

//! b'[σ(i,j,k)] = b[i][j][k] for a permutation σ of the three indices: perm[m] is the position
//! in the new index triple that the old index m goes to (e.g. {1, 0, 2} swaps i and j).
TriNet permuted(const TriNet& net, const std::array<int, 3>& perm);

}  // namespace coons::tri
