// The conclusions of the α study's report (experiment E01), computed from its tables: a claim is
// printed only when the numbers support it, otherwise the measured values take its place.
// The first sentence is the report's headline (scripts/run_experiment.sh makes it the README's title).
#pragma once

#include <string>
#include <vector>

#include "coons/study/study.h"

namespace coons {

//! The sentences, headline first: whether one α is best for every shape (per objective, at the
//! shapes' own degrees), which shapes are flat, the best fit to each target, and whether μ* stays
//! put across the degrees of the study.
std::vector<std::string> study_conclusions(const StudyResult& result, double same_alpha_tolerance = 0.05,
                                           double constant_mu_tolerance = 0.05);

//! "## 5. Conclusions, computed from the tables" with the sentences as bullets.
std::string study_conclusions_markdown(const StudyResult& result);

}  // namespace coons
