// The frame in which the α search works: the boundary moved so that its bounding-box centre is
// the origin and scaled by a power of two to a diagonal in [1/√2, √2), the objective's target moved
// with it. Every objective over α is invariant under translation and scales as s² (energies) or
// s (the rms distance to a target), so the search's optimum, flatness and bound are the same in
// this frame, and no tolerance of the search meets coordinates of size 1e−150 or 1e150 (issue 17).
// The weights are divided by W, the power of two nearest to the largest (after the target's 1/s),
// so that the frame's objective is of order one for any weights. Values map back exactly:
// f = value_factor · f_unit, where
//   energies (and weighted sums with a target): value_factor = s²·W, target weight w/(s·W) in the frame;
//   the target alone:                             value_factor = s·W,  target weight w/W.
// Sizes: a copy of the boundary (and of a target net).
#pragma once

#include <Eigen/Core>
#include <limits>

#include "coons/alpha/objective.h"
#include "coons/net/control_net.h"

namespace coons {

struct NormalisedFrame {
  Eigen::RowVector3d centre{0, 0, 0};  //!< bounding-box centre of the boundary
  double scale = 1;                    //!< s: x = centre + s · x_unit (a power of two)
  double value_factor = 1;             //!< f(x) = value_factor · f_unit(x_unit)
  Boundary boundary;                   //!< the boundary in the frame
  Objective objective;                 //!< the objective in the frame (target moved, weight scaled)

  //! A net of the frame back in the caller's coordinates.
  [[nodiscard]] ControlNet to_original(ControlNet net) const;
};

//! A boundary whose bounding-box half diagonal is at most this fraction of its largest coordinate
//! magnitude is one point to within rounding (16 ε).
inline constexpr double kPointExtent = 16 * std::numeric_limits<double>::epsilon();

//! Whether the bounding box [lo, hi] (finite) is one point to within rounding (kPointExtent): the
//! rule of this frame, and of the triangles' search.
bool is_one_point(const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi);

//! The frame of `boundary` and `objective` (an empty boundary: scale 1, centre 0; a one-point
//! boundary, kPointExtent included: scale 1, centre the box centre, every frame point exactly 0).
NormalisedFrame normalised_frame(const Boundary& boundary, const Objective& objective);

}  // namespace coons
