// `coons study --family … --shard I/N --out DIR` and `coons study --merge DIR --out REPORT_DIR`:
// the family study's tasks (coons/study/family_tasks.h) split into shards written as JSON Lines,
// resumed by key, and merged into the report an unsharded run writes (docs/formats.md,
// "Sharded studies").
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "coons/io/shard_file.h"
#include "coons/io/write_files.h"
#include "coons/study/alpha_family.h"
#include "coons/study/bspline_study.h"
#include "coons/study/study.h"
#include "coons/study/study_failures.h"
#include "coons/study/task_key.h"

namespace coons::cli {

//! OUT/shard-I-of-N.jsonl made ready for appending: `done` receives the keys already there, an
//! unfinished last line is dropped; a file of another `study` is an input error.
std::filesystem::path open_shard_file(const std::string& out_dir, int shard, int shards, const nlohmann::json& study,
                                      std::set<std::string>* done);

//! report.md, figures/ and results.json of a family study, staged and published together; the
//! report is also printed.
void write_family_report(const AlphaFamilyResult& result, const std::string& out_dir);

//! Runs the tasks of shard `shard` of `shards` not yet in DIR/shard-I-of-N.jsonl and appends them.
int run_family_shard(const AlphaFamilyOptions& options, int shard, int shards, const std::string& out_dir);

//! Reads every DIR/shard-*-of-*.jsonl, checks that they hold one study with every task, and writes
//! its report to `out_dir`.
int run_study_merge(const std::string& merge_dir, const std::string& out_dir);

// ---- boundary-file studies (study_files_shard.cpp) ----

//! report.md, figures/ and results.json of the per-shape study, staged and published together;
//! the report is also printed. `command_line` goes into the report's provenance line.
//! `extra` (optional) writes more files to the same output set and returns Markdown to append.
void write_study_report(const StudyResult& result, const std::string& out_dir, const std::string& command_line,
                        const std::function<std::string(OutputSet&)>& extra = {});

//! The B-spline rows' share of a per-shape study's output: `bspline.json` into `out` and the
//! Markdown section to append to the report ("" without rows). The same for a run and a merge.
std::string write_bspline_rows(const std::vector<BSplineStudyRow>& rows, OutputSet& out);

//! The exit status of a per-shape study whose report is written: kExitSolverFailed with one
//! `error:` line on standard error naming the first failed solve (study_failures.h), else kExitOk.
int study_exit_status(const StudyResult& result, const std::vector<BSplineStudyRow>& bspline_rows);

//! The exit status of any study whose report is written: kExitSolverFailed with one `error:` line
//! naming the first of `failures` (and how many more), else kExitOk.
int failures_exit_status(const std::vector<StudyFailure>& failures);

//! The backend of the B-spline rows for the study's --solver: a backend that works from a grid
//! stencil cannot take the non-uniform system, so "" (auto, auto_bspline_solver) then.
std::string bspline_row_solver(const solvers::SolverInfo* solver);

//! `coons study FILES --shard I/N`: one task per input file (in the order given), task t in shard
//! t mod N; every file is read and checked first.
int run_files_shard(const std::vector<std::string>& files, const StudyOptions& options, double corner_tolerance,
                    int shard, int shards, const std::string& out_dir);

//! Whether the first record of this shard file belongs to a boundary-file study; nullopt when the
//! file holds no complete record (a shard stopped during its first task).
std::optional<bool> is_files_study_shard(const std::filesystem::path& file);

//! The per-shape study's report from the shard files of a boundary-file study.
int run_files_merge(const std::vector<std::filesystem::path>& files, const std::string& merge_dir,
                    const std::string& out_dir);

}  // namespace coons::cli
