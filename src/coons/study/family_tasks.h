// The random-smooth family study (alpha_family.h) as a list of independent tasks, so that it can
// be split into shards, resumed and merged: one task is one boundary index × degree × objective ×
// parameter (α); its result is α*, the optimum's value, how the search ended and the objective on
// the family's logit grid of α (grid_points values over [−1/4 + 1e−6, 1/4 − 1e−6]), everything the
// aggregation (assemble_alpha_family) needs. A task's key is a hash of its inputs and of the coons
// version and git revision: equal keys, equal results. Sizes: one search and grid_points
// evaluations of one (n+1) × (n+1) net per task.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/study/alpha_family.h"

namespace coons {

struct FamilyTask {
  int index = 0;  //!< the boundary of the family
  int degree = 0;
  std::string objective;
};

//! Every task of a family study: objective-major, then degree, then boundary index.
std::vector<FamilyTask> family_tasks(const AlphaFamilyOptions& options, const std::vector<std::string>& objectives);

//! Shard `shard` of `shards` (0 ≤ shard < shards): the tasks numbered t with t mod shards == shard.
std::vector<FamilyTask> shard_tasks(const std::vector<FamilyTask>& all, int shard, int shards);

//! "I/N" → (I, N) with 0 ≤ I < N; nullopt (and `why`) otherwise.
std::optional<std::pair<int, int>> parse_shard(const std::string& text, std::string* why);

enum class FamilyTaskStatus { kInterior, kAtBound, kFlat, kFailed };
std::string to_string(FamilyTaskStatus s);

struct FamilyTaskResult {
  FamilyTask task;
  FamilyTaskStatus status = FamilyTaskStatus::kFailed;
  std::optional<double> alpha;  //!< α* (interior or on a bound)
  double value = 0;             //!< the objective at α*
  std::vector<double> grid;     //!< the objective at the grid's α (∞ where it failed); empty without α*
  double seconds = 0;           //!< how long the task took (not part of any comparison)
};

//! How a task's α* search ended, as the study of files judges searches (search_failed): kFailed
//! when it found no α* or its verdict rests on failed solves (solver_failed, failed_region,
//! not_applicable); a search that did not converge (not_converged) keeps its best α as α*.
FamilyTaskStatus family_task_status(const AlphaSearchSummary& s);

//! Computes one task (the boundary made alone: random_smooth_boundary is per index).
FamilyTaskResult run_family_task(const AlphaFamilyOptions& options, const FamilyTask& task);

//! What identifies the study a task belongs to (its options and coons's version and revision).
nlohmann::json family_study_json(const AlphaFamilyOptions& options, const std::vector<std::string>& objectives,
                                 const std::string& version, const std::string& revision);

//! 16 hex digits: FNV-1a (64 bit) of the task's inputs — family, seed, generator, index, degree,
//! objective, parameter, solver choice, grid — and of `version` and `revision`.
std::string family_task_key(const AlphaFamilyOptions& options, const FamilyTask& task, const std::string& version,
                            const std::string& revision);

//! One JSON Lines record: {"key", "study", "index", "degree", "objective", "parameter", "status",
//! "alpha", "value", "grid", "seconds"} (docs/formats.md, "Sharded studies").
nlohmann::json family_task_record(const nlohmann::json& study, const std::string& key, const FamilyTaskResult& r);

//! The options a study block describes; throws InputError(`where`, "study", …) when it is not one.
AlphaFamilyOptions family_options_of(const nlohmann::json& study, std::vector<std::string>* objectives,
                                     const std::string& where);

//! A record of the study `options` read back; throws InputError(`where`, FIELD, …) on a malformed
//! one (among them a grid that has not options.grid_points values).
FamilyTaskResult family_task_from_record(const nlohmann::json& record, const AlphaFamilyOptions& options,
                                         const std::string& where);

//! The family study from the results of all its tasks (in family_tasks order, one each).
AlphaFamilyResult assemble_alpha_family(const AlphaFamilyOptions& options, const std::vector<std::string>& objectives,
                                        const std::vector<FamilyTaskResult>& results);

}  // namespace coons
