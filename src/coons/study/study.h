// The α study, the toolkit's main job: for every boundary, the optimal mask parameter (α* and μ*)
// of each objective at its own degree with the Coons and Laplace values for comparison and energy
// curves over α; the optimum at many degrees (refitted from the analytic sides, or elevated
// exactly) with the degree law α* + 1/4 ≈ c/n²; and, for every boundary that carries a target, a
// reference table (S(½,½).z, thin plate, Dirichlet, rms distance at α = −1/4, −1/5, −1/10, 0) and
// the α that fits the target best; for every boundary with two data rings ("ribbons", or a net
// with "rings" ≥ 2) the best weight w* of the 5×5 C1 family beside α* (family_search.h). Usable without the command
// line: run_study computes, the report functions (report_markdown.h) write. Based on: G. Farin, D. Hansford, Discrete
// Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/curves/curve.h"
#include "coons/io/boundary_io.h"
#include "coons/io/misspelt_fields.h"
#include "coons/mask/stencil_problem.h"
#include "coons/study/degree_law.h"
#include "coons/study/sweep.h"
#include "coons/study/tri_study.h"
#include "solvers/registry.h"

namespace coons {

//! One boundary of the study, read and checked before anything is computed.
struct StudyInput {
  std::string file;  //!< as given (recorded in results.json)
  Boundary boundary;
  std::optional<std::vector<Curve>> curves;  //!< analytic sides: refitted at each degree
  std::optional<Target> target;              //!< reference table and best-fit α
  std::optional<StencilProblem> two_rings;   //!< two data rings: the C1 family's column
  std::string one_ring;                      //!< without them: why, short ("one data ring, no ribbons")
  std::vector<MisspeltField> misspelt;       //!< BoundaryFile::misspelt, for the command to warn about
};

//! Reads a boundary file with its curves and target; every input error is thrown here.
StudyInput read_study_input(const std::string& path, const BoundaryReadOptions& options = {});
//! The same from the file at path already read as `file` (the commands that first look whether it
//! is a B-spline boundary): reads only its curves and target again.
StudyInput read_study_input(const std::string& path, const BoundaryFile& file);

struct StudyOptions {
  std::vector<int> degrees = {3, 4, 6, 8, 12, 16};  //!< each in [2, 200], increasing
  std::vector<Objective> objectives;                //!< empty: thin_plate and e3
  const solvers::SolverInfo* solver =
      nullptr;            //!< nullptr: auto, per boundary and degree; else one check_search_backend accepts
  int curve_points = 41;  //!< α values of the energy curves
  std::vector<double> reference_alphas = {-0.25, -0.2, -0.1, 0.0};
  //! The weight searches' backend: `solver` when it works from the matrix, else cholmod or
  //! eigen-ldlt (backend_choice.h: weight_search_backend).

  bool is_valid(std::string* why) const;
};

//! The objectives a study uses when none are given: thin_plate and e3.
std::vector<Objective> default_study_objectives();

struct ShapeOptimum {  //!< one objective at the shape's own degree
  std::string objective;
  AlphaSearchSummary alpha;       //!< α*
  AlphaSearchSummary mu;          //!< μ* (parameter in μ units); not searched when m or n is 1
  double coons = 0, laplace = 0;  //!< the objective at α = −1/4 and α = 0
  //! w* of the C1 family and its value; absent when the input has one data ring
  std::optional<AlphaSearchSummary> weight;
};

struct ShapeEntry {
  std::string file;
  Boundary boundary;
  std::string solver;  //!< the backend of its searches
  bool solver_picked_automatically = false;
  std::vector<ShapeOptimum> optima;
  std::string weight_solver;     //!< the backend of the weight searches (two data rings only)
  std::string one_ring;          //!< why there are none (StudyInput::one_ring)
  std::vector<SweepRow> curves;  //!< energies on the α grid
  std::vector<std::pair<std::string, ControlNet>> pictures;  //!< Coons, Laplace, thin-plate optimum
};

struct DegreeCell {
  int degree = 0;
  AlphaSearchSummary alpha, mu;  //!< mu.parameter in μ units
};

struct DegreeLawEntry {
  std::string boundary, objective;
  std::vector<DegreeCell> cells;                 //!< the degrees the shape has (refitted or elevated)
  std::vector<std::pair<int, double>> interior;  //!< (degree, α*) with an interior optimum
  std::optional<DegreeLawFit> fit;
};

struct FitDeviationEntry {  //!< shapes given by curves: deviation of the refitted sides per degree
  std::string boundary;
  std::vector<std::pair<int, double>> max_deviation;
};

struct ReferenceRow {
  double alpha = 0, center_z = 0, thin_plate = 0, dirichlet = 0, rms_target = 0;
};

struct ReferenceTable {
  std::string boundary;
  int m = 0, n = 0;
  std::vector<ReferenceRow> rows;
  AlphaSearchSummary best;  //!< the α of least rms distance to the target
  double coons_rms = 0;     //!< rms distance of the Coons net
};

struct StudyResult {
  std::vector<int> degrees;
  std::vector<std::string> objectives;
  std::vector<ShapeEntry> shapes;
  std::vector<DegreeLawEntry> laws;
  std::vector<FitDeviationEntry> fit_deviations;
  std::vector<ReferenceTable> references;
  std::vector<TriStudyEntry> triangles;  //!< triangular boundaries (run_tri_study)
};

//! Everything the report shows; `progress` (optional) hears a short line per finished step.
StudyResult run_study(const std::vector<StudyInput>& inputs, const StudyOptions& options,
                      const std::function<void(const std::string&)>& progress = {});

//! results.json: one entry per shape ("kind": "shape"), per shape and objective over the degrees
//! ("degree_law"), per refitted shape ("fit_deviation"), per target ("reference_table") and per
//! triangular boundary ("triangle", tri_study.h); every number the report prints.
nlohmann::json study_results_json(const StudyResult& result);

//! The μ search of the study: μ ∈ [0, 1000·mn] on the compressed scale, reported in μ units.
AlphaSearchSummary study_search_mu(const Boundary& boundary, const Objective& objective,
                                   const solvers::SolverInfo& solver);

}  // namespace coons
