// The per-shape α study's results (study.h, tri_study.h) as JSON and back, losslessly: the record
// of a sharded boundary-file study (docs/formats.md, "Sharded studies") carries one input's part
// of a StudyResult so that a merge rebuilds the result an unsharded run has and writes the same
// report. Doubles are written in nlohmann's shortest round-trip form (exact); non-finite ones as
// the strings "inf", "-inf", "nan". Timings (seconds) are carried too but compare in no report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "coons/study/bspline_study.h"
#include "coons/study/study.h"

namespace coons {

//! {"shapes", "laws", "fit_deviations", "references", "triangles"} of a (partial) study result.
nlohmann::json study_part_json(const StudyResult& part);

//! The part read back into `into` (appended to its lists); throws InputError(`where`, FIELD, …).
void append_study_part(const nlohmann::json& part, const std::string& where, StudyResult* into);

//! The B-spline rows of a study (bspline_study.h), losslessly: the record of a B-spline file's task.
nlohmann::json bspline_rows_json(const std::vector<BSplineStudyRow>& rows);

//! Those rows read back, appended to `into`; throws InputError(`where`, "bspline", …).
void append_bspline_rows(const nlohmann::json& rows, const std::string& where, std::vector<BSplineStudyRow>* into);

}  // namespace coons
