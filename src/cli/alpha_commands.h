// The commands of the α study: search-alpha (one boundary, one objective), sweep (a grid of α or
// μ with every metric) and study (the toolkit's main job: every boundary at many degrees, with a
// self-contained report).
#pragma once

#include <string>
#include <vector>

#include "common.h"

namespace coons::cli {

struct SearchRequest {
  std::string objective;
  std::string parameter = "alpha";  //!< alpha | mu | alpha-gamma
  std::optional<double> lower, upper;
  bool allow_indefinite = false;
  std::string target;               //!< hermite-coons | coons | FILE | sphere:… | cylinder:… | plane:…
  int scan_points = 9;
  int samples = 41;
};

struct SweepRequest {
  std::string parameter = "alpha";  //!< alpha | mu
  double from = -0.25, to = 0.25;
  int count = 51;
  std::string out_dir = ".";
  std::string target;
  int samples = 41;
};

struct StudyRequest {
  std::vector<std::string> inputs;
  std::vector<int> degrees = {3, 4, 6, 8, 12, 16};
  std::string out_dir = "out/study";
  std::string command_line;
};

struct RefitRequest {
  std::vector<int> degree;  //!< M N
  std::string out;
};

void add_refit_options(CLI::App& cmd, RefitRequest& r);
//! The boundary at another degree: refitted from its "curves" when it has them, else elevated.
int cmd_refit(const std::string& path, const NetRequest& net, const RefitRequest& request);

void add_search_options(CLI::App& cmd, SearchRequest& r);
void add_sweep_options(CLI::App& cmd, SweepRequest& r);
void add_study_options(CLI::App& cmd, StudyRequest& r);

int cmd_search_alpha(const std::string& path, const NetRequest& net, const SearchRequest& request);
int cmd_sweep(const std::string& path, const NetRequest& net, const SweepRequest& request);
int cmd_study(const StudyRequest& request, const NetRequest& net);

}  // namespace coons::cli
