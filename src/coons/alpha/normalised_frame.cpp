#include "normalised_frame.h"

#include <algorithm>
#include <cmath>

namespace coons {
namespace {

// The bounding box of the four sides, computed without overflow (max − min may not fit, so the
// centre is min/2 + max/2 and the diagonal is measured on the halves).
void bounding_box(const Boundary& b, Eigen::RowVector3d& lo, Eigen::RowVector3d& hi) {
  lo.setConstant(HUGE_VAL);
  hi.setConstant(-HUGE_VAL);
  for (const Eigen::MatrixX3d* side : {&b.bottom, &b.top, &b.left, &b.right}) {
    if (side->rows() == 0) continue;
    lo = lo.cwiseMin(side->colwise().minCoeff());
    hi = hi.cwiseMax(side->colwise().maxCoeff());
  }
}

Eigen::MatrixX3d moved(const Eigen::MatrixX3d& points, const Eigen::RowVector3d& centre, double inv_scale) {
  return (points.rowwise() - centre) * inv_scale;
}

}  // namespace

bool is_one_point(const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi) {
  // halves and stableNorm: max − min may not fit, and norm() underflows to 0 below about 1e-154
  const double half_diagonal = (0.5 * hi - 0.5 * lo).stableNorm();
  return half_diagonal <= kPointExtent * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
}

ControlNet NormalisedFrame::to_original(ControlNet net) const {
  net.points = (net.points * scale).rowwise() + centre;
  return net;
}

NormalisedFrame normalised_frame(const Boundary& boundary, const Objective& objective) {
  NormalisedFrame f;
  f.boundary = boundary;
  f.objective = objective;
  Eigen::RowVector3d lo, hi;
  bounding_box(boundary, lo, hi);
  if (!lo.allFinite() || !hi.allFinite()) return f;
  const Eigen::RowVector3d half = 0.5 * hi - 0.5 * lo;
  const double half_diagonal = half.stableNorm();  // norm() underflows to 0 below about 1e-154
  if (!std::isfinite(half_diagonal)) return f;
  f.centre = 0.5 * lo + 0.5 * hi;
  // s = 2^k nearest to the diagonal 2·|half|: scaling by it is exact. A one-point boundary keeps
  // s = 1 but moves to the origin: its nets are then exactly 0, with no rounding noise of the
  // size of its coordinates for the search to read as a signal.
  // Below a diagonal of about 2^-537 the value factor s² is 0 and values could not be mapped into
  // the frame: such a boundary keeps s = 1 (its energies underflow in the caller's units).
  // An extent within rounding of the position is one point too: the exact elevation of a constant
  // side, computed in floating point, spreads 3 to 3.0000000000000004, and scaled up to unit size
  // that spread read as a shape with interior optima.
  const bool one_point = is_one_point(lo, hi);
  if (half_diagonal > 0 && !one_point) {
    const long exponent = std::lround(std::log2(half_diagonal)) + 1;
    if (2 * exponent >= -1074) f.scale = std::ldexp(1.0, int(exponent));
  }
  const double inv = 1 / f.scale;
  for (Eigen::MatrixX3d* side : {&f.boundary.bottom, &f.boundary.top, &f.boundary.left, &f.boundary.right})
    *side = one_point ? Eigen::MatrixX3d::Zero(side->rows(), 3) : moved(*side, f.centre, inv);

  const bool energies = !objective.energy.empty() || !objective.discrete.empty();
  f.value_factor = energies ? f.scale * f.scale : f.scale;
  if (energies) f.objective.target_weight = objective.target_weight * inv;
  // The weights: divided by W = 2^k nearest to the largest, so that the frame's objective is of
  // order one for any weights (1e-300*thin_plate would read as flat against tolerances in units
  // of the boundary, 1e300*e3 would overflow near the optimum); W joins the value factor.
  double largest = f.objective.target_weight;
  for (const EnergyTerm& t : f.objective.energy) largest = std::max(largest, t.weight);
  for (const auto& [kind, weight] : f.objective.discrete) largest = std::max(largest, weight);
  if (largest > 0 && std::isfinite(largest)) {
    const double w = std::ldexp(1.0, int(std::lround(std::log2(largest))));
    if (std::isnormal(f.value_factor * w)) {  // else values could not be mapped back: keep W = 1
      f.value_factor *= w;
      for (EnergyTerm& t : f.objective.energy) t.weight /= w;
      for (auto& [kind, weight] : f.objective.discrete) weight /= w;
      f.objective.target_weight /= w;
    }
  }
  if (f.objective.target) {
    Target& t = *f.objective.target;
    if (t.kind == Target::Kind::kNet) {
      t.net.points = moved(t.net.points, f.centre, inv);
    } else {
      t.point = (t.point - f.centre) * inv;
      t.radius *= inv;
    }
  }
  return f;
}

}  // namespace coons
