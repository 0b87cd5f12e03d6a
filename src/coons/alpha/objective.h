// Objectives for choosing a mask: exact energies of the Bézier surface (docs/math.md §5), the rms
// distance of the sampled surface to a target, and weighted sums of them. Each objective gives
// its value at a net N and its derivative along an interior variation dN (energies are quadratic,
// so the derivative is 2·form(N, dN)).
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999); H. P. Moreton,
// C. H. Séquin, Functional optimization for fair surface design, SIGGRAPH 1992.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"

namespace coons {

//! What the surface should be close to (for the `target` objective).
struct Target {
  enum class Kind { kNet, kSphere, kCylinder, kPlane };
  Kind kind = Kind::kNet;
  ControlNet net;                         //!< kNet: compared point by point at the same (u, v)
  Eigen::RowVector3d point{0, 0, 0};      //!< sphere centre, a point on the cylinder axis or plane
  Eigen::RowVector3d direction{0, 0, 1};  //!< cylinder axis or plane normal (any length)
  double radius = 1;                      //!< sphere and cylinder
  int samples = 41;                       //!< the surface is sampled on samples × samples points
};

//! Signed distance of p to an analytic target (sphere, cylinder, plane) and its gradient.
//! With `hessian`, also its Hessian in p (sphere: (I − nnᵀ)/r; cylinder: (I − aaᵀ − nnᵀ)/r, a the
//! axis; plane: 0), for searches that use second derivatives.
double target_distance(const Target& target, const Eigen::RowVector3d& p, Eigen::RowVector3d* gradient = nullptr,
                       Eigen::Matrix3d* hessian = nullptr);

//! rms distance of the sampled surface of `net` to the target.
double rms_distance(const ControlNet& net, const Target& target);

struct Objective {
  std::string name;                                         //!< as given, e.g. "thin_plate" or "thin_plate+0.1*e3"
  std::vector<EnergyTerm> energy;                           //!< Σ weight·E(a, b)
  std::vector<std::pair<DiscreteEnergy, double>> discrete;  //!< Σ weight·(discrete energy), O(mn)
  double target_weight = 0;                                 //!< weight of the rms distance to `target`
  std::optional<Target> target;
};

//! The range of a term's weight, as coordinates are bounded by 1e60: the search divides the
//! weights by the largest (normalised_frame.h) but reports values in the caller's units, and
//! 1e300·e3 would overflow them near the optimum.
inline constexpr double kMinObjectiveWeight = 1e-60, kMaxObjectiveWeight = 1e60;

//! The named objectives (thin_plate, twist, dirichlet, e3, target; and discrete_twist,
//! discrete_dirichlet, discrete_thin_plate, which cost O(mn) for very large nets) and weighted sums:
//! "thin_plate", "e3+0.5*twist", "2*target+thin_plate". Returns nullopt for an unknown name
//! (`why` says which part); `target` still has to be set for objectives that use it.
std::optional<Objective> parse_objective(const std::string& text, std::string* why);

struct ObjectiveValue {
  double value = 0;
  double derivative = 0;  //!< along dN
};

//! Value at N and derivative along dN (dN has the degree of N and a zero boundary).
ObjectiveValue evaluate_objective(const Objective& objective, const ControlNet& N, const ControlNet& dN);

}  // namespace coons
