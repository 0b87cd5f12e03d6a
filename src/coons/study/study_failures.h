// What failed in a study: every solve of the per-shape study (the α*, μ* and w* searches, the
// objective at α = −1/4 and 0, the energy curves, the degree cells, the reference rows and best
// fit), of the triangle rows, of the B-spline rows and of a family study, one short phrase per failure. The shape
// entries' solver status in results.json and the command's exit status (3 when anything failed)
// are derived from these. Sizes: one entry per failure.
#pragma once

#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/study/alpha_family.h"
#include "coons/study/bspline_study.h"
#include "coons/study/study.h"

namespace coons {

//! Whether a search's verdict rests on failed solves: solver_failed, failed_region (some
//! evaluations failed next to the optimum) or not_applicable (the backend cannot take the system).
bool search_failed(const AlphaSearchSummary& s);

//! The failures among one shape's solves at its own degree (its section-1 row and energy curves):
//! phrases such as "thin_plate: μ* failed_region", empty when every solve succeeded.
std::vector<std::string> shape_failures(const ShapeEntry& shape);

struct StudyFailure {
  std::string file;  //!< the input file ("" when the result does not name it)
  std::string what;  //!< "oscillating: thin_plate: the objective at α = −1/4 failed"
};

//! Every failure of the study, in the report's order: shapes, degree cells, reference tables,
//! triangles. A degree cell or reference table names its file through the shape of that name.
std::vector<StudyFailure> study_failures(const StudyResult& r);

//! The failures of the B-spline rows (the energies at α = −1/4 and 0, the searches).
std::vector<StudyFailure> bspline_study_failures(const std::vector<BSplineStudyRow>& rows);

//! The failures of a family study (`coons study --family`), one per cell (degree × objective) that
//! has them: its α* searches that failed, its failed evaluations on the best-single-α grid. The
//! file is "" (the boundaries are made, not read).
std::vector<StudyFailure> family_failures(const AlphaFamilyResult& r);

}  // namespace coons
