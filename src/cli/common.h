// What the commands of the `coons` CLI share: exit codes, how a net is requested on the command
// line, and the translation of those strings into enums, masks and backend names.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "coons/io/boundary_io.h"
#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons::cli {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

enum class Method { kAlpha, kCoons, kHermiteCoons };

struct NetRequest {
  std::string method = "alpha";
  double alpha = -0.25;
  std::optional<double> mu;
  std::string solver = "auto";
  bool allow_indefinite = false;
  double corner_tolerance = 1e-9;
  double tolerance = 1e-12;
  int max_iterations = 0;
  double omega = 1.0;
};

struct ResolvedRequest {
  Method method = Method::kAlpha;
  Mask9 mask;
  std::string solver;  // concrete backend (alpha method only)
  bool picked_automatically = false;  // --solver auto chose it
  solvers::SolverOptions options;
};

struct NetOutcome {
  ControlNet net;
  std::optional<solvers::SolveSummary> summary;  // alpha method only
};

const char* to_string(Method m);
void add_net_options(CLI::App& cmd, NetRequest& r);
//! Checks the request against the boundary; throws InputError naming the bad option.
ResolvedRequest resolve(const NetRequest& r, const Boundary& boundary, const std::string& source);
NetOutcome make_net(const Boundary& boundary, const ResolvedRequest& r);
nlohmann::json solve_report(const Boundary& boundary, const ResolvedRequest& r, const NetOutcome& outcome,
                            const std::optional<double>& mu);
BoundaryFile read_input(const std::string& path, const NetRequest& r);
//! Files as given, folders expanded to their *.json files (sorted).
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

}  // namespace coons::cli
