// The study's report: a self-contained Markdown file (report.md) with its figures (PNG through
// gnuplot, in a figures/ folder beside it). Every number it prints is in results.json too.
#pragma once

#include <string>
#include <vector>

#include "coons/study/provenance.h"
#include "coons/study/study.h"

namespace coons {

//! Figure files of a study (names relative to the report's folder) and why any could not be made.
struct StudyFigure {
  std::string file;   //!< e.g. figures/dome_energies.png
  std::string error;  //!< empty when the figure was made
};
struct StudyFigures {
  std::vector<StudyFigure> energies, nets;  //!< per shape, in the order of StudyResult::shapes
  StudyFigure alpha_vs_degree, mu_vs_degree;
};

//! File stems of the shapes, made safe for file names and distinct (a repeated name gets its
//! degree, then a counter).
std::vector<std::string> shape_file_stems(const StudyResult& result);

//! Draws every figure of the report: `path_of(file)` gives where to write a figure whose name
//! relative to the report is `file` (e.g. a staging name of an output set).
StudyFigures plot_study_figures(const StudyResult& result,
                                const std::function<std::string(const std::string&)>& path_of);

//! report.md.
std::string study_report_markdown(const StudyResult& result, const Provenance& provenance, const StudyFigures& figures);

}  // namespace coons
