// The input edge of stencil problems: a stencil from its JSON description, the free grid of a
// "net" boundary file, and the problem checks as InputError ("FILE: FIELD: reason").
//
// Stencil file (docs/formats.md, masks `file:PATH`):  {"weights": [[...], ...]}
//   3 or 5 rows of as many numbers; rows run along i (u), columns along j (v); symmetric:
//   weights[r][c] = weights[R−1−r][R−1−c] (what makes the system matrix symmetric); the centre is
//   implied so that the weights sum to 0 (affine invariance): write null, 0 or that value there.
//   The stencil is then normalised to centre 1 (stencil.h). Errors name the field and the index:
//   "weights[1][3]: breaks the symmetry ...".
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"

namespace coons {

//! Throws InputError(file, "weights…", reason) on anything but a valid stencil.
Stencil stencil_from_json(const nlohmann::json& doc, const std::string& file);

//! The `free` field (a 0/1 grid of (m+1) rows of (n+1)); throws InputError(file, "free…", reason).
FreeGrid free_grid_from_json(const nlohmann::json& free, int m, int n, const std::string& file);

//! Throws InputError(file, issue.field, issue.reason) for the first issue of check_stencil_problem.
void require_valid_problem(const StencilProblem& problem, const Stencil& stencil, const std::string& file,
                           const ProblemCheckOptions& options = {});

}  // namespace coons
