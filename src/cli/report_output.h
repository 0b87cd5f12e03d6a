// Printing a report that holds a whole net (`solve`): the net is formatted straight to standard
// output in pieces (write_net_json), never built as a JSON array, and the report's "timing" block
// is closed after that write, so that it includes a "write" phase.
#pragma once

#include <nlohmann/json.hpp>

#include "common.h"
#include "coons/net/control_net.h"

namespace coons::cli {

//! Prints `report` pretty-printed (2 spaces; with points_inline, each array of numbers on one
//! line, as dump_points_inline), with "net" = `net` unless `net` is null (then the report's own
//! "net", if any) and "timing" = the phases' seconds, the "write" phase included.
//! A failed write is an InputError ("<stdout>: write failed: REASON"), as for print_json.
void print_net_report(nlohmann::json report, const ControlNet* net, Phases& phases, bool points_inline = false);

}  // namespace coons::cli
