// `coons import-step` and `coons export --step/--iges` (docs/cad.md).
#include "cad_commands.h"

#include <filesystem>
#include <memory>

#include "coons/config.h"
#include "coons/io/input_error.h"
#if COONS_HAVE_OCCT
#include "coons/cad/cad_surface.h"
#include "coons/cad/step_import.h"
#endif

namespace coons::cli {

namespace {

constexpr const char* kNoOcct =
    "this coons was built without OpenCASCADE (apt-get install libocct-data-exchange-dev "
    "libocct-modeling-algorithms-dev, then reconfigure; docs/cad.md)";

struct ImportRequest {
  std::string file, out, name;
  int face = -1;  // −1: not given (StepImportOptions' convention)
  bool face_given = false;
  std::vector<int> edges;
  double gap_tolerance = 1e-6;
  bool force = false;
};

#if COONS_HAVE_OCCT
// An InputError unless the import's options are valid, naming the option that set the one at fault.
void require_valid_import_options(const cad::StepImportOptions& options) {
  using F = cad::StepImportOptionsField;
  const cad::StepImportOptionsProblem problem = cad::options_problem(options);
  switch (problem.field) {
    case F::kNone:
      return;
    case F::kFace:
      throw InputError("command line", "--face", problem.reason);
    case F::kEdges:
      throw InputError("command line", "--edges", problem.reason);
    case F::kFaceOrEdges:
      throw InputError("command line", "--face/--edges", "give exactly one of --face K and --edges a,b,c,d");
    case F::kGapTolerance:
      throw InputError("command line", "--gap-tolerance", problem.reason);
  }
}
#endif

int run_import_step(const ImportRequest& q) {
#if COONS_HAVE_OCCT
  if (q.out.empty()) throw InputError("command line", "--out", "is required (the boundary file to write)");
  // a given -1 would read as "not given" below (and be blamed on --edges)
  if (q.face_given && q.face < 0) throw InputError("command line", "--face", "must be >= 0 (faces count from 0)");
  cad::StepImportOptions options;
  options.face = q.face;
  options.edges = q.edges;
  options.gap_tolerance = q.gap_tolerance;
  require_valid_import_options(options);
  require_new_file(q.out, q.force, "--out");
  const cad::StepImport import = cad::import_step_boundary(q.file, options);
  const std::string what = q.face >= 0 ? "face " + std::to_string(q.face) : "4 edges";
  const std::string name = q.name.empty() ? std::filesystem::path(q.file).stem().string() +
                                                (q.face >= 0 ? "-face" + std::to_string(q.face) : "")
                                          : q.name;
  const nlohmann::json doc = cad::boundary_document(import, name, "coons import-step " + q.file + " (" + what + ")");
  OutputSet out(".", "--out");
  out.write_path(q.out, [&](std::ostream& o) { o << doc.dump(2) << '\n'; });
  nlohmann::json report = {{"file", q.file}, {"boundary", name}, {"import", cad::import_note(import)}};
  report["written"] = {q.out};
  out.publish([&] { print_json(report); });
  return kExitOk;
#else
  (void)q;
  throw InputError("command line", "import-step", kNoOcct);
#endif
}

}  // namespace

void add_cad_export_options(CLI::App& cmd, CadExportRequest& r) {
  cmd.add_option("--step", r.step, "also write the net as a B-spline surface to this STEP file (OpenCASCADE)");
  cmd.add_option("--iges", r.iges, "also write the net as a B-spline surface to this IGES file (OpenCASCADE)");
}

void check_cad_export(const CadExportRequest& r, bool force) {
  const std::string option = r.step.empty() ? "--iges" : "--step";
  if (!COONS_HAVE_OCCT) throw InputError("command line", option, kNoOcct);
  for (const std::string* path : {&r.step, &r.iges})
    if (!path->empty()) require_new_file(*path, force, path == &r.step ? "--step" : "--iges");
  if (!r.step.empty() && !r.iges.empty() && same_file_path(r.step, r.iges))
    throw InputError("command line", "--iges", "is the same file as --step");
}

BSplineSurface bezier_surface_for_cad(const ControlNet& net) {
#if COONS_HAVE_OCCT
  return cad::bezier_as_bspline(net);
#else
  (void)net;
  throw InputError("command line", "--step", kNoOcct);
#endif
}

std::vector<std::string> write_cad_export(const CadExportRequest& r, const BSplineSurface& surface, OutputSet& out) {
#if COONS_HAVE_OCCT
  std::vector<std::string> written;
  if (!r.step.empty()) {
    cad::check_writable(surface, r.step, "--step");
    out.write_path(r.step, [&](std::ostream& o) { cad::write_step_surface(o, surface, r.step, "--step"); });
    written.push_back(r.step);
  }
  if (!r.iges.empty()) {
    cad::check_writable(surface, r.iges, "--iges");
    out.write_path(r.iges, [&](std::ostream& o) { cad::write_iges_surface(o, surface, r.iges, "--iges"); });
    written.push_back(r.iges);
  }
  return written;
#else
  (void)surface, (void)out;
  throw InputError("command line", r.step.empty() ? "--iges" : "--step", kNoOcct);
#endif
}

void register_import_step(CLI::App& app, Registry& registry) {
  auto q = std::make_shared<ImportRequest>();
  auto* cmd = app.add_subcommand("import-step", "a boundary file from four edges of a STEP file (OpenCASCADE)");
  cmd->add_option("FILE", q->file, "STEP file (.step, .stp)")->required();
  auto* face = cmd->add_option("--face", q->face, "the outer wire of face K (0-based, OpenCASCADE's order)");
  auto* edges = cmd->add_option("--edges", q->edges, "four edges a,b,c,d (0-based), any order and orientation")
                    ->delimiter(',')
                    ->expected(4)
                    ->check(int_item());
  face->excludes(edges);
  cmd->add_option("--out", q->out, "the boundary file to write (docs/formats.md)")->required();
  cmd->add_option("--name", q->name, "the boundary's name (default: the file's stem and the face)");
  cmd->add_option("--gap-tolerance", q->gap_tolerance,
                  "largest corner gap, as a fraction of the bounding-box diagonal of the poles")
      ->capture_default_str();
  cmd->add_flag("--force", q->force, "overwrite an existing --out file");
  set_example(*cmd, "coons import-step data/cad/bspline_patch.step --face 0 --out patch.json");
  registry.add(cmd, [q, face] {
    q->face_given = face->count() > 0;
    return run_import_step(*q);
  });
}

}  // namespace coons::cli
