// The triangles of the α study: for every triangular boundary (docs/formats.md, "Triangular
// boundary files") the optimal member c of the triangular mask family (tri_mask.h) per objective
// that exists for triangles (thin_plate, e3, dirichlet, twist, and the fit to the file's target), at
// the file's own degree and at every degree of the study at or above it (the sides elevated
// exactly: a triangle's boundary curves do not change), with the objective at c = −1/6 (quadratic
// precision) and c = 0 (the triangular Laplace mask) for comparison. Flat objectives and optima on
// a bound are reported as such (search_tri_c). Based on: G. Farin, D. Hansford, Discrete Coons
// patches, CAGD 16 (1999) 691–700.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/tri/tri_net.h"
#include "solvers/registry.h"

namespace coons {

//! One triangular boundary of the study.
struct TriStudyInput {
  std::string file;
  tri::TriBoundary boundary;
  std::optional<Target> target;  //!< the file's "target": adds the `target` objective
};

//! Reads a triangular boundary file with its target (InputError on any fault).
TriStudyInput read_tri_study_input(const std::string& path, double corner_tolerance = 1e-9);

//! The objectives every triangle is studied for: thin_plate, e3, dirichlet, twist (and target when the
//! file has one).
std::vector<std::string> tri_study_objectives(const TriStudyInput& input);

struct TriStudyCell {
  int degree = 0;
  double lower = 0, upper = 0;  //!< the search bounds at this degree (default_tri_bounds)
  AlphaSearchSummary c;         //!< the summary's parameter is c*
  double quadratic = 0;         //!< the objective at c = −1/6
  double laplace = 0;           //!< the objective at c = 0
};

struct TriStudyRow {
  std::string objective;
  std::vector<TriStudyCell> cells;  //!< the file's own degree first, then the study's higher degrees
};

struct TriStudyEntry {
  std::string file;
  tri::TriBoundary boundary;
  std::string solver;
  bool solver_picked_automatically = false;
  std::vector<TriStudyRow> rows;
};

//! Searches every objective of every triangle at its own degree and at each of `degrees` above it;
//! `solver` nullptr: the default triangular backend (an LU).
std::vector<TriStudyEntry> run_tri_study(const std::vector<TriStudyInput>& inputs, const std::vector<int>& degrees,
                                         const solvers::SolverInfo* solver,
                                         const std::function<void(const std::string&)>& progress = {});

//! The results.json entries, one per triangle: {"kind": "triangle", "boundary", "degree", "file",
//! "solver", "objectives": {NAME: [{"degree", "c", "value", "flat", "at_bound", "local_minima",
//! "status", "bounds", "at_quadratic", "at_laplace"}, …]}}.
nlohmann::json tri_study_results_json(const std::vector<TriStudyEntry>& entries);

//! The report's section on triangles (empty when there are none): one table per triangle.
std::string tri_study_markdown(const std::vector<TriStudyEntry>& entries, const std::string& section_number);

}  // namespace coons
