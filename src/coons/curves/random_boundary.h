// A seeded family of random smooth boundaries: four Bézier sides of a low degree p with shared
// corners, over the unit square (sizes: each side p + 1 by 3). The distribution (documented in
// docs/formats.md, "random-smooth"): the corners lie at (0,0), (1,0), (1,1), (0,1) in x, y with
// heights z uniform in [−height, height]; the inner control points of each side sit on the
// chord between its corners, plus a displacement uniform in [−height, height] in z and in
// [−wiggle, wiggle] in x and y. Low degree is low frequency: p is the smoothness parameter.
// Boundary k of the family with seed S draws from std::mt19937_64 seeded with
// std::seed_seq{S mod 2³², S div 2³², k}, each uniform being (g() >> 11)·2⁻⁵³ (not a
// std::*_distribution, whose output differs between standard libraries), so the family is the
// same everywhere and any boundary can be made alone (a shard of a study makes only its own).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "coons/net/control_net.h"

namespace coons {

struct RandomSmoothOptions {
  int side_degree = 3;  //!< p ≥ 1: the sides' degree (the study elevates them exactly)
  double height = 0.5;  //!< amplitude out of the plane
  double wiggle = 0.1;  //!< amplitude in the plane (below 1/(2p) keeps the sides simple)

  bool is_valid(std::string* why) const;
};

//! Boundary `index` of the family with `seed`: m = n = side_degree, named "random-smooth-S-k".
Boundary random_smooth_boundary(std::uint64_t seed, int index, const RandomSmoothOptions& options = {});

//! The displacement of random-smooth boundary `index`: its sides minus the flat unit square's
//! (corners at height 0, inner points on the chords), so it is shared at the corners and the
//! four sides of degree side_degree move in z by up to 2·`height` (the chord between two corner
//! heights plus its own), in x and y by up to `wiggle`.
Boundary random_smooth_displacement(std::uint64_t seed, int index, const RandomSmoothOptions& options = {});

//! Member `index` of the perturbed family of `base` (seed `seed`): base + amplitude·diag·D, with
//! diag the base's bounding-box diagonal and D random_smooth_displacement(seed, index, options);
//! both elevated exactly to degree (max(m, p), max(n, p)) for p = options.side_degree. Corners
//! stay as consistent as the base's (D's corners are shared exactly). Named "NAME-perturbed-S-k".
Boundary perturbed_boundary(const Boundary& base, double amplitude, std::uint64_t seed, int index,
                            const RandomSmoothOptions& options = {});

//! Boundaries first, first + 1, ..., first + count − 1 of the family.
std::vector<Boundary> random_smooth_family(std::uint64_t seed, int count, const RandomSmoothOptions& options = {},
                                           int first = 0);

}  // namespace coons
