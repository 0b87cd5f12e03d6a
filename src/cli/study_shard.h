// `coons study --family … --shard I/N --out DIR` and `coons study --merge DIR --out REPORT_DIR`:
// the family study's tasks (coons/study/family_tasks.h) split into shards written as JSON Lines,
// resumed by key, and merged into the report an unsharded run writes (docs/formats.md,
// "Sharded studies").
#pragma once

#include <string>
#include <vector>

#include "coons/study/alpha_family.h"

namespace coons::cli {

//! report.md, figures/ and results.json of a family study, staged and published together; the
//! report is also printed.
void write_family_report(const AlphaFamilyResult& result, const std::string& out_dir);

//! Runs the tasks of shard `shard` of `shards` not yet in DIR/shard-I-of-N.jsonl and appends them.
int run_family_shard(const AlphaFamilyOptions& options, int shard, int shards, const std::string& out_dir);

//! Reads every DIR/shard-*-of-*.jsonl, checks that they hold one study with every task, and writes
//! its report to `out_dir`.
int run_study_merge(const std::string& merge_dir, const std::string& out_dir);

}  // namespace coons::cli
