// How the commands of `coons` are registered: each command file exposes
// `void register_NAME(CLI::App& app, Registry& registry)`, which adds its subcommand with its
// options (bound to a request it owns) and the function that runs it. run() parses once, runs the
// chosen command and maps every exception to an exit status with one `error:` line:
// 2 for bad input (InputError, a JSON error of an input), 1 for anything internal.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "common.h"

namespace coons::cli {

struct Registry {
  struct Entry {
    CLI::App* command = nullptr;
    std::function<int()> run;
  };
  std::vector<Entry> entries;
  std::string command_line;  //!< the whole command line, for provenance

  void add(CLI::App* command, std::function<int()> run) { entries.push_back({command, std::move(run)}); }
};

void register_solve(CLI::App& app, Registry& registry);
void register_solvers(CLI::App& app, Registry& registry);
void register_export(CLI::App& app, Registry& registry);
void register_batch(CLI::App& app, Registry& registry);
void register_search_alpha(CLI::App& app, Registry& registry);
void register_sweep(CLI::App& app, Registry& registry);
void register_study(CLI::App& app, Registry& registry);
void register_refit(CLI::App& app, Registry& registry);
void register_surface(CLI::App& app, Registry& registry);
void register_join(CLI::App& app, Registry& registry);
void register_bench_matrix(CLI::App& app, Registry& registry);
void register_degree_limit(CLI::App& app, Registry& registry);
void register_view(CLI::App& app, Registry& registry);
void register_import_step(CLI::App& app, Registry& registry);  // cad_commands.cpp

//! The `coons` command line (docs/formats.md is its contract). Exit status: 0 success, 1 internal
//! error, 2 bad input (one `error:` line on stderr, nothing written), 3 a solver failed (the report
//! says why, and one `error:` line on stderr).
int run(int argc, char** argv);

}  // namespace coons::cli
