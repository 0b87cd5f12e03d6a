// libFuzzer target: the records of the shard files `coons study --merge DIR` reads
// (docs/formats.md "Sharded studies"). The bytes are split into records by parse_shard_lines
// (coons/io/shard_file.h), which read_shard_file calls for the merge, and every record is then
// read as the merge reads it
// (the key check left out: a fuzzer cannot forge the hashes):
//   a boundary-file study ("study": {"inputs": "files", ...}): study.degrees through json_int and
//   StudyOptions::is_valid, study.objectives, then append_study_part("result") and
//   append_bspline_rows("bspline"), and the report text a merge writes from them (markdown, results.json);
//   a family study: family_options_of("study"), family_tasks, family_task_from_record.
// An InputError is the expected answer to bad bytes; anything else escaping (another exception, a
// crash, UB) is a finding.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/shard_file.h"
#include "coons/study/bspline_study.h"
#include "coons/study/family_tasks.h"
#include "coons/study/provenance.h"
#include "coons/study/report_markdown.h"
#include "coons/study/study.h"
#include "coons/study/study_conclusions.h"
#include "coons/study/study_json.h"
#include "coons/study/tri_study.h"

namespace {

using nlohmann::json;

// One scratch file per process for the figures, in memory where the system has /dev/shm.
const std::string& scratch_path() {
  static const std::string path = [] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
    return std::string(dir) + "/coons_fuzz_shard_" + std::to_string(getpid()) + ".png";
  }();
  return path;
}

void files_record(const json& r) {
  const json& study = r.at("study");
  coons::StudyResult result;
  const json degrees = study.contains("degrees") ? study.at("degrees") : json();
  if (!degrees.is_array()) return;
  for (std::size_t k = 0; k < degrees.size(); ++k)
    result.degrees.push_back(coons::json_int(degrees[k], "fuzz", "study.degrees", 1));
  coons::StudyOptions valid;
  valid.degrees = result.degrees;
  if (std::string why; !valid.is_valid(&why)) return;
  if (!study.contains("objectives") || !study.at("objectives").is_array()) return;
  for (const json& o : study.at("objectives"))
    if (!o.is_string()) return;
  result.objectives = study.at("objectives").get<std::vector<std::string>>();
  if (!r.contains("result")) return;
  coons::append_study_part(r.at("result"), "fuzz", &result);
  std::vector<coons::BSplineStudyRow> rows;
  if (r.contains("bspline")) coons::append_bspline_rows(r.at("bspline"), "fuzz", &rows);
  // what the merge writes: the figures (drawn into one scratch file), the report, results.json
  const coons::StudyFigures figures =
      coons::plot_study_figures(result, [](const std::string&) { return scratch_path(); });
  (void)coons::study_report_markdown(result, coons::Provenance{}, figures);
  (void)coons::study_conclusions_markdown(result);
  (void)coons::tri_study_markdown(result.triangles, "6");
  (void)coons::study_results_json(result).dump();
  (void)coons::bspline_study_markdown(rows);
}

void family_record(const json& r) {
  std::vector<std::string> objectives;
  const coons::AlphaFamilyOptions options = coons::family_options_of(r.at("study"), &objectives, "fuzz");
  if (objectives.size() * options.degrees.size() * std::size_t(options.count) > 100000) return;  // memory only
  (void)coons::family_tasks(options, objectives);
  (void)coons::family_task_from_record(r, options, "fuzz");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const json& j : coons::parse_shard_lines(text, "fuzz").records) {
    if (!j.contains("study")) continue;  // the merge: InputError "study: missing"
    try {
      // the merge keeps the first record's study block by value and compares every later one to it
      const json study = j["study"];
      if (study != j["study"]) return 0;
      // (as is_files_study_shard tests it: a comparison, which no type of "inputs" makes throw)
      if (study.is_object() && study.contains("inputs") && study["inputs"] == "files")
        files_record(j);
      else
        family_record(j);
    } catch (const coons::InputError&) {
    }
  }
  return 0;
}
