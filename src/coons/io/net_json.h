// JSON forms of nets, boundaries and metrics (docs/formats.md). Numbers are written so that they read
// back exactly (nlohmann's shortest round-trip doubles).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string_view>

#include "coons/metrics/energies.h"
#include "coons/net/control_net.h"
#include "solvers/linear_solver.h"

namespace coons {

//! m+1 rows of n+1 [x, y, z] points: net[i][j] = b[i][j].
nlohmann::json net_to_json(const ControlNet& net);

//! The same array as JSON text, without building it: pretty-printed with 2 spaces as if nested
//! `level` deep, one point per line ("[x, y, z]"), every number in its shortest round-trip form
//! (fmt), with ".0" on integral values as nlohmann's dump writes them. Handed to `sink` in pieces of
//! about 1 MiB. A non-finite coordinate is written as null.
void write_net_json(const ControlNet& net, int level, const std::function<void(std::string_view)>& sink);

//! A boundary file (docs/formats.md) holding the four sides.
nlohmann::json boundary_to_json(const Boundary& boundary);

nlohmann::json metrics_to_json(const NetMetrics& metrics);

//! The `solver` block of a solve report; non-finite numbers become null.
nlohmann::json summary_to_json(const solvers::SolveSummary& summary);

//! A finite double as a number, anything else as null (JSON has no NaN or infinity).
nlohmann::json number_or_null(double x);

//! number_or_null of the value, null when there is none.
nlohmann::json optional_number(const std::optional<double>& x);

}  // namespace coons
