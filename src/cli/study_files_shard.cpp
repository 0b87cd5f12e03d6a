// `coons study FILES --shard I/N` and the merge of its shards (study_shard.h): one task per
// boundary file, whose record carries that file's part of the study (coons/study/study_json.h; a
// B-spline file's row in "bspline"), so that the merge rebuilds the unsharded run's StudyResult
// and B-spline rows and writes its report with the same writer (docs/formats.md, "Sharded studies").
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <vector>

#include "common.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/tri_boundary_io.h"
#include "coons/io/write_files.h"
#include "coons/study/provenance.h"
#include "coons/study/report_markdown.h"
#include "coons/study/study_conclusions.h"
#include "coons/study/study_json.h"
#include "coons/study/task_key.h"
#include "study_shard.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

void write_study_report(const StudyResult& result, const std::string& out_dir, const std::string& command_line,
                        const std::function<std::string(OutputSet&)>& extra) {
  OutputSet out(out_dir, "--out");
  const StudyFigures figures = plot_study_figures(result, [&](const std::string& file) { return out.stage(file); });
  for (const auto* list : {&figures.energies, &figures.nets})
    for (const StudyFigure& f : *list)
      if (!f.error.empty()) out.discard(f.file);
  for (const StudyFigure* f : {&figures.alpha_vs_degree, &figures.mu_vs_degree})
    if (!f->error.empty()) out.discard(f->file);
  const std::string md = study_report_markdown(result, current_provenance(command_line), figures) + "\n" +
                         study_conclusions_markdown(result) + "\n" + tri_study_markdown(result.triangles, "6") +
                         (extra ? extra(out) : std::string());
  out.write("results.json", [&](std::ostream& o) { o << dump(study_results_json(result), 1) << '\n'; });
  out.write("report.md", [&](std::ostream& o) { o << md; });
  out.publish([&] { print_text(md + '\n' + fmt::format("report: {}\n", out.path_of("report.md") + "")); });
}

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot be read");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A task's result without its timings ("seconds" at any depth): two runs of one task may differ
// there and nowhere else, the searches being deterministic.
json without_seconds(const json& j) {
  if (j.is_object()) {
    json out = json::object();
    for (const auto& [key, value] : j.items())
      if (key != "seconds") out[key] = without_seconds(value);
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (const json& value : j) out.push_back(without_seconds(value));
    return out;
  }
  return j;
}

std::vector<std::string> objective_names(const StudyOptions& options) {
  std::vector<std::string> out;
  for (const Objective& o : options.objectives.empty() ? default_study_objectives() : options.objectives)
    out.push_back(o.name);
  return out;
}

// Every input of the study but the files' contents (those are in each task's key).
json files_study_json(const std::vector<std::string>& files, const StudyOptions& o, double corner_tolerance,
                      const Provenance& p) {
  return {{"inputs", "files"},
          {"files", files},
          {"degrees", o.degrees},
          {"objectives", objective_names(o)},
          {"curve_points", o.curve_points},
          {"reference_alphas", o.reference_alphas},
          {"corner_tolerance", corner_tolerance},
          {"solver", o.solver ? o.solver->name : std::string("auto")},
          {"coons", {{"version", p.version}, {"git_revision", p.git_revision}}}};
}

std::string degree_list(const std::vector<int>& degrees) { return fmt::format("[{}]", fmt::join(degrees, ", ")); }

// The degrees of a record's results must be the study's (the key covers the study block, not the
// results, so an edited block passes it): a shape's degree law has the study's degrees from its
// first on (the shape's own degree and above, every one for a shape given by curves), its fit
// deviations every one, a triangle's rows its own degree and then the study's degrees above it.
// Else the report's columns would be the block's degrees and every cell "–".
void check_part_degrees(const StudyResult& part, const std::vector<int>& degrees, const std::string& where) {
  const auto tail_from = [&](int lowest) {
    std::vector<int> out;
    for (int d : degrees)
      if (d >= lowest) out.push_back(d);
    return out;
  };
  const auto refuse = [&](const std::string& what, const std::vector<int>& has) {
    throw InputError(
        where, "study.degrees",
        fmt::format("{} are not the degrees of the results: {} has {}", degree_list(degrees), what, degree_list(has)));
  };
  for (const DegreeLawEntry& l : part.laws) {
    std::vector<int> has;
    for (const DegreeCell& c : l.cells) has.push_back(c.degree);
    if (!has.empty() && has != tail_from(has.front())) refuse(l.boundary + " " + l.objective, has);
  }
  for (const FitDeviationEntry& f : part.fit_deviations) {
    std::vector<int> has;
    for (const auto& [d, deviation] : f.max_deviation) has.push_back(d);
    if (has != degrees) refuse(f.boundary + " (fit deviations)", has);
  }
  for (const TriStudyEntry& t : part.triangles)
    for (const TriStudyRow& r : t.rows) {
      std::vector<int> has;
      for (const TriStudyCell& c : r.cells) has.push_back(c.degree);
      if (has.empty()) refuse(t.file + " " + r.objective, has);
      std::vector<int> expected = tail_from(has.front() + 1);
      expected.insert(expected.begin(), has.front());
      if (has != expected) refuse(t.file + " " + r.objective, has);
    }
}

}  // namespace

int run_files_shard(const std::vector<std::string>& files, const StudyOptions& options, double corner_tolerance,
                    int shard, int shards, const std::string& out_dir) {
  Phases phases("study");
  const Provenance p = current_provenance("");
  const json study = files_study_json(files, options, corner_tolerance, p);
  BoundaryReadOptions read_options;
  read_options.min_model_size = kMinModelSize;  // the searches
  read_options.corner_tolerance = corner_tolerance;
  // Every file of the shard read (once) before the shard file is made: a bad one fails the run
  // with nothing written, as the unsharded study does (an empty shard file and its folder stayed).
  // Its content key is taken at the same time, so that a task is keyed by the bytes it was run on.
  struct Task {
    size_t index = 0;
    std::string content;                   // fnv1a_hex of the file's bytes
    std::optional<TriStudyInput> tri;      // a triangular boundary file
    std::optional<BoundaryFile> boundary;  // otherwise
  };
  std::vector<Task> tasks;
  for (size_t t = size_t(shard); t < files.size(); t += size_t(shards)) {
    Task& task = tasks.emplace_back();
    task.index = t;
    task.content = fnv1a_hex(file_bytes(files[t]));
    if (is_triangle_file(files[t]))
      task.tri = read_tri_study_input(files[t], corner_tolerance);
    else
      task.boundary = read_boundary_file(files[t], read_options);
  }
  std::set<std::string> done;
  const fs::path path = open_shard_file(out_dir, shard, shards, study, &done);
  std::ofstream o(path, std::ios::binary | std::ios::app);
  if (!o) throw InputError(path.string(), "--out", "cannot be written");
  phases.start("solve");
  size_t skipped = 0, ran = 0;
  for (const Task& task : tasks) {
    const size_t t = task.index;
    const std::string& file = files[t];
    const std::string& content = task.content;
    const std::string key = files_task_key(study, t, content);
    if (done.count(key)) {
      ++skipped;
      continue;
    }
    phases.note(file);
    const auto start = std::chrono::steady_clock::now();
    StudyResult part;
    std::vector<BSplineStudyRow> bspline;  // a B-spline file's row (its own knots, no degrees)
    if (task.tri) {
      part.triangles = run_tri_study({*task.tri}, options.degrees, options.solver);
    } else if (const BoundaryFile& b = *task.boundary; b.bspline) {
      bspline = run_bspline_study({{file, b.boundary.name, *b.bspline}}, default_study_objectives(),
                                  bspline_row_solver(options.solver));
    } else {
      part = run_study({read_study_input(file, b)}, options);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    json record{{"key", key},        {"study", study},     {"index", t},
                {"file", file},      {"content", content}, {"result", study_part_json(part)},
                {"seconds", seconds}};
    if (!bspline.empty()) record["bspline"] = bspline_rows_json(bspline);
    o << dump(record) << '\n' << std::flush;
    if (!o) throw InputError(path.string(), "--out", "cannot be written");
    done.insert(key);
    ++ran;
  }
  print_text(fmt::format("shard {}/{}: {} tasks, {} already there, {} run; {}\n", shard, shards, tasks.size(), skipped,
                         ran, path.string()));
  return kExitOk;
}

std::optional<bool> is_files_study_shard(const fs::path& file) {
  const ShardFile f = read_shard_file(file);
  if (f.records.empty()) return std::nullopt;
  // (value("inputs", "") of a number threw a JSON type_error that named no field: a comparison does not)
  const json& first = f.records.front();
  return first.contains("study") && first["study"].is_object() && first["study"].contains("inputs") &&
         first["study"]["inputs"] == "files";
}

int run_files_merge(const std::vector<fs::path>& files, const std::string& merge_dir, const std::string& out_dir) {
  Phases phases("study");
  phases.start("read");
  std::optional<json> study;
  std::map<size_t, json> by_index;
  std::map<size_t, std::string> file_of;  // the shard file each record came from, for its errors
  for (const fs::path& file : files) {
    const std::string where = file.string();
    for (const json& r : read_shard_file(file).records) {
      if (!r.contains("study")) throw InputError(where, "study", "missing");
      if (!study) {
        study = r["study"];
        // the names are read for the messages below: a list of anything else is no study of coons's
        const json* names = study->contains("files") ? &(*study)["files"] : nullptr;
        if (!names || !names->is_array() ||
            !std::all_of(names->begin(), names->end(), [](const json& f) { return f.is_string(); }))
          throw InputError(where, "study.files", "missing or not a list of file names");
      } else if (r["study"] != *study) {
        throw InputError(where, "study", "the shards hold tasks of different studies (options or coons revision)");
      }
      if (!r.contains("index") || !r["index"].is_number_unsigned() || !r.contains("content") ||
          !r["content"].is_string() || !r.contains("result"))
        throw InputError(where, "index", "a record without index, content or result");
      const size_t index = r["index"].get<size_t>();
      if (!(*study)["files"].is_array() || index >= (*study)["files"].size())
        throw InputError(where, "index", fmt::format("{} is outside the study's file list", index));
      if (r["key"] != files_task_key(*study, index, r["content"].get<std::string>()))
        throw InputError(where, "key",
                         fmt::format("'{}' is not the key of its task ({})", r["key"].get<std::string>(),
                                     (*study)["files"][index].get<std::string>()));
      // a task run twice over different contents (the file was edited between runs of its shard):
      // neither record can be told to be the current one
      if (const auto seen = by_index.find(index); seen != by_index.end() && seen->second["key"] != r["key"])
        throw InputError(where, "key",
                         fmt::format("task {} ({}) was run on two different contents of its file; remove the "
                                     "shard files and run the shards again",
                                     index, (*study)["files"][index].get<std::string>()));
      // the same task twice (shards of different N mixed): the same result, or an edited record,
      // and the first one read would silently win
      if (const auto seen = by_index.find(index); seen != by_index.end()) {
        const json kept = without_seconds(seen->second["result"]), now = without_seconds(r["result"]);
        if (kept != now) {
          const json patch = json::diff(kept, now);
          throw InputError(where, "key",
                           fmt::format("task {} ({}) is in the shards twice with different results (first at "
                                       "result{}, also in {}); remove the shard files and run the shards again",
                                       index, (*study)["files"][index].get<std::string>(),
                                       patch.empty() ? std::string() : patch[0].value("path", ""), file_of[index]));
        }
      }
      if (by_index.emplace(index, r).second) file_of.emplace(index, where);
    }
  }
  if (!study) throw InputError(merge_dir, "--merge", "the shards hold no finished task");
  const size_t count = (*study)["files"].size();
  if (by_index.size() != count) {
    size_t first = 0;
    while (by_index.count(first)) ++first;
    throw InputError(merge_dir, "--merge",
                     fmt::format("{} of {} tasks are missing (the first: {}); run their shards (again) before merging",
                                 count - by_index.size(), count, (*study)["files"][first].get<std::string>()));
  }
  StudyResult result;
  const std::string first = file_of.begin()->second;
  const json& degrees = (*study).contains("degrees") ? (*study)["degrees"] : json();
  if (!degrees.is_array()) throw InputError(first, "study.degrees", "missing or not a list");
  for (size_t k = 0; k < degrees.size(); ++k)  // json_int, not get<int>: 1e300 is no int
    result.degrees.push_back(json_int(degrees[k], first, fmt::format("study.degrees[{}]", k), 1));
  {
    StudyOptions valid;  // the degrees as a study takes them: some, increasing, each once, in [2, 200]
    valid.degrees = result.degrees;
    if (std::string why; !valid.is_valid(&why)) throw InputError(first, "study.degrees", why);
  }
  try {
    result.objectives = (*study).at("objectives").get<std::vector<std::string>>();
  } catch (const json::exception&) {
    throw InputError(first, "study", "objectives malformed");
  }
  std::vector<BSplineStudyRow> bspline_rows;  // in the files' order, as the unsharded run has them
  for (const auto& [index, record] : by_index) {
    StudyResult part;
    append_study_part(record["result"], file_of[index], &part);
    check_part_degrees(part, result.degrees, file_of[index]);
    const auto append = [](auto& from, auto& to) { std::move(from.begin(), from.end(), std::back_inserter(to)); };
    append(part.shapes, result.shapes);
    append(part.laws, result.laws);
    append(part.fit_deviations, result.fit_deviations);
    append(part.references, result.references);
    append(part.triangles, result.triangles);
    if (record.contains("bspline")) append_bspline_rows(record["bspline"], file_of[index], &bspline_rows);
  }
  phases.start("write");
  write_study_report(result, out_dir, fmt::format("coons study --merge {} --out {}", merge_dir, out_dir),
                     [&](OutputSet& out) { return write_bspline_rows(bspline_rows, out); });
  print_text(fmt::format("merged {} tasks from {} shard files\n", count, files.size()));
  return study_exit_status(result, bspline_rows);
}

}  // namespace coons::cli
