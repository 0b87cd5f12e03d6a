// `coons solve BOUNDARY`: one net, one JSON report (docs/formats.md).
#include <memory>

#include "bspline_commands.h"
#include "coons/io/input_error.h"
#include "coons/io/tri_boundary_io.h"
#include "net_request.h"
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

// Beyond the classical problem: two data rings, a free grid, or a mask other than alpha.
int run_stencil_solve(const SolveRequest& request, const BoundaryFile& input, const ResolvedRequest& r,
                      Phases& phases) {
  phases.start("solve");  // checks and assembling included
  const StencilRun run = solve_stencil_request(input, r, request.net, request.global, request.boundary);
  phases.start("metrics");
  const nlohmann::json report = stencil_report(input, r, run, request.net.mu);
  const bool ok = run.result.summary.ok();
  print_net_report(report, ok ? &run.result.net : nullptr, phases);  // one point per line; write, then timing
  if (!ok) {
    print_solver_failure(request.boundary, run.result.summary);
    return kExitSolverFailed;
  }
  print_solver_warning(request.boundary, run.result.summary);
  return kExitOk;
}

int run_solve(const SolveRequest& request) {
  if (is_triangle_file(request.boundary)) return run_tri_solve(request.boundary, request.net, request.global);
  Phases phases("solve");
  phases.start("read");
  const BoundaryFile input = read_input(request.boundary, request.net.corner_tolerance, true);
  if (input.bspline) return run_bspline_solve(request.boundary, input, request.net, request.global, phases);
  const ResolvedRequest r = resolve(request.net, input.boundary, request.boundary);
  if (!is_classical_request(input, r)) return run_stencil_solve(request, input, r, phases);
  check_net_memory(request.global, input.boundary, r.solver, request.boundary);
  phases.start("solve");  // the singularity check and assembling included
  check_classical_request(input, r, request.boundary);
  const NetOutcome outcome = make_net(input.boundary, r);
  phases.start("metrics");
  const nlohmann::json report = net_report(input.boundary, r.method, r.mask, outcome, request.net.mu,
                                           r.picked_automatically, false, r.options.threads);
  const bool ok = !outcome.summary || outcome.summary->ok();
  print_net_report(report, ok ? &outcome.net : nullptr, phases);  // the write phase, then timing
  if (outcome.summary && !outcome.summary->ok()) {
    print_solver_failure(request.boundary, *outcome.summary);
    return kExitSolverFailed;
  }
  if (outcome.summary) print_solver_warning(request.boundary, *outcome.summary);
  return kExitOk;
}

}  // namespace

void register_solve(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<SolveRequest>();
  auto* cmd = app.add_subcommand("solve", "solve one boundary; prints one JSON report (docs/formats.md)");
  cmd->add_option("BOUNDARY", request->boundary, "boundary JSON file (docs/formats.md)")->required();
  add_net_options(*cmd, request->net);
  add_mask_options(*cmd, request->net);
  add_memory_option(*cmd, request->global);
  set_example(*cmd,
              "coons solve data/boundaries/dome.json --alpha -0.2 --solver eigen-ldlt\n"
              "  coons solve data/boundaries/sphere_cap_ribbons.json --mask c1-family --weight 0.5");
  registry.add(cmd, [request] { return run_solve(*request); });
}

}  // namespace coons::cli
