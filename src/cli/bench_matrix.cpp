// `coons bench-matrix A.mtx [B.mtx]`: any Matrix Market system through every general backend that
// accepts it; one JSON object per backend (JSON Lines) or, with --table, a Markdown table.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "coons/io/input_error.h"
#include "coons/io/matrix_market.h"
#include "registry.h"
#include "solvers/general_system.h"

namespace coons::cli {

namespace {

struct BenchMatrixRequest {
  std::string matrix, rhs;
  std::string solvers_text;          //!< --solvers as given: names separated by commas
  std::vector<std::string> solvers;  //!< empty: every backend built in
  bool table = false;
  double tolerance = 1e-10;
  int max_iterations = 0;
  double time_limit = 0;  //!< --time-limit, seconds per solve of an iterative backend (0: none)
  GlobalOptions global;
  const CLI::Option *tolerance_option = nullptr, *max_iterations_option = nullptr, *time_limit_option = nullptr;
};

std::vector<const solvers::SolverInfo*> chosen_backends(const std::vector<std::string>& names) {
  std::vector<const solvers::SolverInfo*> out;
  if (names.empty()) {
    for (const auto& info : solvers::available_solvers()) out.push_back(&info);
    return out;
  }
  for (const std::string& name : names) {
    const solvers::SolverInfo* info = solvers::find_solver(name);
    if (!info) {
      std::string built_in;
      for (const auto& s : solvers::available_solvers()) built_in += (built_in.empty() ? "" : ", ") + s.name;
      throw InputError("command line", "--solvers", fmt::format("unknown solver '{}' (built in: {})", name, built_in));
    }
    if (std::find(out.begin(), out.end(), info) != out.end())
      throw InputError("command line", "--solvers", "'" + name + "' is named twice");
    out.push_back(info);
  }
  return out;
}

// "a,b,c" → {a, b, c}; an empty name anywhere (",b", "a,,c", "a,") is bad input.
std::vector<std::string> solver_names(const std::string& text) {
  std::vector<std::string> names;
  if (text.empty()) return names;
  for (std::size_t start = 0;;) {
    const std::size_t comma = text.find(',', start);
    names.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (names.back().empty())
      throw InputError("command line", "--solvers",
                       fmt::format("an empty name in '{}' (names separated by commas)", text));
    if (comma == std::string::npos) return names;
    start = comma + 1;
  }
}

nlohmann::json or_null(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }

nlohmann::ordered_json run_to_json(const solvers::GeneralRun& run, const solvers::SolverInfo& info) {
  nlohmann::ordered_json j;
  j["solver"] = run.solver;
  j["family"] = solvers::to_string(info.family);
  j["status"] = run.status_name();
  if (run.skipped) j["reason"] = run.reason;
  if (!run.skipped && !run.ok()) j["message"] = run.reason;
  if (run.ok() && !run.reason.empty()) j["note"] = run.reason;
  j["seconds"] = {{"analyze", or_null(run.analyze_seconds)},
                  {"factorize", or_null(run.factorize_seconds)},
                  {"solve", or_null(run.solve_seconds)}};
  j["iterations"] = run.iterations ? nlohmann::json(*run.iterations) : nlohmann::json(nullptr);
  j["relative_residual"] = or_null(run.relative_residual);
  j["backward_error"] = or_null(run.backward_error);
  j["factor_nnz"] = run.factor_nnz ? nlohmann::json(*run.factor_nnz) : nlohmann::json(nullptr);
  j["balancing_exponent"] = run.exponent;
  return j;
}

std::string cell(const std::optional<double>& v) { return v ? fmt::format("{:.3g}", *v) : "–"; }

std::string table_row(const solvers::GeneralRun& run) {
  std::string note;  // a table cell: '|' escaped, one line
  for (const char c : run.reason) note += c == '|' ? std::string("\\|") : std::string(1, c == '\n' ? ' ' : c);
  return fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", run.solver, run.status_name(),
                     cell(run.analyze_seconds), cell(run.factorize_seconds), cell(run.solve_seconds),
                     run.iterations ? std::to_string(*run.iterations) : "–", cell(run.relative_residual),
                     cell(run.backward_error), run.factor_nnz ? std::to_string(*run.factor_nnz) : "–", note);
}

// What the largest of the runs needs beyond A (the backends run one at a time), an upper-bound
// sketch as in memory_estimate.h: B and X (n by k) with the residual's temporaries (three more),
// a block of three columns and its solution, and the backend's share: a direct factor of about
// (nnz + n)·log2(n) entries (fill grows with n: the 8·log2(N) a row of net_solve_bytes for a 3×3
// mask), an iterative one's vectors (GMRES(50) keeps 51 of n a column) and a preconditioner of
// a few copies of A. A file of a few bytes can declare 2^26 rows: this comes before any of it
// (before A·1 and the symmetry check's transposed copy too).
double bench_bytes(Eigen::Index n, Eigen::Index nnz, Eigen::Index columns,
                   const std::vector<const solvers::SolverInfo*>& backends) {
  const double rows = double(n), entries = double(nnz);
  double share = 0;
  for (const solvers::SolverInfo* info : backends) {
    if (!info->needs_matrix) continue;  // skipped (the symmetric-only ones counted: A is not checked yet)
    if (info->family == solvers::SolverFamily::kDirect)
      share = std::max(share, 16 * (entries + rows) * std::log2(std::max(rows, 2.0)));
    else
      share = std::max(share, 8 * rows * 64 + 16 * entries * 3);
  }
  return 8 * rows * (5 * double(columns) + 9) + share;
}

int run_bench_matrix(BenchMatrixRequest r) {
  r.solvers = solver_names(r.solvers_text);
  solvers::SolverOptions options;
  options.tolerance = r.tolerance;
  options.max_iterations = r.max_iterations;
  if (!(std::isfinite(r.time_limit) && r.time_limit >= 0))
    throw InputError("command line", "--time-limit", "must be a finite number of seconds >= 0 (0: none)");
  options.time_limit_seconds = r.time_limit;
  require_valid_solver_options(options);
  const std::vector<const solvers::SolverInfo*> backends = chosen_backends(r.solvers);
  // As in `coons solve`: a stopping rule that none of the chosen backends reads is an error. The
  // iterative backends that run on a matrix read them (one that needs a grid stencil, mg say, is
  // skipped here and reads none), but for a time limit hypre-amg, whose iterations have no clock.
  std::vector<const solvers::SolverInfo*> iterative, clocked;
  for (const solvers::SolverInfo* b : backends)
    if (b->family == solvers::SolverFamily::kIterative && solvers::accepts_matrix(*b)) {
      iterative.push_back(b);
      if (b->name.rfind("hypre-", 0) != 0) clocked.push_back(b);
    }
  if (iterative.empty())
    for (const auto& [option, name] : {std::pair{r.tolerance_option, "--tolerance"},
                                       {r.max_iterations_option, "--max-iterations"},
                                       {r.time_limit_option, "--time-limit"}})
      if (given(option))
        throw InputError("command line", name,
                         fmt::format("{} is a stopping rule of the iterative solvers; none of --solvers {} is an "
                                     "iterative backend that runs on a matrix",
                                     name, fmt::join(r.solvers, ",")));
  if (given(r.time_limit_option) && clocked.empty())
    throw InputError("command line", "--time-limit",
                     fmt::format("no backend of --solvers {} can be stopped by a time limit (hypre-amg has no clock "
                                 "in its iterations)",
                                 fmt::join(r.solvers, ",")));

  // The sizes a file declares are checked before the reader allocates for them (a 72-byte file
  // declaring 2^26 columns took 560 MB before --max-memory refused it).
  // For A (is_a) the system is its own size; for B it is A's (n, nnz) with B's columns.
  const auto check_declared = [&](const std::string& file, bool is_a, Eigen::Index n, Eigen::Index nnz) {
    return [&, is_a, n, nnz](long long rows, long long cols, long long stored, int size_line) {
      check_memory(r.global,
                   market_matrix_bytes(cols, stored) + bench_bytes(is_a ? Eigen::Index(rows) : n,
                                                                   is_a ? Eigen::Index(stored) : nnz,
                                                                   is_a ? 1 : Eigen::Index(cols), backends),
                   fmt::format("a {} by {} matrix of {} entries as declared", rows, cols, stored), file,
                   fmt::format("line {}", size_line));
    };
  };
  const MarketMatrix a = read_market_matrix(r.matrix, check_declared(r.matrix, true, 0, 0));
  const Eigen::SparseMatrix<double>& A = a.matrix;
  const Eigen::Index n = A.rows();
  if (A.rows() != A.cols())
    throw InputError(r.matrix, fmt::format("line {}", a.size_line),
                     fmt::format("A must be square, not {} by {}", A.rows(), A.cols()));
  const auto check_bench_memory = [&](Eigen::Index columns, const std::string& file, int size_line) {
    check_memory(r.global, bench_bytes(n, A.nonZeros(), columns, backends),
                 fmt::format("a {} by {} system with {} right-hand side{} and the backends' work", n, n, columns,
                             columns == 1 ? "" : "s"),
                 file, fmt::format("line {}", size_line));
  };
  Eigen::MatrixXd B;
  if (r.rhs.empty()) {
    check_bench_memory(1, r.matrix, a.size_line);
    B = A * Eigen::VectorXd::Ones(n);
    for (Eigen::Index i = 0; i < n; ++i)  // finite entries can sum beyond the doubles
      if (!std::isfinite(B(i, 0)))
        throw InputError(r.matrix, fmt::format("row {}", i + 1),
                         "the default right-hand side A times ones is not finite there (the row sums beyond the "
                         "doubles); give B.mtx");
  } else {
    const MarketMatrix b = read_market_matrix(r.rhs, check_declared(r.rhs, false, n, A.nonZeros()));
    if (b.matrix.rows() != n)
      throw InputError(r.rhs, fmt::format("line {}", b.size_line),
                       fmt::format("B has {} rows, A ({}) has {}", b.matrix.rows(), r.matrix, n));
    check_bench_memory(1, r.matrix, a.size_line);  // A's size alone is too much: A is at fault
    check_bench_memory(b.matrix.cols(), r.rhs, b.size_line);
    B = Eigen::MatrixXd(b.matrix);
  }
  solvers::GeneralSystem system;
  system.A = &A;
  system.B = &B;
  const double defect = solvers::symmetry_defect(A);
  system.symmetric = defect <= solvers::kSymmetryDefectLimit;
  system.exponent = solvers::balancing_exponent(A);

  if (r.table) {
    print_text(fmt::format(
        "{}: {} by {}, {} non-zeros ({} values listed in the file, {} {} {}), {}; {} right-hand side{}; iterative "
        "tolerance {}{}\n\n"
        "| solver | status | analyze [s] | factorize [s] | solve [s] | iterations | relative residual | backward "
        "error | factor nnz | note |\n|---|---|---|---|---|---|---|---|---|---|\n",
        r.matrix, n, n, A.nonZeros(), a.file_entries, a.format, a.field, a.symmetry,
        system.symmetric ? "symmetric" : fmt::format("not symmetric (defect {:.3g})", defect), B.cols(),
        B.cols() == 1 ? (r.rhs.empty() ? " (A times ones)" : "") : "s", solvers::format_g(r.tolerance),
        system.exponent == 0 ? std::string()
                             : fmt::format("; the backends see 2^{} A (balanced, exactly), and X is 2^{} times their "
                                           "solution",
                                           system.exponent, system.exponent)));
  }
  int succeeded = 0, failed = 0;
  for (const solvers::SolverInfo* info : backends) {
    const solvers::GeneralRun run = solvers::run_general_system(*info, system, options);
    succeeded += run.ok() ? 1 : 0;
    failed += !run.ok() && !run.skipped ? 1 : 0;
    if (r.table)
      print_text(table_row(run));
    else
      print_json(run_to_json(run, *info), -1);
  }
  if (failed > 0 && succeeded == 0) {
    std::cerr << fmt::format("error: {}: solver: no backend solved the system ({} failed)\n", r.matrix, failed);
    return kExitSolverFailed;
  }
  return kExitOk;
}

}  // namespace

void register_bench_matrix(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<BenchMatrixRequest>();
  auto* cmd =
      app.add_subcommand("bench-matrix", "run a Matrix Market system A X = B through every backend that accepts it");
  cmd->add_option("A.mtx", request->matrix,
                  "square matrix (Matrix Market: coordinate or array; real, integer or "
                  "pattern; general, symmetric or skew-symmetric)")
      ->required();
  cmd->add_option("B.mtx", request->rhs, "right-hand side(s), n by k, array or coordinate (default: A times ones)");
  // split here, not by CLI11, which dropped an empty last name: "--solvers eigen-lu," ran
  cmd->add_option("--solvers", request->solvers_text, "only these backends, comma separated (see `coons solvers`)");
  cmd->add_flag("--table", request->table, "print a Markdown table instead of JSON Lines");
  request->tolerance_option =
      cmd->add_option("--tolerance", request->tolerance, "relative residual at which every iterative backend stops")
          ->capture_default_str();
  request->max_iterations_option =
      cmd->add_option("--max-iterations", request->max_iterations,
                      "iteration limit of the iterative backends (0: automatic, always finite)")
          ->capture_default_str();
  request->time_limit_option =
      cmd->add_option("--time-limit", request->time_limit,
                      "seconds after which an iterative backend's solve stops, not_converged with the iterate "
                      "reached (0: none; not hypre-amg, which has no clock; a limit makes the Krylov backends "
                      "restart in chunks, so their counts differ slightly from a run without)")
          ->capture_default_str();
  add_memory_option(*cmd, request->global);
  set_example(*cmd, "coons bench-matrix data/matrices/anisotropic_diffusion.mtx --table");
  registry.add(cmd, [request] { return run_bench_matrix(*request); });
}

}  // namespace coons::cli
