// What the commands of the `coons` CLI share: exit codes, --solver and --threads, the memory
// limit, the input files, the progress and timing of the phases, and the checked printing of a
// report. (The options that request a net: net_request.h.)
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/io/boundary_io.h"
#include "coons/io/input_error.h"
#include "coons/io/misspelt_fields.h"
#include "coons/mask/mask9.h"
#include "coons/mask/solve_stencil_net.h"
#include "coons/mask/stencil.h"
#include "coons/mask/stencil_problem.h"
#include "coons/net/control_net.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/net_report.h"
#include "solvers/linear_solver.h"
#include "solvers/registry.h"

namespace coons::cli {

constexpr int kExitOk = 0;
constexpr int kExitInternal = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitSolverFailed = 3;

using Method = NetMethod;

//! The options of every command (registered on each subcommand).
struct GlobalOptions {
  std::string max_memory;  //!< --max-memory: BYTES, NNMB, NNGB (default: half of MemAvailable)
  bool force = false;      //!< --force (commands whose file names are chosen by the user)
  //! The limit in bytes (parsed once; throws InputError for a bad --max-memory).
  [[nodiscard]] double memory_limit() const;
};
void add_memory_option(CLI::App& cmd, GlobalOptions& g);

//! A CLI11 transform for parameter options (--alpha, --mu, --weight, --lower, --upper, --from,
//! --to, --alphas): a value that reads as zero becomes "0", so that -0 is the same parameter as 0
//! in reports, file names ("c1-family-w0") and duplicate checks.
const CLI::Validator& fold_negative_zero();

//! A CLI11 check for each value of an integer-list option (--degrees, --continuum-degrees, --edges,
//! --degree): a value that is no int names that value alone, "'9999999999' is not an integer from
//! -2147483648 to 2147483647", where CLI11 quoted the whole list ("'8,12,16,9999999999' is …").
const CLI::Validator& int_item();

//! A CLI11 transform for an option naming one of `names` (--method, --parameter): the name becomes
//! the enum, anything else (another word, or the enum's number) is "'foo' is not one of a, b, c".
//! (CLI::CheckedTransformer said "Check foo value in {alpha->0,coons->1,...} OR {0,1,2} FAILED"
//! and took the numbers too.)
template <class Enum>
CLI::Validator choice_of(const std::map<std::string, Enum>& names) {
  std::string list;
  for (const auto& entry : names) list += (list.empty() ? "" : ", ") + entry.first;
  return CLI::Validator(
      [names, list](std::string& text) {
        const auto it = names.find(text);
        if (it == names.end()) return "'" + text + "' is not one of " + list;
        text = std::to_string(static_cast<long long>(it->second));
        return std::string();
      },
      "{" + list + "}", "CHOICE");
}

//! An output file the command is about to write: a folder of that name is bad input naming
//! `option` (--force cannot replace a folder by a file; it said "give --force"), and so is an
//! existing file without --force.
void require_new_output(const std::string& path, bool force, const std::string& option);

//! require_new_output for a file written where the user names it (refit --out, surface --obj ...):
//! also its folder must exist (a regular file in the path is named), and its name fit a file name
//! (255 bytes); each an InputError naming `option`. Nothing for an empty path.
void require_new_file(const std::string& path, bool force, const std::string& option);

//! Refuses (InputError naming `file` and `field`) when `bytes` exceeds the limit.
void check_memory(const GlobalOptions& g, double bytes, const std::string& what, const std::string& file,
                  const std::string& field);

//! `--samples` of a target objective: at least 2, and a k×k grid of target samples
//! (target_samples_bytes) within the memory limit; else an InputError naming --samples.
void check_target_samples(const GlobalOptions& g, int samples);

//! `--solver NAME`: nullptr for auto; an unknown name is an InputError listing the built-in ones.
const solvers::SolverInfo* solver_from_name(const std::string& name);

//! --solver alone (search, sweep, batch, study).
void add_solver_option(CLI::App& cmd, std::string& solver);
//! True when `option` exists and was given on the command line.
bool given(const CLI::Option* option);
//! --threads N (0: every core) for the backends that use threads (solve, export, batch, sweep).
CLI::Option* add_threads_option(CLI::App& cmd, int& threads);
//! The solver options of --threads: InputError (field --threads) outside 0 .. kMaxThreads, or
//! when --threads was given (`option`) with a backend `solver` names that does not use threads.
solvers::SolverOptions threads_options(int threads, const CLI::Option* option = nullptr,
                                       const std::string& solver = "auto");
//! An InputError on --alpha unless it is finite with |α| <= kMaxAlpha (mask9.h); the quad and the
//! triangular mask families share the rule.
void require_alpha_value(double alpha);
//! An --objective as given without its white space: weighted sums may be written with spaces,
//! "thin_plate + 10*target" is "thin_plate+10*target" (search-alpha, degree-limit, triangles).
std::string objective_text(const std::string& given);

//! The InputError of --samples given to a search whose objective has no target term (rectangles
//! and triangles alike).
InputError samples_without_target(const std::string& objective);
//! The InputError of --samples given to a sweep that has no target (neither --target nor the
//! file's): it reports no rms_target, so the samples would be ignored.
InputError samples_without_sweep_target();
//! An InputError unless SolverOptions::is_valid, naming the option that set the field at fault
//! (--tolerance, --max-iterations, --omega, --threads).
void require_valid_solver_options(const solvers::SolverOptions& options);
//! An InputError unless AlphaSearchOptions::is_valid, naming the option that set the member at
//! fault (--lower, --upper, both for their order, --scan).
void require_valid_search_options(const AlphaSearchOptions& options);
//! An InputError unless --corner-tolerance is a finite number >= 0 (every command that reads
//! boundaries checks it before reading them).
void check_corner_tolerance(double corner_tolerance);
//! A B-spline boundary (knots_u, knots_v) is an InputError unless `accept_bspline` (the commands
//! that handle one: bspline_commands.h); so is a model smaller than `min_model_size` (the searches
//! pass kMinModelSize, BoundaryReadOptions).
BoundaryFile read_input(const std::string& path, double corner_tolerance, bool accept_bspline = false,
                        double min_model_size = 0);
//! One line on standard error per misspelt field of the file at `path` ("warning: FILE: fre:
//! unknown field, ignored (did you mean "free"?)"); read_input calls it.
void warn_misspelt(const std::string& path, const std::vector<MisspeltField>& misspelt);
//! Files as given, folders expanded to their *.json files (sorted); unreadable folders, folders
//! without a *.json file, and an entry *.json of a folder that is no regular file (a FIFO would
//! block the run), are InputErrors naming the folder or the entry.
std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs);

//! The memory of solving and measuring an (m+1)×(n+1) net, checked against the limit;
//! `stencil_nonzeros` a row of the system (memory_estimate.h: 9 for a 3×3 mask, 25 for a 5×5 stencil).
void check_net_memory(const GlobalOptions& g, const Boundary& b, const solvers::SolverInfo* solver,
                      const std::string& file, int stencil_nonzeros = kMask3Nonzeros);

//! The options of `export` every boundary kind checks alike (InputError on the command line):
//! --samples at least 2, --mtx only where a system is solved (`solves_system`: --method alpha),
//! --prefix a plain file name.
void check_export_options(int samples, bool mtx, bool solves_system, const std::string& prefix);

//! Prints a JSON document on standard output and flushes it; a failed write is an InputError
//! ("<stdout>: write failed: REASON"). Invalid UTF-8 in names is replaced, never an exception.
void print_json(const nlohmann::json& doc, int indent = 2);
void print_json(const nlohmann::ordered_json& doc, int indent = 2);  //!< keeps the keys' order
void print_text(const std::string& text);
std::string dump(const nlohmann::json& doc, int indent = -1);
//! dump(doc, 2), except that an array of numbers (a point [x, y, z]) stays on one line: the
//! layout of the `net` of a solve report (docs/formats.md), for nets that write_net_json does not
//! stream (the triangular one).
std::string dump_points_inline(const nlohmann::json& doc);

//! One `error:` line on standard error for a failed solve (exit 3 goes with it).
//! `net`, when given, names which of several nets of the file failed (batch: "alpha-0.1"); it
//! opens the parenthesis: "(alpha-0.1: MESSAGE)".
void print_solver_failure(const std::string& file, const solvers::SolveSummary& summary, const std::string& net = "");

//! One `warning:` line on standard error for a successful solve whose forward error bound κ·ε
//! exceeds solvers::kForwardErrorNotice (its message says so); nothing otherwise. Exit status 0.
//! `net` names the net as for print_solver_failure: "(alpha-0.1: MESSAGE)".
void print_solver_warning(const std::string& file, const solvers::SolveSummary& summary, const std::string& net = "");

//! A command's phases (read, assemble, solve, metrics, write): a progress line on a terminal
//! (standard error), nothing otherwise; their seconds for the report's "timing" block.
class Phases {
 public:
  explicit Phases(std::string command);
  ~Phases();
  void start(const std::string& phase, const std::string& detail = "");
  //! A progress note inside the current phase (e.g. "3/41").
  void note(const std::string& detail);
  [[nodiscard]] nlohmann::json timing();  //!< seconds per phase (the current one closed)

 private:
  void close();
  std::string command_, current_;
  double started_ = 0;
  std::vector<std::pair<std::string, double>> seconds_;
  bool tty_ = false, printed_ = false;
};

//! The worked example that ends a command's --help.
void set_example(CLI::App& cmd, const std::string& example);

}  // namespace coons::cli
