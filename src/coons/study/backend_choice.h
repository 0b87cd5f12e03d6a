// Which backend a search, sweep or study uses on a boundary: the one asked for, or the one that
// `auto` stands for on the α family's operator (the fastest applicable one built in; a general one
// when the range leaves the positive definite α ∈ [−1/4, 1/4]). Whether a requested backend can
// serve is a separate check, so that the caller decides what a refusal is (the CLI: bad input).
#pragma once

#include <string>

#include "coons/net/control_net.h"
#include "solvers/registry.h"

namespace coons {

//! Whether a requested backend can serve a search; `reason` is empty when it can.
struct SearchBackendCheck {
  bool applicable = false;
  std::string reason;
};

//! Whether `requested` serves the α searches on `boundary`: it must take indefinite systems when
//! `indefinite` (the range leaves [−1/4, 1/4]), and a grid-stencil backend must solve the 3×3 α
//! family (separable-banded takes only α = −1/4 and fast5 only 5×5 stencils).
SearchBackendCheck check_search_backend(const solvers::SolverInfo& requested, const Boundary& boundary,
                                        bool indefinite);

//! `requested` as given, or (nullptr: auto) the fastest applicable backend on the α family of
//! `boundary`, eigen-lu where that one needs a definite system and `indefinite` says it may not be.
//! Precondition: check_search_backend accepts `requested` (the CLI checks --solver before any
//! search); a refused one is the caller's error, std::invalid_argument with the reason. (Through
//! the sine-basis evaluator a search would otherwise answer under its name without solving with it.)
const solvers::SolverInfo& search_backend(const solvers::SolverInfo* requested, const Boundary& boundary,
                                          bool indefinite);

//! Whether `requested` serves the C1 family's weight search (a 5×5 stencil, positive definite for
//! w ∈ [0, 1]), which refills one assembled system per evaluation: it must work from the matrix.
SearchBackendCheck check_weight_search_backend(const solvers::SolverInfo& requested);

//! The backend of the weight search: `requested` when it works from the assembled matrix, else
//! (and for auto, nullptr) cholmod when built, else eigen-ldlt.
const solvers::SolverInfo& weight_search_backend(const solvers::SolverInfo* requested);

}  // namespace coons
