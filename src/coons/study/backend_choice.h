// Which backend a search, sweep or study uses on a boundary: the one asked for, or the one that
// `auto` stands for on the α family's operator (the fastest applicable one built in; a general one
// when the range leaves the positive definite α ∈ [−1/4, 1/4]).
#pragma once

#include "coons/net/control_net.h"
#include "solvers/registry.h"

namespace coons {

//! `requested` nullptr means auto. Throws InputError ("--solver") when the requested backend
//! needs a positive definite system and `indefinite` says the range leaves it.
const solvers::SolverInfo& search_backend(const solvers::SolverInfo* requested, const Boundary& boundary,
                                          bool indefinite);

//! The backend of the C1 family's weight search (a 5×5 stencil, positive definite for w ∈ [0, 1]):
//! `requested` when it works from the assembled matrix, else (and for auto, nullptr) cholmod when
//! built, else eigen-ldlt. `fallback` (false) makes a requested backend without a matrix an
//! InputError ("--solver") instead.
const solvers::SolverInfo& weight_search_backend(const solvers::SolverInfo* requested, bool fallback);

}  // namespace coons
