// One net from a boundary, by the method asked for, and its report (docs/formats.md, `coons
// solve`): the mask, μ, the solver block, the net and every metric. Shared by solve, export and
// batch.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>

#include "coons/mask/mask9.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons {

enum class NetMethod { kAlpha, kCoons, kHermiteCoons };
const char* to_string(NetMethod method);

struct NetOutcome {
  ControlNet net;
  std::optional<solvers::SolveSummary> summary;  //!< the alpha method only
};

//! kAlpha solves the mask system with `solver` (required then); the others are closed forms.
NetOutcome make_net(const Boundary& boundary, NetMethod method, const Mask9& mask, const solvers::SolverInfo* solver,
                    const solvers::SolverOptions& options = {});

//! The solve report without a timing block; `mu` as given on the command line, if it was. With
//! `with_net` false a successful net is left out of it, for the caller to write (write_net_json).
nlohmann::json net_report(const Boundary& boundary, NetMethod method, const Mask9& mask, const NetOutcome& outcome,
                          const std::optional<double>& mu, bool solver_picked_automatically, bool with_net = true);

}  // namespace coons
