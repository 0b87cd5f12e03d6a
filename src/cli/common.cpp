#include "common.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/stencil_json.h"
#include "coons/io/write_files.h"
#include "coons/study/memory_estimate.h"
#include "coons/study/net_report.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

// ---- memory ----------------------------------------------------------------------------------

double GlobalOptions::memory_limit() const {
  if (max_memory.empty()) return default_memory_limit();
  const auto bytes = parse_memory_size(max_memory);
  if (!bytes)
    throw InputError("command line", "--max-memory",
                     "'" + max_memory + "' is not a size such as 2000000000, 512MB or 4GB");
  return *bytes;
}

void add_memory_option(CLI::App& cmd, GlobalOptions& g) {
  cmd.add_option("--max-memory", g.max_memory,
                 "refuse work estimated to need more memory than this: BYTES, NNMB or NNGB "
                 "(default: half of the available memory)");
}

void require_new_output(const std::string& path, bool force, const std::string& option) {
  if (std::filesystem::is_directory(path))
    throw InputError(path, option, "is a folder; name a file to write (--force does not replace a folder)");
  std::error_code ec;
  if (const auto status = std::filesystem::status(path, ec);
      std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(path, option, "is not a regular file (--force replaces regular files only)");
  if (!force && std::filesystem::exists(path))
    throw InputError(path, "--force", "exists; give --force to overwrite it");
}

void require_new_file(const std::string& path, bool force, const std::string& option) {
  if (path.empty()) return;
  const std::filesystem::path file(path);
  const std::filesystem::path parent = file.parent_path();
  std::error_code ec;
  if (!parent.empty() && !std::filesystem::is_directory(parent, ec)) {
    // the nearest part of the path that exists: a regular file there is the reason
    std::filesystem::path up = parent;
    while (!up.empty() && !std::filesystem::exists(up, ec) && up.has_parent_path() && up.parent_path() != up)
      up = up.parent_path();
    if (!up.empty() && std::filesystem::exists(up, ec) && !std::filesystem::is_directory(up, ec))
      throw InputError("command line", option, fmt::format("'{}' is a file, not a folder", up.string()));
    throw InputError("command line", option, fmt::format("the folder '{}' does not exist", parent.string()));
  }
  // (the file is written first as NAME.tmp-PID-N beside it: up to 20 bytes more, within 255)
  if (const std::size_t bytes = file.filename().string().size(); bytes > 235)
    throw InputError("command line", option,
                     fmt::format("the file name is {} bytes long, more than 235 (255, the most a file name may have, "
                                 "less the suffix of the staging file written first)",
                                 bytes));
  require_new_output(path, force, option);
}

void check_memory(const GlobalOptions& g, double bytes, const std::string& what, const std::string& file,
                  const std::string& field) {
  const double limit = g.memory_limit();
  if (bytes > limit)
    throw InputError(file, field,
                     fmt::format("{} needs about {} of memory, more than the limit of {} (--max-memory to change it)",
                                 what, format_bytes(bytes), format_bytes(limit)));
}

void check_target_samples(const GlobalOptions& g, int samples) {
  if (samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  check_memory(g, target_samples_bytes(samples), fmt::format("{} x {} target samples", samples, samples),
               "command line", "--samples");
}

void check_export_options(int samples, bool mtx, bool solves_system, const std::string& prefix) {
  if (samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  if (mtx && !solves_system)
    throw InputError("command line", "--mtx",
                     "Matrix Market export needs --method alpha (closed forms solve no system)");
  if (const std::string safe = safe_file_stem(prefix); !prefix.empty() && safe != prefix) {
    // safe_file_stem keeps kMaxFileStemBytes: a longer name of letters was called "not a plain file name"
    if (prefix.size() > kMaxFileStemBytes && prefix.compare(0, safe.size(), safe) == 0)
      throw InputError("command line", "--prefix",
                       fmt::format("is {} bytes long, more than {}", prefix.size(), kMaxFileStemBytes));
    throw InputError("command line", "--prefix", "'" + prefix + "' is not a plain file name (letters, digits, - _ .)");
  }
}

void check_net_memory(const GlobalOptions& g, const Boundary& b, const solvers::SolverInfo* solver,
                      const std::string& file, int stencil_nonzeros) {
  const double bytes = net_solve_bytes(b.m, b.n, solver, stencil_nonzeros) + net_metrics_bytes(b.m, b.n);
  check_memory(g, bytes, fmt::format("a net of degree ({}, {})", b.m, b.n), file, "degree");
}

// ---- solvers ---------------------------------------------------------------------------------

const solvers::SolverInfo* solver_from_name(const std::string& name) {
  if (name == "auto") return nullptr;
  if (const solvers::SolverInfo* info = solvers::find_solver(name)) return info;
  std::string names;
  for (const auto& s : solvers::available_solvers()) names += (names.empty() ? "" : ", ") + s.name;
  throw InputError("command line", "--solver", "unknown solver '" + name + "' (built in: auto, " + names + ")");
}

// ---- net options -----------------------------------------------------------------------------

void add_solver_option(CLI::App& cmd, std::string& solver) {
  cmd.add_option("--solver", solver, "a name from `coons solvers`, or auto")->capture_default_str();
}

namespace {

// The backends built in that use SolverOptions::threads, "a, b and c" (SolverInfo::uses_threads).
std::string threaded_backend_names() {
  std::vector<std::string> names;
  for (const solvers::SolverInfo& info : solvers::available_solvers())
    if (info.uses_threads) names.push_back(info.name);
  if (names.size() < 2) return fmt::format("{}", fmt::join(names, ""));
  const std::string last = names.back();
  names.pop_back();
  return fmt::format("{} and {}", fmt::join(names, ", "), last);
}

}  // namespace

CLI::Option* add_threads_option(CLI::App& cmd, int& threads) {
  return cmd
      .add_option("--threads", threads,
                  "threads of the backends that use them (" + threaded_backend_names() +
                      "; a sweep on fast: whole members; solve with one of them: also the exact energies of its "
                      "report); "
                      "0: every core. "
                      "The result is the same for every count")
      ->capture_default_str();
}

solvers::SolverOptions threads_options(int threads, const CLI::Option* option, const std::string& solver) {
  if (threads < 0 || threads > solvers::kMaxThreads)
    throw InputError("command line", "--threads",
                     fmt::format("must lie in 0 .. {} (0: every core), not {}", solvers::kMaxThreads, threads));
  if (option && option->count() > 0 && solver != "auto" && solvers::find_solver(solver) &&
      !solvers::uses_threads(solver))
    throw InputError("command line", "--threads",
                     solver + " runs on one thread; the backends that use threads are " + threaded_backend_names());
  solvers::SolverOptions options;
  options.threads = threads;
  return options;
}

bool given(const CLI::Option* option) { return option != nullptr && option->count() > 0; }

void require_alpha_value(double alpha) {
  if (!std::isfinite(alpha)) throw InputError("command line", "--alpha", "must be a finite number");
  if (std::abs(alpha) > kMaxAlpha)
    throw InputError("command line", "--alpha",
                     fmt::format("{:g} is beyond the bound |alpha| <= {:g} (the mask's weights would overflow in "
                                 "the solvers' products)",
                                 alpha, kMaxAlpha));
}

std::string objective_text(const std::string& given) {
  std::string out;
  for (char c : given)
    if (!std::isspace(static_cast<unsigned char>(c))) out += c;
  return out;
}

InputError samples_without_target(const std::string& objective) {
  return {"command line", "--samples",
          "--samples sets the target's sampling but --objective '" + objective + "' has no target term"};
}

const CLI::Validator& int_item() {
  static const CLI::Validator check(
      [](const std::string& value) {
        int parsed = 0;  // (an empty value is refused by refuse_empty_values, registry.cpp)
        if (value.empty() || CLI::detail::lexical_cast(value, parsed)) return std::string();
        return fmt::format("'{}' is not an integer from {} to {}", value, std::numeric_limits<int>::min(),
                           std::numeric_limits<int>::max());
      },
      "", "integer");
  return check;
}

const CLI::Validator& fold_negative_zero() {
  static const CLI::Validator fold(
      [](std::string& value) {
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        // (1e-400 also reads as 0: it is left for the check that refuses it)
        if (end != value.c_str() && *end == '\0' && number == 0 && zero_digits(value)) value = "0";
        return std::string();
      },
      "", "fold -0 to 0");
  return fold;
}

void require_valid_solver_options(const solvers::SolverOptions& options) {
  using F = solvers::SolverOptionsField;
  const solvers::SolverOptionsProblem problem = solvers::options_problem(options);
  switch (problem.field) {
    case F::kNone:
      return;
    case F::kTolerance:
      throw InputError("command line", "--tolerance", problem.reason);
    case F::kMaxIterations:
      throw InputError("command line", "--max-iterations", problem.reason);
    case F::kSorOmega:
      throw InputError("command line", "--omega", problem.reason);
    case F::kThreads:
      throw InputError("command line", "--threads", problem.reason);
    case F::kTimeLimitSeconds:
      throw InputError("command line", "--time-limit", problem.reason);
    case F::kSingularResidual:
      break;  // no option sets it
  }
  throw InputError("command line", "solver options",
                   std::string(solvers::to_string(problem.field)) + " " + problem.reason);
}

void require_valid_search_options(const AlphaSearchOptions& options) {
  using F = SearchOptionsField;
  const SearchOptionsProblem problem = options_problem(options);
  switch (problem.field) {
    case F::kNone:
      return;
    case F::kLower:
      throw InputError("command line", "--lower", problem.reason);
    case F::kUpper:
      throw InputError("command line", "--upper", problem.reason);
    case F::kBounds:
      throw InputError("command line", "--lower/--upper", problem.reason);
    case F::kScanPoints:
      throw InputError("command line", "--scan", problem.reason);
    case F::kFlatTolerance:
    case F::kParameterTolerance:
    case F::kMaxIterations:
      break;  // no option sets them
  }
  throw InputError("command line", "search options", std::string(to_string(problem.field)) + " " + problem.reason);
}

InputError samples_without_sweep_target() {
  return {"command line", "--samples",
          "--samples sets the target's sampling but there is no target (neither --target nor the file's \"target\")"};
}

void check_corner_tolerance(double corner_tolerance) {
  if (!(corner_tolerance >= 0 && std::isfinite(corner_tolerance)))
    throw InputError("command line", "--corner-tolerance", "must be a finite number >= 0");
}

void warn_misspelt(const std::string& path, const std::vector<MisspeltField>& misspelt) {
  for (const MisspeltField& f : misspelt)
    std::cerr << fmt::format("warning: {}: {}: unknown field, ignored (did you mean \"{}\"?)\n", path, f.given,
                             f.known);
}

BoundaryFile read_input(const std::string& path, double corner_tolerance, bool accept_bspline, double min_model_size) {
  BoundaryReadOptions options;
  options.min_model_size = min_model_size;
  check_corner_tolerance(corner_tolerance);
  options.corner_tolerance = corner_tolerance;
  BoundaryFile file = read_boundary_file(path, options);
  warn_misspelt(path, file.misspelt);
  if (file.bspline && !accept_bspline)
    throw InputError(
        path, "knots_u",
        "a B-spline boundary is read by solve, export, batch, search-alpha, study and view only, not by this command");
  return file;
}

std::vector<std::string> expand_inputs(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const auto& in : inputs) {
    std::error_code ec;
    if (fs::is_directory(in, ec)) {
      std::vector<std::string> found;
      fs::directory_iterator it(in, ec);
      if (ec) throw InputError(in, "", "cannot read the folder: " + ec.message());
      for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) throw InputError(in, "", "cannot read the folder: " + ec.message());
        if (it->path().extension() != ".json") continue;
        // a FIFO named *.json blocked the run forever waiting for a writer: a folder is read for
        // its regular files (symbolic links to them included), and anything else is named
        std::error_code kind;
        if (!it->is_regular_file(kind))
          throw InputError(it->path().string(), "",
                           "is not a regular file (a folder given as input is read for its regular *.json files)");
        found.push_back(it->path().string());
      }
      if (found.empty()) throw InputError(in, "", "the folder holds no *.json boundary file");
      std::sort(found.begin(), found.end());
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(in);
    }
  }
  return files;
}

// ---- output ----------------------------------------------------------------------------------

std::string dump(const json& doc, int indent) { return doc.dump(indent, ' ', false, json::error_handler_t::replace); }

namespace {

void dump_points_inline(const json& v, int depth, std::string& out) {
  const auto is_number = [](const json& e) { return e.is_number() || e.is_null(); };
  const std::string indent(std::size_t(2 * (depth + 1)), ' '), close(std::size_t(2 * depth), ' ');
  if (v.is_array() && !v.empty() && std::all_of(v.begin(), v.end(), is_number)) {
    out += '[';
    for (std::size_t k = 0; k < v.size(); ++k) out += (k ? ", " : "") + dump(v[k]);
    out += ']';
  } else if (v.is_array() && !v.empty()) {
    out += "[\n";
    for (std::size_t k = 0; k < v.size(); ++k) {
      out += indent;
      dump_points_inline(v[k], depth + 1, out);
      out += k + 1 < v.size() ? ",\n" : "\n";
    }
    out += close + ']';
  } else if (v.is_object() && !v.empty()) {
    out += "{\n";
    std::size_t k = 0;
    for (const auto& [key, value] : v.items()) {
      out += indent + dump(json(key)) + ": ";
      dump_points_inline(value, depth + 1, out);
      out += ++k < v.size() ? ",\n" : "\n";
    }
    out += close + '}';
  } else {
    out += dump(v);
  }
}

}  // namespace

std::string dump_points_inline(const json& doc) {
  std::string out;
  dump_points_inline(doc, 0, out);
  return out;
}

void print_text(const std::string& text) {
  errno = 0;
  std::cout << text;
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout;
  if (failed) {
    const int error = errno;
    std::cout.clear();
    std::clearerr(stdout);
    throw InputError("<stdout>", "", std::string("write failed: ") + (error ? std::strerror(error) : "unknown error"));
  }
}

void print_json(const json& doc, int indent) { print_text(dump(doc, indent) + '\n'); }

void print_json(const nlohmann::ordered_json& doc, int indent) {
  print_text(doc.dump(indent, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + '\n');
}

void print_solver_failure(const std::string& file, const solvers::SolveSummary& s, const std::string& net) {
  std::string line = fmt::format("error: {}: solver: {} {}", file, s.solver, solvers::to_string(s.status));
  line += std::isfinite(s.relative_residual) ? fmt::format(", relative residual {:.3g}", s.relative_residual)
                                             : std::string(", relative residual not finite");
  if (!s.message.empty() || !net.empty()) {
    std::string message = s.message;
    std::replace(message.begin(), message.end(), '\n', ' ');
    line += " (" + net + (net.empty() || message.empty() ? "" : ": ") + message + ")";
  }
  std::cerr << line << '\n';
}

void print_solver_warning(const std::string& file, const solvers::SolveSummary& s, const std::string& net) {
  if (!s.ok() || !(s.forward_error_bound() > solvers::kForwardErrorNotice)) return;
  std::string message = s.message;
  std::replace(message.begin(), message.end(), '\n', ' ');
  if (!net.empty()) message = "(" + net + ": " + message + ")";
  std::cerr << fmt::format("warning: {}: solver: {} {}", file, s.solver, message) << '\n';
}

void set_example(CLI::App& cmd, const std::string& example) { cmd.footer("\nExample:\n  " + example); }

}  // namespace coons::cli
