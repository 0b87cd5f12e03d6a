// What the search commands (search-alpha, sweep, study, degree-limit, view) take from the command
// line besides plain numbers: the `--target` specification (hermite-coons | coons | NET.json |
// sphere:cx,cy,cz,r | cylinder:px,py,pz,dx,dy,dz,r | plane:px,py,pz,nx,ny,nz), checked number by
// number, and whether the `--solver` asked for can serve the search (bad input naming --solver
// when not). Built as a library of its own so that the tests and the fuzzers call it directly.
#pragma once

#include <optional>
#include <string>

#include "coons/alpha/objective.h"
#include "coons/net/control_net.h"
#include "solvers/registry.h"

namespace coons::cli {

//! A --target specification; an empty one means the boundary file's own target (or none). Throws
//! InputError naming --target for a bad number or direction, and the file for a bad target file.
std::optional<Target> resolve_target(const std::string& spec, const std::string& boundary_path,
                                     const Boundary& boundary, int samples);

//! A `--solver` that cannot serve the α searches on `boundary` (backend_choice.h:
//! check_search_backend) is bad input naming --solver; auto (nullptr) always serves. `where`, when
//! not empty, names the boundary file in the message.
void require_search_backend(const solvers::SolverInfo* requested, const Boundary& boundary, bool indefinite,
                            const std::string& where = "");

//! The same for the C1 family's weight search (backend_choice.h: check_weight_search_backend).
void require_weight_search_backend(const solvers::SolverInfo* requested);

//! `requested` (nullptr for auto), or bad input naming --solver when it works from a grid stencil
//! only: "NAME works from the grid stencil only; " followed by `needs` (what needs an assembled
//! matrix), one wording for every command that refuses such a backend.
const solvers::SolverInfo* require_matrix_backend(const solvers::SolverInfo* requested, const std::string& needs);

//! `needs` of require_matrix_backend for the non-uniform mask systems of a B-spline boundary
//! (solve, export, search-alpha, view).
extern const char* const kBSplineNeedsMatrix;

}  // namespace coons::cli
