// What `coons view` shares with `coons study --html`: reading three.js (Debian libjs-three) and the
// page of every shape of a study.
#pragma once

#include <string>
#include <vector>

#include "coons/io/write_files.h"
#include "coons/study/bspline_study.h"
#include "coons/study/study.h"
#include "solvers/registry.h"

namespace coons::cli {

//! The text of three.min.js at `path` (the one found at configure time by default); an InputError
//! naming --three-js and the Debian package libjs-three when there is none.
std::string read_three_js(const std::string& path);

//! `coons study --html`: writes pages/STEM.html into `out` for every shape (its α slider, the C1
//! weight slider where it has two data rings), every triangle (its c slider) and every B-spline
//! boundary (its non-uniform α family up to its definite end), 51 values and 25 × 25 samples each,
//! and returns the report's section linking them.
std::string write_study_pages(const StudyResult& result, const std::vector<StudyInput>& inputs,
                              const std::vector<BSplineStudyInput>& bsplines, OutputSet& out,
                              const std::string& three_js, const solvers::SolverInfo* solver);

}  // namespace coons::cli
