#include "coons/study/family_tasks.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>

#include "coons/alpha/alpha_search.h"
#include "coons/io/input_error.h"
#include "coons/io/json_file.h"
#include "coons/io/net_json.h"
#include "coons/mask/mask_families.h"
#include "coons/net/degree_elevation.h"
#include "coons/study/backend_choice.h"
#include "coons/study/degree_limit_study.h"
#include "coons/study/study.h"
#include "coons/study/study_failures.h"
#include "coons/study/task_key.h"
#if COONS_HAVE_FFTW
#include "coons/alpha/spectral_objective.h"
#endif

namespace coons {

using nlohmann::json;

std::vector<FamilyTask> family_tasks(const AlphaFamilyOptions& options, const std::vector<std::string>& objectives) {
  std::vector<FamilyTask> out;
  out.reserve(objectives.size() * options.degrees.size() * size_t(std::max(options.count, 0)));
  for (const std::string& o : objectives)
    for (int d : options.degrees)
      for (int k = 0; k < options.count; ++k) out.push_back({k, d, o});
  return out;
}

std::vector<FamilyTask> shard_tasks(const std::vector<FamilyTask>& all, int shard, int shards) {
  std::vector<FamilyTask> out;
  for (size_t t = 0; t < all.size(); ++t)
    if (shards > 0 && t % size_t(shards) == size_t(shard)) out.push_back(all[t]);
  return out;
}

std::optional<std::pair<int, int>> parse_shard(const std::string& text, std::string* why) {
  auto fail = [&](const std::string& reason) -> std::optional<std::pair<int, int>> {
    if (why) *why = reason;
    return std::nullopt;
  };
  const size_t slash = text.find('/');
  enum class Whole { kNot, kTooLarge, kOk };
  auto whole = [](const std::string& s, int* out) {
    if (s.empty() || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) return Whole::kNot;
    const size_t first = std::min(s.find_first_not_of('0'), s.size() - 1);  // leading zeros count for nothing
    if (s.size() - first > 9) return Whole::kTooLarge;
    *out = std::stoi(s.substr(first));
    return Whole::kOk;
  };
  int shard = 0, shards = 0;
  const Whole i = slash == std::string::npos ? Whole::kNot : whole(text.substr(0, slash), &shard);
  const Whole n = slash == std::string::npos ? Whole::kNot : whole(text.substr(slash + 1), &shards);
  if (i == Whole::kNot || n == Whole::kNot)
    return fail(fmt::format("'{}' is not I/N (two whole numbers, e.g. 0/4)", text));
  if (i == Whole::kTooLarge || n == Whole::kTooLarge)
    return fail(fmt::format("'{}': I and N must be below 1000000000", text));
  if (shards < 1) return fail(fmt::format("N must be at least 1, not {}", shards));
  if (shard >= shards) return fail(fmt::format("I must be in [0, N) = [0, {}), not {}", shards, shard));
  return std::make_pair(shard, shards);
}

std::string to_string(FamilyTaskStatus s) {
  switch (s) {
    case FamilyTaskStatus::kInterior:
      return "interior";
    case FamilyTaskStatus::kAtBound:
      return "at_bound";
    case FamilyTaskStatus::kFlat:
      return "flat";
    case FamilyTaskStatus::kFailed:
      return "failed";
  }
  return "failed";
}

namespace {

// f_b(α) of one boundary: the sine basis where it applies, else a factorisation and a solve.
std::function<double(double)> alpha_curve(const Boundary& b, const Objective& objective,
                                          const solvers::SolverInfo& solver) {
#if COONS_HAVE_FFTW
  if (b.m >= 2 && b.n >= 2 && SpectralAlphaObjective::supports(objective)) {
    auto f = std::make_shared<SpectralAlphaSearchObjective>(b, objective);
    return [f](double alpha) {
      const auto e = f->evaluate(alpha, false);
      return e.ok() ? e.value : HUGE_VAL;
    };
  }
#endif
  auto f = std::make_shared<MaskObjective>(
      b, objective, [](double a) { return alpha_family(a); }, solver);
  return [f](double alpha) {
    const auto e = f->evaluate(alpha, false);
    return e.ok() ? e.value : HUGE_VAL;
  };
}

Objective objective_named(const std::string& name) {
  std::string why;
  const std::optional<Objective> o = parse_objective(name, &why);
  if (!o) throw InputError("study", "objective", why);
  return *o;
}

json finite_or_null(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

}  // namespace

FamilyTaskStatus family_task_status(const AlphaSearchSummary& s) {
  if (s.flat) return FamilyTaskStatus::kFlat;
  if (!s.parameter || search_failed(s)) return FamilyTaskStatus::kFailed;
  return s.at_bound ? FamilyTaskStatus::kAtBound : FamilyTaskStatus::kInterior;
}

FamilyTaskResult run_family_task(const AlphaFamilyOptions& options, const FamilyTask& task) {
  const auto start = std::chrono::steady_clock::now();
  FamilyTaskResult r;
  r.task = task;
  const Objective objective = objective_named(task.objective);
  const Boundary b = elevate_boundary(family_boundary(options, task.index), task.degree, task.degree);
  const solvers::SolverInfo& solver = search_backend(options.solver, b, false);
  const AlphaSearchSummary s = search_alpha(b, objective, solver);
  r.status = family_task_status(s);
  if (r.status == FamilyTaskStatus::kInterior || r.status == FamilyTaskStatus::kAtBound) {
    r.alpha = s.parameter;
    r.value = s.value;
    const auto curve = alpha_curve(b, objective, solver);
    for (double alpha : family_alpha_grid(options.grid_points)) r.grid.push_back(curve(alpha));
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

json family_study_json(const AlphaFamilyOptions& o, const std::vector<std::string>& objectives,
                       const std::string& version, const std::string& revision) {
  json study = family_description_json(o);
  study["objectives"] = objectives;
  study["parameter"] = "alpha";
  study["grid_points"] = o.grid_points;
  study["grid"] = kFamilyGridName;
  study["solver"] = o.solver ? o.solver->name : std::string("auto");
  study["coons"] = {{"version", version}, {"git_revision", revision}};
  if (!o.base_name.empty()) study["base_content"] = o.base_content;
  return study;
}

std::string family_task_key(const AlphaFamilyOptions& o, const FamilyTask& task, const std::string& version,
                            const std::string& revision) {
  // Every input that changes the task's result, in a fixed order (json objects sort their keys).
  json inputs = {
      {"family", o.family_name()},
      {"seed", o.seed},
      {"generator",
       {{"side_degree", o.generator.side_degree}, {"height", o.generator.height}, {"wiggle", o.generator.wiggle}}},
      {"index", task.index},
      {"degree", task.degree},
      {"objective", task.objective},
      {"parameter", "alpha"},
      {"grid_points", o.grid_points},
      {"solver", o.solver ? o.solver->name : std::string("auto")},
      {"version", version},
      {"git_revision", revision}};
  if (!o.base_name.empty()) {  // the perturbed family: its base (by content) and amplitude too
    inputs["amplitude"] = o.amplitude;
    inputs["base_content"] = o.base_content;
  }
  return task_key(inputs);
}

json family_task_record(const json& study, const std::string& key, const FamilyTaskResult& r) {
  json grid = json::array();
  for (double v : r.grid) grid.push_back(finite_or_null(v));
  return {{"key", key},
          {"study", study},
          {"index", r.task.index},
          {"degree", r.task.degree},
          {"objective", r.task.objective},
          {"parameter", "alpha"},
          {"status", to_string(r.status)},
          {"alpha", r.alpha ? finite_or_null(*r.alpha) : json(nullptr)},
          {"value", r.alpha ? finite_or_null(r.value) : json(nullptr)},
          {"grid", grid},
          {"seconds", r.seconds}};
}

namespace {

template <typename T>
T field(const json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name)) throw InputError(where, name, "missing");
  try {
    return j.at(name).get<T>();
  } catch (const json::exception&) {
    throw InputError(where, name, "has the wrong type");
  }
}

// Integers go through json_integer, never get<int>: a fraction or a number beyond the range
// (1e300 converted to int is undefined behaviour) is an InputError naming the field.
int int_field(const json& j, const char* name, const std::string& where, int lo = std::numeric_limits<int>::min()) {
  if (!j.is_object() || !j.contains(name)) throw InputError(where, name, "missing");
  return json_int(j.at(name), where, name, lo);
}

std::uint64_t seed_field(const json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name)) throw InputError(where, name, "missing");
  const json& v = j.at(name);
  if (v.is_number_unsigned()) return v.get<std::uint64_t>();
  if (v.is_number_integer() && v.get<std::int64_t>() >= 0) return std::uint64_t(v.get<std::int64_t>());
  throw InputError(where, name, fmt::format("must be an integer in [0, 2^64), not {}", v.dump()));
}

}  // namespace

AlphaFamilyOptions family_options_of(const json& study, std::vector<std::string>* objectives,
                                     const std::string& where) {
  AlphaFamilyOptions o;
  const auto family = field<std::string>(study, "family", where);
  if (family.rfind("perturbed:", 0) == 0 && family.size() > 10) {
    o.base_name = family.substr(10);
    o.amplitude = field<double>(study, "amplitude", where);
    o.base_content = field<std::string>(study, "base_content", where);
  } else if (family != "random-smooth") {
    throw InputError(where, "study.family", "not a random-smooth or perturbed family study");
  }
  o.seed = seed_field(study, "seed", where);
  o.count = int_field(study, "count", where);
  const json generator = field<json>(study, "generator", where);
  o.generator.side_degree = int_field(generator, "side_degree", where);
  o.generator.height = field<double>(generator, "height", where);
  o.generator.wiggle = field<double>(generator, "wiggle", where);
  const json degrees = field<json>(study, "degrees", where);
  if (!degrees.is_array()) throw InputError(where, "degrees", "has the wrong type");
  o.degrees.clear();  // not the default list
  for (size_t k = 0; k < degrees.size(); ++k)
    o.degrees.push_back(json_int(degrees[k], where, fmt::format("degrees[{}]", k)));
  o.grid_points = int_field(study, "grid_points", where);
  // shards from a coons whose grid was another (a log grid of α + 1/4 until 2026-11) hold values
  // at other α: a merge would place them wrongly
  if (!study.contains("grid") || study["grid"] != kFamilyGridName)
    throw InputError(where, "study.grid",
                     fmt::format("not '{}' but {}: these shards were made on another grid of alpha (a coons "
                                 "before 2026-11-29 wrote none); rerun them with this one",
                                 kFamilyGridName, study.contains("grid") ? study["grid"].dump() : "missing"));
  const auto solver = field<std::string>(study, "solver", where);
  if (solver != "auto") {
    o.solver = solvers::find_solver(solver);
    if (!o.solver) throw InputError(where, "study.solver", fmt::format("'{}' is not built into this coons", solver));
  }
  *objectives = field<std::vector<std::string>>(study, "objectives", where);
  std::set<std::string> named;
  for (const std::string& name : *objectives) {
    std::string why;
    if (!parse_objective(name, &why)) throw InputError(where, "study.objectives", why);
    if (!named.insert(name).second) throw InputError(where, "study.objectives", fmt::format("names '{}' twice", name));
  }
  std::string why;
  if (!o.is_valid(&why)) throw InputError(where, "study", why);
  return o;
}

FamilyTaskResult family_task_from_record(const json& record, const AlphaFamilyOptions& options,
                                         const std::string& where) {
  FamilyTaskResult r;
  r.task.index = int_field(record, "index", where, 0);
  r.task.degree = int_field(record, "degree", where, 0);
  r.task.objective = field<std::string>(record, "objective", where);
  const auto status = field<std::string>(record, "status", where);
  bool known = false;
  for (FamilyTaskStatus s :
       {FamilyTaskStatus::kInterior, FamilyTaskStatus::kAtBound, FamilyTaskStatus::kFlat, FamilyTaskStatus::kFailed})
    if (status == to_string(s)) {
      r.status = s;
      known = true;
    }
  if (!known) throw InputError(where, "status", fmt::format("unknown status '{}'", status));
  // what run_family_task writes beside the key: the searched parameter is α, and a record without
  // an optimum has none (an edited "status": "flat" beside a number moved the best single α)
  if (record.contains("parameter") && record["parameter"] != "alpha")
    throw InputError(where, "parameter",
                     fmt::format("{} is not \"alpha\", the parameter of the study", record["parameter"].dump()));
  if (record.contains("seconds") && !(record["seconds"].is_number() && record["seconds"].get<double>() >= 0))
    throw InputError(where, "seconds",
                     fmt::format("{} is no duration (a number, at least 0)", record["seconds"].dump()));
  const bool optimum = r.status == FamilyTaskStatus::kInterior || r.status == FamilyTaskStatus::kAtBound;
  if (!optimum)
    for (const char* key : {"alpha", "value"})
      if (record.contains(key) && !record[key].is_null())
        throw InputError(where, key,
                         fmt::format("a record with status '{}' has no optimum, so {} must be null, not {}", status,
                                     key, record[key].dump()));
  if (optimum) {
    // what run_family_task can have written: α* within the search's bounds, energies ≥ 0 (an
    // edited record would otherwise move the quantiles and the best single α without a word)
    const AlphaSearchOptions bounds;
    r.alpha = field<double>(record, "alpha", where);
    if (!(*r.alpha >= bounds.lower && *r.alpha <= bounds.upper))
      throw InputError(where, "alpha",
                       fmt::format("{} is outside the search's bounds [{}, {}]", *r.alpha, bounds.lower, bounds.upper));
    if (r.status == FamilyTaskStatus::kAtBound && !lies_on_bound(*r.alpha, bounds.lower, bounds.upper))
      throw InputError(where, "alpha",
                       fmt::format("{} is not on a bound of [{}, {}], as status 'at_bound' says", *r.alpha,
                                   bounds.lower, bounds.upper));
    r.value = field<double>(record, "value", where);
    if (!(std::isfinite(r.value) && r.value >= 0))
      throw InputError(where, "value", fmt::format("{} is no energy (finite and at least 0)", r.value));
    const json grid = field<json>(record, "grid", where);
    if (!grid.is_array()) throw InputError(where, "grid", "not an array");
    for (size_t k = 0; k < grid.size(); ++k) {
      const json& v = grid[k];
      if (!v.is_null() && !v.is_number()) throw InputError(where, "grid", "not a number or null");
      if (v.is_number() && !(v.get<double>() >= 0))
        throw InputError(where, fmt::format("grid[{}]", k),
                         fmt::format("{} is no energy (at least 0, or null)", v.get<double>()));
      r.grid.push_back(v.is_null() ? HUGE_VAL : v.get<double>());
    }
    // the task's key covers its inputs, not this result: an edited grid passes it, and the
    // aggregation reads grid_points values of every curve
    if (r.grid.size() != size_t(std::max(options.grid_points, 0)))
      throw InputError(
          where, "grid",
          fmt::format("has {} values, not the study's grid_points = {}", r.grid.size(), options.grid_points));
  }
  if (record.contains("seconds") && record["seconds"].is_number()) r.seconds = record["seconds"].get<double>();
  return r;
}

AlphaFamilyResult assemble_alpha_family(const AlphaFamilyOptions& options, const std::vector<std::string>& objectives,
                                        const std::vector<FamilyTaskResult>& results) {
  AlphaFamilyResult r;
  r.options = options;
  r.objectives = objectives;
  const int count = options.count;
  size_t next = 0;
  for (const std::string& objective : objectives)
    for (int degree : options.degrees) {
      AlphaFamilyCell cell;
      cell.degree = degree;
      cell.objective = objective;
      cell.alpha_star.resize(count);
      cell.mu_star.resize(count);
      cell.loss.resize(count);
      std::vector<int> used;
      std::vector<bool> interior;  // of each used task: its α* lies inside the bounds
      std::vector<double> optimum;
      std::vector<std::vector<double>> curves;
      for (int k = 0; k < count && next < results.size(); ++k, ++next) {
        const FamilyTaskResult& t = results[next];
        switch (t.status) {
          case FamilyTaskStatus::kFlat:
            ++cell.flat;
            continue;
          case FamilyTaskStatus::kFailed:
            ++cell.failed;
            continue;
          case FamilyTaskStatus::kAtBound:
            ++cell.at_bound;
            break;
          case FamilyTaskStatus::kInterior:
            ++cell.interior;
            break;
        }
        cell.alpha_star[k] = t.alpha;
        if (t.status == FamilyTaskStatus::kInterior && t.alpha) cell.mu_star[k] = mu_of_alpha(degree, *t.alpha);
        for (double v : t.grid) cell.grid_failed += std::isfinite(v) ? 0 : 1;
        double own = t.value, largest = 0;
        for (double v : t.grid)
          if (std::isfinite(v)) own = std::min(own, v), largest = std::max(largest, v);
        if (own <= kZeroOptimum * largest) {  // reproduced: no relative loss (AlphaFamilyCell)
          ++cell.zero_optimum;
          continue;
        }
        used.push_back(k);
        interior.push_back(t.status == FamilyTaskStatus::kInterior);
        optimum.push_back(t.value);
        curves.push_back(t.grid);
      }
      std::vector<double> alphas, mus;
      for (const auto& a : cell.alpha_star)
        if (a) alphas.push_back(*a);
      for (const auto& m : cell.mu_star)
        if (m) mus.push_back(*m);
      cell.alpha = distribution_of(alphas);
      cell.mu = distribution_of(mus);
      const std::optional<BestSingleAlpha> best = best_single_alpha_on_grid(curves, optimum);
      if (best) {
        cell.best_alpha = best->alpha;
        cell.best_mu = mu_of_alpha(degree, best->alpha);
        cell.best_at_grid_end = best->at_grid_end;
        std::vector<double> losses, ratios;
        for (size_t u = 0; u < used.size(); ++u) {
          const double value = interpolate_on_grid(curves[u], best->s);
          double own = std::min(optimum[u], value);
          for (double v : curves[u])
            if (std::isfinite(v)) own = std::min(own, v);
          // a loss beyond the doubles (a merged record's grid of 1e308) is no loss to print
          if (const double loss = (value - own) / own; own > 0 && std::isfinite(loss)) {
            cell.loss[used[u]] = loss;
            losses.push_back(loss);
          }
          // interior optima only: one on the bound −1/4 is found from inside, a rounding of it
          // (2e-9) over the best α's 1e-6 made factors of 0.003 out of nothing
          const double a = *cell.alpha_star[used[u]];
          if (interior[u] && a > -0.25 && best->alpha > -0.25) ratios.push_back((a + 0.25) / (best->alpha + 0.25));
        }
        cell.losses = distribution_of(losses);
        cell.alpha_ratio = distribution_of(ratios);
        if (!losses.empty()) {
          double mean = 0;  // running: a sum of finite losses may overflow
          for (std::size_t k = 0; k < losses.size(); ++k) mean += (losses[k] - mean) / double(k + 1);
          cell.loss_mean = mean;
        }
      }
      r.cells.push_back(std::move(cell));
    }
  return r;
}

AlphaFamilyResult run_alpha_family(const AlphaFamilyOptions& options,
                                   const std::function<void(const std::string&)>& progress) {
  std::vector<std::string> objectives;
  if (options.objectives.empty())
    for (const Objective& o : default_study_objectives()) objectives.push_back(o.name);
  else
    for (const Objective& o : options.objectives) objectives.push_back(o.name);
  std::vector<FamilyTaskResult> results;
  int last_degree = -1;
  std::string last_objective;
  for (const FamilyTask& task : family_tasks(options, objectives)) {
    if (progress && (task.degree != last_degree || task.objective != last_objective))
      progress(fmt::format("degree {}, {}", task.degree, task.objective));
    last_degree = task.degree;
    last_objective = task.objective;
    results.push_back(run_family_task(options, task));
  }
  return assemble_alpha_family(options, objectives, results);
}

}  // namespace coons
