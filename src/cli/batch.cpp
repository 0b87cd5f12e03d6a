// `coons batch BOUNDARY...`: every boundary as the Coons net and at several α; a folder per
// boundary and degree (<name>-<m>x<n>/) with a solve report and OBJ files per net, named by the
// method and α to full precision, and a metrics table. All written at the end, together.
// With --mask NAME (not alpha, as for solve: c1-coons, biharmonic, c1-family --weight w,
// file:PATH) every boundary is solved once with that mask instead, over its whole problem
// (ribbons, rings, free grid), the net named by the mask (c1-family-w0.5.json, ...).
#include <fmt/format.h>
#include <locale.h>
#include <wchar.h>

#include <algorithm>
#include <cwchar>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "bspline_commands.h"
#include "coons/io/input_error.h"
#include "coons/io/obj_export.h"
#include "coons/io/write_files.h"
#include "coons/mask/stencil_problem.h"
#include "coons/metrics/energies.h"
#include "coons/study/memory_estimate.h"
#include "coons/surfaces/bspline_sampling.h"
#include "net_request.h"
#include "registry.h"

namespace coons::cli {

namespace {

struct BatchRequest {
  std::vector<std::string> inputs;
  std::string out_dir = "out";
  std::vector<double> alphas = {-0.25, -0.1, 0.0};
  int samples = 33;
  NetRequest net;  // --solver, --mask, --weight
  GlobalOptions global;
  CLI::Option* alphas_option = nullptr;
};

// The file stem of a --mask run: the mask's name, c1-family with its weight, file: by the file's stem.
std::string mask_tag(const ResolvedRequest& r) {
  if (r.mask_kind == MaskKind::kC1Family) return fmt::format("c1-family-w{}", *r.weight);
  if (r.mask_kind == MaskKind::kFile)
    return "file-" + safe_file_stem(std::filesystem::path(r.mask_name.substr(5)).stem().string());
  return r.mask_name;
}

// "alpha-0.1004": α to full precision (shortest round trip), with its sign.
std::string alpha_tag(double a) { return fmt::format("alpha{:+}", a == 0 ? 0.0 : a); }

struct Row {
  std::string boundary;
  int m, n;
  std::string method;
  std::string alpha;  // α, w= of c1-family, or - for the other masks
  std::string status;
  std::optional<NetMetrics> metrics;  // none when the solve failed: the table then says so
  std::string folder;                 // NAME-MxN[-K]: tells apart two files of one name
};

// A table cell from a name in an input file: '|' escaped, control characters (a line break would
// end the row) as spaces.
std::string table_cell(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '|')
      out += "\\|";
    else
      out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  }
  return out;
}

// Columns as a terminal shows the text: glibc's wcwidth in the C.UTF-8 locale (a CJK character
// takes two, a combining mark none); a byte that is not UTF-8, or a character wcwidth does not
// know, takes one. Without that locale, one per code point.
std::size_t display_width(const std::string& text) {
  static const locale_t utf8 = newlocale(LC_CTYPE_MASK, "C.UTF-8", locale_t(nullptr));
  if (utf8 == locale_t(nullptr))
    return std::size_t(
        std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
  const locale_t previous = uselocale(utf8);
  std::size_t width = 0;
  std::mbstate_t state{};
  const char* at = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    wchar_t c = 0;
    std::size_t used = std::mbrtowc(&c, at, left, &state);
    int columns = 1;
    if (used == std::size_t(-1) || used == std::size_t(-2)) {  // not UTF-8: one byte, one column
      used = 1;
      state = std::mbstate_t{};
    } else {
      used = std::max<std::size_t>(used, 1);  // an embedded '\0' is one byte
      columns = wcwidth(c) < 0 ? 1 : wcwidth(c);
    }
    width += std::size_t(columns);
    at += used;
    left -= used;
  }
  uselocale(previous);
  return width;
}

std::string metrics_table(const std::vector<Row>& rows) {
  struct Column {
    const char* title;
    std::size_t width;  // at least; a longer cell widens the column
    bool left;
  };
  std::vector<Column> columns = {{"boundary", 22, true},   {"degree", 7, false}, {"method", 10, true},
                                 {"alpha", 6, false},      {"twist", 11, false}, {"thin plate", 12, false},
                                 {"Dirichlet", 12, false}, {"E3", 12, false},    {"disc. twist", 12, false},
                                 {"mask res.", 9, false},  {"status", 11, true}};
  // A name given by two files (two folders NAME-MxN and NAME-MxN-2) is told apart by its folder.
  std::map<std::string, std::set<std::string>> folders_of;
  for (const Row& r : rows) folders_of[r.boundary].insert(r.folder);
  std::vector<std::vector<std::string>> cells;
  for (const Row& r : rows) {
    const std::string name =
        folders_of[r.boundary].size() > 1 ? fmt::format("{} ({})", r.boundary, r.folder) : r.boundary;
    std::vector<std::string> row = {table_cell(name), fmt::format("{}x{}", r.m, r.n), table_cell(r.method), r.alpha};
    if (r.metrics) {
      const NetMetrics& k = *r.metrics;
      for (const double e :
           {k.twist_energy, k.thin_plate_energy, k.dirichlet_energy, k.e3_energy, k.discrete_twist_energy})
        row.push_back(fmt::format("{:.6g}", e));
      row.push_back(fmt::format("{:.2e}", k.mask_residual));
    } else {  // a failed solve has no net: no numbers, not zeros
      row.insert(row.end(), 6, "-");
    }
    row.push_back(r.status);
    cells.push_back(std::move(row));
  }
  for (const auto& row : cells)
    for (std::size_t c = 0; c < columns.size(); ++c)
      columns[c].width = std::max(columns[c].width, display_width(row[c]));
  const auto line = [&](const std::vector<std::string>& row) {
    std::string out = "|";
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const std::string pad(columns[c].width - display_width(row[c]), ' ');
      out += " " + (columns[c].left ? row[c] + pad : pad + row[c]) + " |";
    }
    return out + "\n";
  };
  std::vector<std::string> titles;
  titles.reserve(columns.size());
  for (const Column& c : columns) titles.emplace_back(c.title);
  std::string table = line(titles) + "|";
  for (const Column& c : columns) table += std::string(c.width + 2, '-') + "|";
  table += "\n";
  for (const auto& row : cells) table += line(row);
  return table;
}

// A run's files under `stem`: its report, and its surface and net OBJ files unless `failure`;
// a failure removes an earlier run's nets (they do not stand beside it) and says why.
void write_run(OutputSet& out, const std::string& stem, const nlohmann::json& report, const ControlNet& net,
               int samples, const std::string& file, const solvers::SolveSummary* failure) {
  out.write(stem + ".json", [&](std::ostream& o) { o << dump(report, 2) << '\n'; });
  if (!failure) {
    out.write(stem + ".surface.obj", [&](std::ostream& o) { write_surface_obj(o, net, samples); });
    out.write(stem + ".net.obj", [&](std::ostream& o) { write_net_obj(o, net); });
  } else {
    out.remove_stale(stem + ".surface.obj");
    out.remove_stale(stem + ".net.obj");
    print_solver_failure(file, *failure, std::filesystem::path(stem).filename().string());
  }
}

// One stencil solve of a boundary's whole problem (ribbons, rings, free grid), as `coons solve`
// gives it for `request`: a --mask run (tag from the mask), or one α of a file that is not a
// one-ring rectangle (tag alpha±A).
void run_stencil(const BatchRequest& b, const NetRequest& request, const BoundaryFile& input, const std::string& file,
                 const std::string& folder, OutputSet& out, std::vector<Row>& rows, Phases& phases) {
  const ResolvedRequest r = resolve(request, input.boundary, file);
  const bool by_mask = r.mask_kind != MaskKind::kAlpha;
  const std::string tag = by_mask ? mask_tag(r) : alpha_tag(request.alpha);
  phases.start("solve", fmt::format("{} {}", input.boundary.name, tag));
  const StencilRun run = solve_stencil_request(input, r, request, b.global, file);
  const bool ok = run.result.summary.ok();
  Row row{input.boundary.name,
          input.boundary.m,
          input.boundary.n,
          r.mask_name,
          r.weight  ? fmt::format("w={}", *r.weight)
          : by_mask ? std::string("-")
                    : fmt::format("{}", request.alpha),
          solvers::to_string(run.result.summary.status),
          {},
          folder};
  phases.start("metrics");
  if (ok) row.metrics = net_metrics(run.result.net, free_points(run.problem), run.stencil);
  rows.push_back(row);
  const nlohmann::json report = stencil_report(input, r, run, std::nullopt);
  phases.start("write");
  write_run(out, fmt::format("{}/{}", folder, tag), report, run.result.net, b.samples, file,
            ok ? nullptr : &run.result.summary);
  if (ok) print_solver_warning(file, run.result.summary, tag);
}

// The nets of a one-ring boundary, by file stem: the closed-form Coons net, then the mask solve
// at each --alphas value with --solver and --threads.
std::vector<std::pair<std::string, NetRequest>> coons_and_alpha_runs(const BatchRequest& b) {
  std::vector<std::pair<std::string, NetRequest>> runs;
  NetRequest coons;
  coons.method = Method::kCoons;
  runs.emplace_back("coons", coons);
  for (double a : b.alphas) {
    NetRequest r;
    r.alpha = a;
    r.solver = b.net.solver;
    r.threads = b.net.threads;
    r.threads_option = b.net.threads_option;
    runs.emplace_back(alpha_tag(a), r);
  }
  return runs;
}

// A B-spline boundary (knots_u, knots_v): its Greville-weighted Coons net and the non-uniform
// alpha family at each --alphas value, as `coons solve` and `coons export` give them.
void run_bspline(const BatchRequest& b, const BoundaryFile& input, const std::string& file, const std::string& folder,
                 OutputSet& out, std::vector<Row>& rows, Phases& phases) {
  for (const auto& [tag, request] : coons_and_alpha_runs(b)) {
    phases.start("solve", fmt::format("{} {}", input.boundary.name, tag));
    const BSplineBatchNet net = bspline_batch_net(file, input, request, b.global);
    const BSplineNetOutcome& outcome = net.outcome;
    rows.push_back(
        Row{input.boundary.name, outcome.surface.net.m, outcome.surface.net.n,
            std::string(to_string(net.resolved.method)) + " (B-spline)", fmt::format("{}", net.resolved.alpha),
            outcome.summary ? solvers::to_string(outcome.summary->status) : "closed-form", net.metrics, folder});
    phases.start("write");
    const std::string stem = fmt::format("{}/{}", folder, tag);
    out.write(stem + ".json", [&](std::ostream& o) { o << dump(net.report, 2) << '\n'; });
    if (net.ok())
      write_bspline_objs(out, stem, sample_bspline_grid(outcome.surface, b.samples),
                         bspline_samples_comment(input.boundary.name, b.samples), outcome.surface.net);
    else {
      out.remove_stale(stem + ".surface.obj");
      out.remove_stale(stem + ".net.obj");
      print_solver_failure(file, *outcome.summary, tag);
    }
  }
}

// The command line's own checks, before any file is read.
void check_batch_request(const BatchRequest& b, bool by_mask) {
  if (b.samples < 2) throw InputError("command line", "--samples", "must be >= 2");
  for (size_t k = 0; k < b.alphas.size(); ++k) {
    const double a = b.alphas[k];
    if (!(a >= -0.25 && a <= 0.25))
      throw InputError("command line", "--alphas", fmt::format("{} is outside [-0.25, 0.25]", a));
    if (std::find(b.alphas.begin(), b.alphas.begin() + k, a) != b.alphas.begin() + k)
      throw InputError("command line", "--alphas", fmt::format("{} is given twice", a));
  }
  if (!by_mask && b.net.weight_option && b.net.weight_option->count() > 0)
    throw InputError("command line", "--weight", "--weight is the weight of --mask c1-family; it needs that mask");
  if (by_mask && b.alphas_option && b.alphas_option->count() > 0)
    throw InputError("command line", "--alphas",
                     "--alphas are the 3x3 masks of --mask alpha; they do not apply to --mask " + b.net.mask);
  check_memory(b.global, samples_bytes(b.samples), fmt::format("{} x {} surface samples", b.samples, b.samples),
               "command line", "--samples");
}

// Every input read and validated before anything is computed or written.
std::vector<BoundaryFile> read_batch_inputs(const BatchRequest& b, const std::vector<std::string>& files,
                                            const solvers::SolverInfo* solver, bool by_mask) {
  std::vector<BoundaryFile> boundaries;
  for (const auto& f : files) {
    boundaries.push_back(read_input(f, b.net.corner_tolerance, true));
    if (boundaries.back().bspline) {  // the non-uniform family (bspline_commands.h): its own checks
      (void)resolve_bspline(b.net, boundaries.back(), f);
      continue;
    }
    const ResolvedRequest r = resolve(b.net, boundaries.back().boundary, f);
    check_net_memory(b.global, boundaries.back().boundary, solver, f, stencil_nonzeros(r));
    if (by_mask || !is_classical(boundaries.back())) check_stencil_request(boundaries.back(), r, f);
  }
  return boundaries;
}

// A boundary with one data ring and no free grid: the closed-form Coons net and every --alphas
// mask solve, each a report and, when it succeeded, its surface and net OBJ files.
void run_classical(const BatchRequest& b, const BoundaryFile& input, const std::string& file, const std::string& folder,
                   OutputSet& out, std::vector<Row>& rows, Phases& phases) {
  const Boundary& boundary = input.boundary;
  for (const auto& [tag, request] : coons_and_alpha_runs(b)) {
    phases.start("solve", fmt::format("{} {}", boundary.name, tag));
    const ResolvedRequest r = resolve(request, boundary, file);
    const NetOutcome outcome = make_net(boundary, r);
    const bool ok = !outcome.summary || outcome.summary->ok();
    Row row{boundary.name,
            boundary.m,
            boundary.n,
            to_string(r.method),
            fmt::format("{}", r.mask.diag),
            outcome.summary ? solvers::to_string(outcome.summary->status) : "closed-form",
            {},
            folder};
    phases.start("metrics");
    if (ok) row.metrics = net_metrics(outcome.net, r.mask);
    rows.push_back(row);
    const nlohmann::json report = solve_report(boundary, r, outcome, std::nullopt);
    phases.start("write");
    write_run(out, fmt::format("{}/{}", folder, tag), report, outcome.net, b.samples, file,
              ok ? nullptr : &*outcome.summary);
    if (ok && outcome.summary) print_solver_warning(file, *outcome.summary, tag);
  }
}

int run_batch(const BatchRequest& b) {
  Phases phases("batch");
  phases.start("read");
  const std::vector<std::string> files = expand_inputs(b.inputs);
  if (files.empty()) throw InputError("command line", "BOUNDARY", "no boundary files given or found");
  const bool by_mask = b.net.mask != "alpha";
  check_batch_request(b, by_mask);
  const solvers::SolverInfo* solver = solver_from_name(b.net.solver);
  const std::vector<BoundaryFile> boundaries = read_batch_inputs(b, files, solver, by_mask);

  OutputSet out(b.out_dir, "--out");
  std::vector<Row> rows;
  std::vector<std::string> folders;
  for (size_t k = 0; k < boundaries.size(); ++k) {
    const Boundary& boundary = boundaries[k].boundary;
    // one folder per boundary and degree (a B-spline's: its net's, after the knots are made
    // compatible); a repeated one (same name and degree) gets a counter
    const BSplineInput* spline = boundaries[k].bspline ? &*boundaries[k].bspline : nullptr;
    const int m = spline ? spline->compatible.bottom.count() - 1 : boundary.m;
    const int n = spline ? spline->compatible.left.count() - 1 : boundary.n;
    std::string folder = fmt::format("{}-{}x{}", safe_file_stem(boundary.name), m, n);
    for (int copy = 2; std::find(folders.begin(), folders.end(), folder) != folders.end(); ++copy)
      folder = fmt::format("{}-{}x{}-{}", safe_file_stem(boundary.name), m, n, copy);
    folders.push_back(folder);
    if (boundaries[k].bspline) {
      run_bspline(b, boundaries[k], files[k], folder, out, rows, phases);
    } else if (by_mask) {
      run_stencil(b, b.net, boundaries[k], files[k], folder, out, rows, phases);
    } else if (!is_classical(boundaries[k])) {
      // two data rings or a free grid: every α over the whole problem; no closed-form Coons net
      for (double a : b.alphas) {
        NetRequest request = b.net;
        request.alpha = a;
        run_stencil(b, request, boundaries[k], files[k], folder, out, rows, phases);
      }
    } else {
      run_classical(b, boundaries[k], files[k], folder, out, rows, phases);
    }
  }
  const std::string table = metrics_table(rows);
  out.write("metrics.md", [&](std::ostream& o) {
    o << "# coons batch: metrics of every boundary given\n\n"
      << (by_mask ? "Every net is the stencil solve of the mask named in the method column (--mask " + b.net.mask +
                        ", over each file's whole problem: ribbons, rings, free grid). "
                  : std::string("Coons = closed-form discrete Coons net; alpha = mask solve (for a file with two "
                                "data rings or a free grid: over its whole problem, and no Coons row, the closed "
                                "form needs one ring). "))
      << "Energies are exact integrals "
         "of the Bézier surface (docs/math.md §5); mask res. is the residual of the row's own mask.\n\n"
      << table;
  });
  out.publish([&] {
    print_text(table + '\n' +
               fmt::format("{} boundaries, {} nets; results in {}/ (per boundary and degree a folder NAME-MxN/ with "
                           "{} and their .surface.obj, .net.obj; the table in metrics.md)\n",
                           boundaries.size(), rows.size(), b.out_dir,
                           by_mask ? "a solve report named by the mask" : "coons.json and alpha±A.json reports"));
  });
  for (const auto& r : rows)
    if (r.status != "success" && r.status != "closed-form") return kExitSolverFailed;
  return kExitOk;
}

}  // namespace

void register_batch(CLI::App& app, Registry& registry) {
  auto request = std::make_shared<BatchRequest>();
  auto* cmd = app.add_subcommand("batch",
                                 "solve many boundaries as Coons net and at several alpha; "
                                 "write nets and OBJ files and a metrics table");
  cmd->add_option("BOUNDARY", request->inputs, "boundary files or folders of them")->required();
  cmd->add_option("--out", request->out_dir, "output folder")->capture_default_str();
  request->alphas_option =
      cmd->add_option("--alphas", request->alphas, "alpha values to solve at (each once; --mask alpha only)")
          ->transform(fold_negative_zero())
          ->capture_default_str();
  cmd->add_option("--samples", request->samples, "surface samples per direction")->capture_default_str();
  add_solver_option(*cmd, request->net.solver);
  add_mask_options(*cmd, request->net);
  request->net.threads_option = add_threads_option(*cmd, request->net.threads);
  add_memory_option(*cmd, request->global);
  set_example(*cmd,
              "coons batch data/boundaries --alphas -0.25 -0.1 0 --out out/batch\n"
              "  coons batch data/boundaries/*_ribbons.json --mask c1-family --weight 0.5 --out out/c1");
  registry.add(cmd, [request] { return run_batch(*request); });
}

}  // namespace coons::cli
