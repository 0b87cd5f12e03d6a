// A mask problem on a full net: which points are data and which are solved for, and its checks.
//
//   net    (m+1)×(n+1) points; the values of free points are ignored (any start value).
//   rings  the number of outer rings of the net that are data (default 1).
//   free   optional (m+1)×(n+1) 0/1 grid of the points to solve for; every other point is data.
//          Without it, every point inside the rings is free. With it, `free` decides, as the
//          contract's example does (rings 2 with free points on the second ring): a point of
//          the data rings may be free when its stencil stays in the net; `rings` then only says
//          how many rings the mask needs (rings ≥ r).
//
// check_stencil_problem lists what makes a problem unusable for a stencil of radius r:
//   "free"        the grid has the wrong shape;
//   "rings"       rings < 0, or rings < r (a 5×5 mask needs two data rings);
//   "free[i][j]"  a free point whose stencil leaves the net, or a
//                 free point among those on which the system is singular ("decouple").
// Singularity: the free points are split into the connected components of the stencil's
// coupling graph (two free points are coupled when the weight between them is non-zero); the
// system is block diagonal over them. When the stencil's symbol is ≥ 0 (stencil.h:
// symbol_nonnegative — every named mask with α ∈ [−1/4, 1/4] and the whole C1 family) every
// block is positive definite and nothing is computed. Otherwise each component is checked
// numerically: up to `dense_limit` points by a dense symmetric eigen-decomposition (singular when
// |λ|min ≤ singular_tolerance·|λ|max), larger ones by a sparse LU of the component and inverse
// iteration towards the smallest |λ|. The eigenvector of that λ is the null vector; the points
// where it is ≥ 0.1 of its largest entry are named as the ones that decouple.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "coons/mask/stencil.h"
#include "coons/net/control_net.h"

namespace coons {

//! (m+1) × (n+1): true where the point is solved for.
using FreeGrid = Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>;

struct StencilProblem {
  ControlNet net;
  int rings = 1;
  FreeGrid free;  //!< empty: every point inside the rings
};

//! The free points of a problem: `free` when given, else the points inside the rings.
//! Precondition: `free` is empty or of the net's shape.
FreeGrid free_points(const StencilProblem& problem);

//! The centre of the bounding box of the data points (those not free) that one of `stencils`
//! couples to a free point, by a non-zero weight (zero when there are none): the solvers solve
//! for the net moved there (solve_stencil_net.h). Data that couple to nothing do not enter the
//! system: counted, a corner at 1e6 beside data of size 1e-3 (α = 0 leaves corners out) moved the
//! centre to 5e5 and cost the net six digits, and cg's reported residual four.
Eigen::RowVector3d data_centre(const StencilProblem& problem, const std::vector<Stencil>& stencils);

//! A problem with the whole frame of `rings` rings fixed and the inside free (the classical case).
StencilProblem rings_problem(ControlNet net, int rings);

struct ProblemIssue {
  std::string field;   //!< "rings", "free" or "free[i][j]"
  int i = -1, j = -1;  //!< the point, when the issue is about one
  std::string reason;  //!< one line, no trailing period
};

struct ProblemCheckOptions {
  bool check_singular = true;         //!< also check that the system is non-singular
  int dense_limit = 400;              //!< components up to this size are checked densely
  double singular_tolerance = 1e-10;  //!< relative size of the smallest |eigenvalue| taken as zero
  int max_named_points = 8;           //!< list at most this many points in a reason

  bool is_valid(std::string* why) const;
};

//! Every issue, structural ones first (shape, rings, points); the singularity check runs only
//! when there is no structural issue. Empty: the problem can be assembled and solved. Options
//! that ProblemCheckOptions::is_valid rejects throw std::invalid_argument (the caller's error).
std::vector<ProblemIssue> check_stencil_problem(const StencilProblem& problem, const Stencil& stencil,
                                                const ProblemCheckOptions& options = {});

}  // namespace coons
