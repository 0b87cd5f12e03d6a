// `coons solvers`: the linear-solver backends built in.
#include <fmt/format.h>

#include <memory>

#include "registry.h"

namespace coons::cli {

namespace {

struct SolversRequest {
  bool json = false, verbose = false;
};

int run_solvers(const SolversRequest& r) {
  if (r.json) {
    nlohmann::json names = nlohmann::json::array();
    for (const auto& s : solvers::available_solvers()) names.push_back(s.name);
    print_json(names, -1);
    return kExitOk;
  }
  std::string text;
  for (const auto& s : solvers::available_solvers())
    text += r.verbose ? fmt::format("{:<20} {:<11} {}\n", s.name, solvers::to_string(s.family), s.description)
                      : s.name + "\n";
  print_text(text);
  return kExitOk;
}

}  // namespace

void register_solvers(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<SolversRequest>();
  auto* cmd = app.add_subcommand("solvers", "list the linear-solver backends built in");
  cmd->add_flag("--json", request->json, "print a JSON array");
  cmd->add_flag("-v,--verbose", request->verbose, "print family and description too");
  set_example(*cmd, "coons solvers --verbose");
  registry.add(cmd, [request] { return run_solvers(*request); });
}

}  // namespace coons::cli
