// JSON forms of nets, boundaries and metrics (docs/formats.md). Numbers are written so that they read
// back exactly (nlohmann's shortest round-trip doubles).
#pragma once

#include <nlohmann/json.hpp>

#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

//! m+1 rows of n+1 [x, y, z] points: net[i][j] = b[i][j].
nlohmann::json net_to_json(const ControlNet& net);

//! A boundary file (docs/formats.md) holding the four sides.
nlohmann::json boundary_to_json(const Boundary& boundary);

nlohmann::json metrics_to_json(const NetMetrics& metrics);

//! The `solver` block of a solve report; non-finite numbers become null.
nlohmann::json summary_to_json(const solvers::SolveSummary& summary);

//! A finite double as a number, anything else as null (JSON has no NaN or infinity).
nlohmann::json number_or_null(double x);

}  // namespace coons
