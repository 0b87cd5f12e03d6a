// `coons study --shard I/N` and `coons study --merge DIR` (study_shard.h).
#include "study_shard.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <tuple>

#include "common.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/write_files.h"
#include "coons/study/family_tasks.h"
#include "coons/study/provenance.h"

namespace coons::cli {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string revision_of(const Provenance& p) { return p.git_revision; }

// Equal, or both NaN (a value not measured).
bool same_task_number(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

fs::path open_shard_file(const std::string& out_dir, int shard, int shards, const json& study,
                         std::set<std::string>* done) {
  const fs::path dir(out_dir);
  if (fs::exists(dir) && !fs::is_directory(dir)) throw InputError(out_dir, "--out", "exists and is not a folder");
  fs::path path = dir / fmt::format("shard-{}-of-{}.jsonl", shard, shards);
  ShardFile existing;
  if (fs::exists(path)) {
    // (a device or a pipe under the shard's name would be read without end: /dev/zero grew to 9 GB)
    if (!fs::is_regular_file(path))
      throw InputError(path.string(), "--out", "exists and is not a regular file: a shard file is one");
    existing = read_shard_file(path);
    for (const json& r : existing.records) {
      if (!r.contains("study") || r["study"] != study)
        throw InputError(path.string(), "study",
                         "holds tasks of another study (other options or another coons revision); give another "
                         "--out or remove the file");
      done->insert(r["key"].get<std::string>());
    }
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError(out_dir, "--out", "cannot be created: " + ec.message());
  if (!existing.clean) {  // drop the unfinished last line (and anything unreadable) before appending
    const fs::path tmp = path.string() + ".tmp";
    {
      std::ofstream o(tmp, std::ios::binary | std::ios::trunc);
      for (const std::string& line : existing.lines) o << line << '\n';
      if (!o) throw InputError(tmp.string(), "--out", "cannot be written");
    }
    fs::rename(tmp, path, ec);
    if (ec) throw InputError(path.string(), "--out", "cannot be replaced: " + ec.message());
  }
  return path;
}

void write_family_report(const AlphaFamilyResult& result, const std::string& out_dir) {
  OutputSet out(out_dir, "--out");
  std::vector<std::string> figures;
  for (const char* kind : {"alpha", "mu", "loss"})
    for (const std::string& o : result.objectives) figures.push_back(fmt::format("figures/{}_family_{}.png", kind, o));
  const std::vector<std::string> errors = plot_alpha_family(result, [&](size_t i) { return out.stage(figures[i]); });
  for (size_t i = 0; i < figures.size(); ++i)
    if (i >= errors.size() || !errors[i].empty()) {
      if (i < errors.size()) out.discard(figures[i]);
      figures[i].clear();
    }
  const std::string md = alpha_family_markdown(result, figures);
  out.write("results.json", [&](std::ostream& o) { o << dump(alpha_family_json(result), 1) << '\n'; });
  out.write("report.md", [&](std::ostream& o) { o << md; });
  out.publish([&] { print_text(md + '\n' + fmt::format("report: {}\n", out.path_of("report.md") + "")); });
}

int run_family_shard(const AlphaFamilyOptions& options, int shard, int shards, const std::string& out_dir) {
  Phases phases("study");
  std::vector<std::string> objectives;
  if (options.objectives.empty())
    objectives = {"thin_plate", "e3"};
  else
    for (const Objective& o : options.objectives) objectives.push_back(o.name);
  const Provenance p = current_provenance("");
  const json study = family_study_json(options, objectives, p.version, revision_of(p));
  const std::vector<FamilyTask> mine = shard_tasks(family_tasks(options, objectives), shard, shards);

  std::set<std::string> done;
  const fs::path path = open_shard_file(out_dir, shard, shards, study, &done);
  std::ofstream o(path, std::ios::binary | std::ios::app);
  if (!o) throw InputError(path.string(), "--out", "cannot be written");
  phases.start("solve");
  int ran = 0, skipped = 0;
  double seconds = 0;
  for (size_t t = 0; t < mine.size(); ++t) {
    const std::string key = family_task_key(options, mine[t], p.version, revision_of(p));
    if (done.count(key)) {
      ++skipped;
      continue;
    }
    phases.note(fmt::format("{}/{}", t + 1, mine.size()));
    const FamilyTaskResult r = run_family_task(options, mine[t]);
    o << dump(family_task_record(study, key, r)) << '\n' << std::flush;
    if (!o) throw InputError(path.string(), "--out", "cannot be written");
    done.insert(key);
    seconds += r.seconds;
    ++ran;
  }
  print_text(fmt::format("shard {}/{}: {} tasks, {} already there, {} run ({:.3g} s of task time); {}\n", shard, shards,
                         mine.size(), skipped, ran, seconds, path.string()));
  return kExitOk;
}

namespace {

using TaskKey = std::tuple<std::string, int, int>;  // objective, degree, boundary index

// The shard-I-of-N.jsonl files of a folder, sorted.
std::vector<fs::path> shard_files(const std::string& merge_dir) {
  if (!fs::is_directory(merge_dir)) throw InputError(merge_dir, "--merge", "is not a folder");
  const std::regex shard_name(R"(shard-[0-9]+-of-[0-9]+\.jsonl)");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(merge_dir))
    if (e.is_regular_file() && std::regex_match(e.path().filename().string(), shard_name)) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(merge_dir, "--merge", "holds no shard-I-of-N.jsonl file");
  return files;
}

// What the shards of a family study hold: its block, options and every task's result.
struct FamilyShards {
  std::optional<json> study;
  AlphaFamilyOptions options;
  std::vector<std::string> objectives;
  std::map<TaskKey, FamilyTaskResult> by_task;
};

FamilyShards read_family_shards(const std::vector<fs::path>& files) {
  FamilyShards out;
  std::string version, revision;
  for (const fs::path& file : files) {
    const std::string where = file.string();
    for (const json& r : read_shard_file(file).records) {
      if (!r.contains("study")) throw InputError(where, "study", "missing");
      if (!out.study) {
        out.study = r["study"];
        out.options = family_options_of(*out.study, &out.objectives, where);
        // (value() of a number where a string belongs threw a JSON type_error that named no field)
        const json coons = out.study->contains("coons") ? (*out.study)["coons"] : json::object();
        const auto text = [&](const char* name) {
          if (!coons.is_object()) throw InputError(where, "study.coons", "is not an object");
          if (!coons.contains(name)) return std::string();
          if (!coons[name].is_string()) throw InputError(where, std::string("study.coons.") + name, "is not a string");
          return coons[name].get<std::string>();
        };
        version = text("version");
        revision = text("git_revision");
      } else if (r["study"] != *out.study) {
        throw InputError(where, "study", "the shards hold tasks of different studies (options or coons revision)");
      }
      FamilyTaskResult t = family_task_from_record(r, out.options, where);
      if (r["key"] != family_task_key(out.options, t.task, version, revision))
        throw InputError(where, "key",
                         fmt::format("'{}' is not the key of its task (boundary {}, degree {}, {})",
                                     r["key"].get<std::string>(), t.task.index, t.task.degree, t.task.objective));
      // A task run by two shard files (shards of different N mixed) has the same result in both: the
      // searches are deterministic. Different results under one key mean an edited record, and
      // the first one read silently won.
      const auto [it, added] = out.by_task.emplace(std::make_tuple(t.task.objective, t.task.degree, t.task.index), t);
      const FamilyTaskResult& kept = it->second;
      if (!added && (kept.status != t.status || kept.alpha != t.alpha || !same_task_number(kept.value, t.value) ||
                     kept.grid.size() != t.grid.size() ||
                     !std::equal(kept.grid.begin(), kept.grid.end(), t.grid.begin(), same_task_number)))
        throw InputError(where, "key",
                         fmt::format("the task of boundary {}, degree {}, {} is in the shards twice with different "
                                     "results (alpha* {} and {})",
                                     t.task.index, t.task.degree, t.task.objective,
                                     kept.alpha ? fmt::format("{}", *kept.alpha) : "null",
                                     t.alpha ? fmt::format("{}", *t.alpha) : "null"));
    }
  }
  return out;
}

// An InputError unless the shards hold exactly the study's tasks. The study's list has objectives
// × degrees × count tasks (count up to 100000, 199 degrees, and as many objectives as a block
// names); it is built only once every task of it is known to be here: an edited block of 4 kB
// (count 100000, degrees 3 … 200) made the merge allocate 1.6 GB before it said that tasks were
// missing.
void require_every_task(const FamilyShards& shards, const std::string& merge_dir) {
  const AlphaFamilyOptions& options = shards.options;
  const std::vector<std::string>& objectives = shards.objectives;
  const std::set<int> degrees(options.degrees.begin(), options.degrees.end());
  const std::set<std::string> named(objectives.begin(), objectives.end());
  const auto in_list = [&](const TaskKey& t) {
    const auto& [objective, degree, index] = t;
    return index >= 0 && index < options.count && degrees.count(degree) > 0 && named.count(objective) > 0;
  };
  size_t inside = 0;
  for (const auto& [task, result] : shards.by_task) inside += in_list(task) ? 1 : 0;
  const size_t total = objectives.size() * options.degrees.size() * size_t(options.count);
  if (inside < total) {
    std::optional<FamilyTask> first_missing;
    for (const std::string& o : objectives) {
      for (int d : options.degrees) {
        for (int k = 0; k < options.count && !first_missing; ++k)
          if (!shards.by_task.count(std::make_tuple(o, d, k))) first_missing = FamilyTask{k, d, o};
        if (first_missing) break;
      }
      if (first_missing) break;
    }
    throw InputError(
        merge_dir, "--merge",
        fmt::format("{} of {} tasks are missing (the first: boundary {}, degree {}, {}); run their "
                    "shards (again) before merging",
                    total - inside, total, first_missing->index, first_missing->degree, first_missing->objective));
  }
  if (shards.by_task.size() != inside)
    throw InputError(merge_dir, "--merge",
                     fmt::format("the shards hold {} tasks outside the study's list", shards.by_task.size() - inside));
}

}  // namespace

int run_study_merge(const std::string& merge_dir, const std::string& out_dir) {
  Phases phases("study");
  phases.start("read");
  const std::vector<fs::path> files = shard_files(merge_dir);
  // The kind of study, from the first shard that holds a complete record (the others are read as
  // that kind; a shard stopped during its first task holds none and only adds missing tasks).
  for (const fs::path& file : files)
    if (const std::optional<bool> files_study = is_files_study_shard(file)) {
      if (*files_study) return run_files_merge(files, merge_dir, out_dir);
      break;
    }
  const FamilyShards shards = read_family_shards(files);
  if (!shards.study) throw InputError(merge_dir, "--merge", "the shards hold no finished task");
  require_every_task(shards, merge_dir);

  const std::vector<FamilyTask> all = family_tasks(shards.options, shards.objectives);
  std::vector<FamilyTaskResult> results;
  results.reserve(all.size());
  double seconds = 0;
  for (const FamilyTask& t : all) {
    const FamilyTaskResult& r = shards.by_task.at(std::make_tuple(t.objective, t.degree, t.index));
    seconds += r.seconds;
    results.push_back(r);
  }
  phases.start("write");
  const AlphaFamilyResult result = assemble_alpha_family(shards.options, shards.objectives, results);
  write_family_report(result, out_dir);
  print_text(fmt::format("merged {} tasks from {} shard files: {:.4g} s of task time, {:.3g} s per task\n", all.size(),
                         files.size(), seconds, seconds / double(all.size())));
  return failures_exit_status(family_failures(result));
}

}  // namespace coons::cli
