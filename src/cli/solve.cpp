// `coons solve BOUNDARY`: one net, one JSON report (docs/formats.md).
#include <memory>

#include "coons/io/input_error.h"
#include "coons/io/tri_boundary_io.h"
#include "registry.h"
#include "report_output.h"
#include "tri_commands.h"

namespace coons::cli {

namespace {

struct SolveRequest {
  std::string boundary;
  NetRequest net;
  GlobalOptions global;
};

int run_solve(const SolveRequest& request) {
  if (is_triangle_file(request.boundary)) return run_tri_solve(request.boundary, request.net, request.global);
  Phases phases("solve");
  phases.start("read");
  const BoundaryFile input = read_input(request.boundary, request.net.corner_tolerance);
  const ResolvedRequest r = resolve(request.net, input.boundary, request.boundary);
  check_net_memory(request.global, input.boundary, r.solver, request.boundary);
  phases.start("solve");  // assembling included
  const NetOutcome outcome = make_net(input.boundary, r);
  phases.start("metrics");
  const nlohmann::json report =
      net_report(input.boundary, r.method, r.mask, outcome, request.net.mu, r.picked_automatically, false);
  const bool ok = !outcome.summary || outcome.summary->ok();
  print_net_report(report, ok ? &outcome.net : nullptr, phases);  // the write phase, then timing
  if (outcome.summary && !outcome.summary->ok()) {
    print_solver_failure(request.boundary, *outcome.summary);
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace

void register_solve(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<SolveRequest>();
  auto* cmd = app.add_subcommand("solve", "solve one boundary; prints one JSON report (docs/formats.md)");
  cmd->add_option("BOUNDARY", request->boundary, "boundary JSON file (docs/formats.md)")->required();
  add_net_options(*cmd, request->net);
  add_memory_option(*cmd, request->global);
  set_example(*cmd, "coons solve data/boundaries/dome.json --alpha -0.2 --solver eigen-ldlt");
  registry.add(cmd, [request] { return run_solve(*request); });
}

}  // namespace coons::cli
