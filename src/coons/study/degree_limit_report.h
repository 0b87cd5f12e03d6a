// The report of `coons degree-limit --out DIR` (experiment E02): a headline and conclusions
// computed from the measurements — a claim is printed only when the numbers support it, otherwise
// the measured value is printed in its place — tables of μ*(n), its limit, rate, fits and the
// continuum optimum, the spreads of the three parametrisations, and log-axis figures with the
// continuum optimum drawn as a line.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "coons/study/degree_limit_study.h"
#include "coons/study/provenance.h"
#include "coons/study/report_markdown.h"

namespace coons {

//! Thresholds of the claims (relative).
struct ClaimThresholds {
  double constant = 0.05;                 //!< "μ* does not depend on the degree": max/min − 1 ≤ this
  double limit_error = kLimitClaimError;  //!< "μ* converges to μ∞": error ≤ this·|μ∞| (limit_claimed)
  double continuum_gap = 0.05;            //!< "μ*(n) tends to μ_c": |μ∞ − μ_c| ≤ max(this·μ_c, 2·error)
};

//! The sentences about one entry, each either a supported claim or the measured fact in its place.
std::vector<std::string> degree_limit_conclusions(const DegreeLimitEntry& entry, const ClaimThresholds& t = {});

//! The headline over all entries of one objective (e.g. "thin_plate"): a claim all of them
//! support, or the measured drift.
std::string degree_limit_headline(const std::vector<DegreeLimitEntry>& entries, const std::string& objective,
                                  const ClaimThresholds& t = {});

//! The two figure files of an objective, relative to the output folder: μ*(n) against n, and
//! |μ*(n) − μ_c| (plot_degree_limit_figures; a run that draws neither removes an earlier run's).
std::array<std::string, 2> degree_limit_figure_files(const std::string& objective);

//! figures/mu_vs_degree_OBJECTIVE.png (μ*(n) and μ_c, log axes) and
//! figures/mu_gap_vs_degree_OBJECTIVE.png (|μ*(n) − μ_c|, log axes), per objective.
std::vector<StudyFigure> plot_degree_limit_figures(const std::vector<DegreeLimitEntry>& entries,
                                                   const std::function<std::string(const std::string&)>& path_of);

std::string degree_limit_report_markdown(const std::vector<DegreeLimitEntry>& entries,
                                         const DegreeLimitStudyOptions& options, const Provenance& provenance,
                                         const std::vector<StudyFigure>& figures);

}  // namespace coons
