// The study's rows for B-spline boundaries (docs/math.md §10): the degree study elevates Bézier
// nets, which a B-spline net is not, so a B-spline boundary gets its own row at its own knots —
// the energies of the Greville Coons net (α = −1/4) and of the non-uniform Laplace net (α = 0),
// and the best α of the non-uniform family for each study objective (search_bspline_alpha).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/io/bspline_boundary_io.h"

namespace coons {

struct BSplineStudyInput {
  std::string file, name;
  BSplineInput sides;
};

struct BSplineStudyRow {
  std::string file, name;
  int degree_u = 0, degree_v = 0, count_u = 0, count_v = 0;  //!< of the compatible net
  std::vector<CompatibilityNote> notes;
  std::string solver;
  double thin_plate_coons = 0, thin_plate_laplace = 0;               //!< NaN when the solve failed
  std::vector<std::pair<std::string, AlphaSearchSummary>> searches;  //!< per objective
};

//! One row per input; `solver` "" for the automatic choice (auto_bspline_solver).
std::vector<BSplineStudyRow> run_bspline_study(const std::vector<BSplineStudyInput>& inputs,
                                               const std::vector<Objective>& objectives, const std::string& solver);

//! A markdown section "B-spline boundaries" (empty string when there are no rows).
std::string bspline_study_markdown(const std::vector<BSplineStudyRow>& rows);

//! The rows for results.json.
nlohmann::json bspline_study_json(const std::vector<BSplineStudyRow>& rows);

}  // namespace coons
