#include "coons/study/family_tasks.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <tuple>

#include "coons/io/input_error.h"
#include "coons/study/study_failures.h"

using namespace coons;

TEST_CASE("parse_shard: I/N with 0 <= I < N, anything else is refused with a reason") {
  std::string why;
  const auto s = parse_shard("2/5", &why);
  REQUIRE(s);
  CHECK(s->first == 2);
  CHECK(s->second == 5);
  for (const char* bad : {"5/5", "1/0", "-1/3", "1", "a/b", "1/2/3", "", "1 /2"}) {
    why.clear();
    CHECK_FALSE(parse_shard(bad, &why));
    CHECK_FALSE(why.empty());
  }
  // ten digits were called "not I/N (two whole numbers …)", which they are: the reason is the size
  CHECK_FALSE(parse_shard("0/1000000000", &why));
  CHECK(why == "'0/1000000000': I and N must be below 1000000000");
  const auto zeros = parse_shard("0000000003/0000000004", &why);  // leading zeros count for nothing
  REQUIRE(zeros);
  CHECK(*zeros == std::make_pair(3, 4));
  const auto largest = parse_shard("3/999999999", &why);
  REQUIRE(largest);
  CHECK(largest->second == 999999999);
}

TEST_CASE("shard_tasks: the shards partition the task list") {
  AlphaFamilyOptions options;
  options.degrees = {3, 5, 8};
  options.count = 7;
  const std::vector<FamilyTask> all = family_tasks(options, {"thin_plate", "e3"});
  REQUIRE(all.size() == 42);
  std::multiset<std::tuple<std::string, int, int>> seen;
  for (int i = 0; i < 4; ++i)
    for (const FamilyTask& t : shard_tasks(all, i, 4)) seen.emplace(t.objective, t.degree, t.index);
  CHECK(seen.size() == all.size());
  for (const FamilyTask& t : all) CHECK(seen.count({t.objective, t.degree, t.index}) == 1);
  CHECK(shard_tasks(all, 0, 50).size() == 1);
}

TEST_CASE("family_task_key: changes with every input of the task and with the coons revision") {
  AlphaFamilyOptions options;
  const FamilyTask task{4, 5, "thin_plate"};
  const std::string key = family_task_key(options, task, "1.0", "abc");
  CHECK(key.size() == 16);
  CHECK(family_task_key(options, task, "1.0", "abc") == key);
  std::set<std::string> keys = {key};
  keys.insert(family_task_key(options, {5, 5, "thin_plate"}, "1.0", "abc"));
  keys.insert(family_task_key(options, {4, 8, "thin_plate"}, "1.0", "abc"));
  keys.insert(family_task_key(options, {4, 5, "e3"}, "1.0", "abc"));
  keys.insert(family_task_key(options, task, "1.1", "abc"));
  keys.insert(family_task_key(options, task, "1.0", "abd"));
  AlphaFamilyOptions other = options;
  other.seed = 2;
  keys.insert(family_task_key(other, task, "1.0", "abc"));
  other = options;
  other.generator.height = 0.25;
  keys.insert(family_task_key(other, task, "1.0", "abc"));
  CHECK(keys.size() == 8);
  other = options;
  other.count = 999;  // the count is not an input of boundary 4's task
  CHECK(family_task_key(other, task, "1.0", "abc") == key);
}

TEST_CASE("interpolate_on_grid: exact at the nodes and for quintics in the grid index") {
  auto quintic = [](double s) {
    return 1 + s - 0.3 * s * s + 0.02 * s * s * s + 1e-3 * std::pow(s, 4) - 1e-4 * std::pow(s, 5);
  };
  std::vector<double> values(9);
  for (int k = 0; k < 9; ++k) values[k] = quintic(k);
  for (int k = 0; k < 9; ++k) CHECK(interpolate_on_grid(values, k) == values[k]);
  for (double s : {0.25, 1.5, 4.7, 7.9}) CHECK(interpolate_on_grid(values, s) == Approx(quintic(s)).epsilon(1e-12));
  // a sextic is not reproduced: the window really is six nodes
  std::vector<double> sextic(9);
  for (int k = 0; k < 9; ++k) sextic[k] = std::pow(k - 4.0, 6);
  CHECK(std::abs(interpolate_on_grid(sextic, 4.5) - std::pow(0.5, 6)) > 1);
  // fewer nodes than the window: the polynomial through all of them
  CHECK(interpolate_on_grid({0, 1, 4}, 1.5) == Approx(2.25));
  values[6] = HUGE_VAL;  // a failed evaluation: linear between finite neighbours, ∞ next to it
  CHECK(interpolate_on_grid(values, 4.5) == Approx(0.5 * (values[4] + values[5])));
  CHECK(std::isinf(interpolate_on_grid(values, 5.5)));
}

TEST_CASE("family_alpha_grid: a logit grid from -1/4 + 1e-6 to 1/4 - 1e-6, symmetric about 0") {
  const std::vector<double> grid = family_alpha_grid(161);
  REQUIRE(grid.size() == 161);
  CHECK(grid.front() == Approx(-0.25 + kFamilyGridEnd).epsilon(1e-9));
  CHECK(grid.back() == Approx(0.25 - kFamilyGridEnd).epsilon(1e-12));
  CHECK(std::abs(grid[80]) < 1e-15);
  for (int k = 0; k < 161; ++k) {
    CHECK(grid[k] == Approx(-grid[160 - k]).epsilon(0).margin(1e-15));
    if (k > 0) CHECK(grid[k] > grid[k - 1]);
    CHECK(family_grid_alpha(k, 161) == grid[k]);
  }
  // uniform in u = log((α + 1/4)/(1/4 − α))
  auto u = [](double a) { return std::log((a + 0.25) / (0.25 - a)); };
  CHECK(u(grid[41]) - u(grid[40]) == Approx(u(grid[121]) - u(grid[120])).epsilon(1e-9));
}

TEST_CASE("family_task_record: a record read back is the same result") {
  AlphaFamilyOptions options;
  options.count = 3;
  options.degrees = {3};
  options.grid_points = 9;
  const FamilyTaskResult r = run_family_task(options, {1, 3, "thin_plate"});
  REQUIRE(r.alpha);
  REQUIRE(r.grid.size() == 9);
  const auto study = family_study_json(options, {"thin_plate"}, "v", "r");
  const FamilyTaskResult back =
      family_task_from_record(nlohmann::json::parse(family_task_record(study, "k", r).dump()), options, "f");
  CHECK(back.alpha == r.alpha);
  CHECK(back.value == r.value);
  CHECK(back.grid == r.grid);
  CHECK(back.status == r.status);
  std::vector<std::string> objectives;
  const AlphaFamilyOptions again = family_options_of(study, &objectives, "f");
  CHECK(again.degrees == options.degrees);
  CHECK(again.count == 3);
  CHECK(objectives == std::vector<std::string>{"thin_plate"});
  // shards of an older coons (no grid named, or another) are refused, not merged on the wrong α
  nlohmann::json older = study;
  older.erase("grid");
  CHECK_THROWS_WITH(family_options_of(older, &objectives, "f"),
                    Catch::Contains("f: study.grid: not 'logit' but missing"));
  older["grid"] = "log";
  CHECK_THROWS_WITH(family_options_of(older, &objectives, "f"),
                    Catch::Contains("f: study.grid: not 'logit' but \"log\""));
  nlohmann::json broken = family_task_record(study, "k", r);
  broken["status"] = "maybe";
  CHECK_THROWS_AS(family_task_from_record(broken, options, "f"), InputError);
}

TEST_CASE("family_task_from_record: a grid of another length or a number that is no int is refused") {
  // the fields a merge reads back from a shard file someone edited: the key covers the task's
  // inputs, not its result, so the reader itself must refuse what the aggregation cannot use
  AlphaFamilyOptions options;
  options.count = 3;
  options.degrees = {3};
  options.grid_points = 9;
  FamilyTaskResult r;
  r.task = {1, 3, "thin_plate"};
  r.status = FamilyTaskStatus::kInterior;
  r.alpha = -0.1;
  r.value = 2;
  r.grid.assign(9, 3.0);
  const auto study = family_study_json(options, {"thin_plate"}, "v", "r");
  const nlohmann::json record = nlohmann::json::parse(family_task_record(study, "k", r).dump());
  REQUIRE(family_task_from_record(record, options, "f").grid.size() == 9);
  auto field_refused = [&](const nlohmann::json& edited) {
    try {
      family_task_from_record(edited, options, "f");
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("(accepted)");
  };
  for (const nlohmann::json& grid :
       {nlohmann::json::array(), nlohmann::json({1, 2, 3}), nlohmann::json(std::vector<double>(10, 1.0))}) {
    nlohmann::json edited = record;
    edited["grid"] = grid;
    CHECK(field_refused(edited) == "grid");
  }
  for (const char* name : {"index", "degree"})
    for (const nlohmann::json& bad :
         {nlohmann::json(1e300), nlohmann::json(1e10), nlohmann::json(-1), nlohmann::json(2.5)}) {
      nlohmann::json edited = record;
      edited[name] = bad;
      INFO(name << " = " << bad.dump());
      CHECK(field_refused(edited) == name);
    }
  // the result itself: α* beyond the search's bounds, an energy below 0 or not finite
  const std::vector<std::pair<const char*, nlohmann::json>> results = {
      {"alpha", 5.0}, {"alpha", -0.2500001}, {"alpha", nullptr}, {"value", -1e-9}, {"value", HUGE_VAL}};
  for (const auto& [name, bad] : results) {
    nlohmann::json edited = record;
    edited[name] = bad;
    INFO(name << " = " << bad.dump());
    CHECK(field_refused(edited) == name);
  }
  // a status that contradicts the record (an edited "flat" beside a number moved the best single
  // α), a parameter other than α, a duration that is no number: what run_family_task cannot write
  const std::vector<std::tuple<const char*, nlohmann::json, const char*>> contradictions = {
      {"status", "flat", "alpha"},      {"status", "failed", "alpha"}, {"status", "at_bound", "alpha"},
      {"parameter", "mu", "parameter"}, {"seconds", "x", "seconds"},   {"seconds", -1.0, "seconds"}};
  for (const auto& [name, bad, field] : contradictions) {
    nlohmann::json edited = record;
    edited[name] = bad;
    INFO(name << " = " << bad.dump());
    CHECK(field_refused(edited) == field);
  }
  nlohmann::json flat = record;  // a flat record as the study writes it: no optimum, accepted
  flat["status"] = "flat";
  flat["alpha"] = nullptr;
  flat["value"] = nullptr;
  CHECK(family_task_from_record(flat, options, "f").status == FamilyTaskStatus::kFlat);
  nlohmann::json on_bound = record;  // at_bound on the bound itself: accepted
  on_bound["status"] = "at_bound";
  on_bound["alpha"] = 0.25;
  CHECK(family_task_from_record(on_bound, options, "f").status == FamilyTaskStatus::kAtBound);
  nlohmann::json negative = record;
  negative["grid"][4] = -2.0;
  CHECK(field_refused(negative) == "grid[4]");
  nlohmann::json failed = record;  // a failed evaluation is null, and accepted
  failed["grid"][4] = nullptr;
  CHECK(std::isinf(family_task_from_record(failed, options, "f").grid[4]));
  // the study block: its integers too
  std::vector<std::string> objectives;
  for (const char* name : {"count", "grid_points"}) {
    nlohmann::json edited = study;
    edited[name] = 1e300;
    INFO(name);
    CHECK_THROWS_WITH(family_options_of(edited, &objectives, "f"),
                      Catch::Contains(std::string("f: ") + name + ": must be an integer"));
  }
  nlohmann::json edited = study;
  edited["degrees"] = {3, 1e10};
  CHECK_THROWS_WITH(family_options_of(edited, &objectives, "f"), Catch::Contains("f: degrees[1]: must be an integer"));
  edited = study;
  edited["generator"]["side_degree"] = -1e300;
  CHECK_THROWS_WITH(family_options_of(edited, &objectives, "f"), Catch::Contains("f: side_degree: must be an integer"));
  edited = study;
  edited["seed"] = 1e300;
  CHECK_THROWS_WITH(family_options_of(edited, &objectives, "f"), Catch::Contains("f: seed: must be an integer"));
}

namespace {

// Three random-smooth boundaries at degree 3 on a grid of 9, and their thin-plate tasks run.
AlphaFamilyOptions three_at_degree_3() {
  AlphaFamilyOptions options;
  options.count = 3;
  options.degrees = {3};
  options.grid_points = 9;
  return options;
}
std::vector<FamilyTaskResult> thin_plate_tasks(const AlphaFamilyOptions& options) {
  std::vector<FamilyTaskResult> results;
  results.reserve(std::size_t(options.count));
  for (int k = 0; k < options.count; ++k) results.push_back(run_family_task(options, {k, 3, "thin_plate"}));
  for (const FamilyTaskResult& r : results) REQUIRE(r.alpha);
  return results;
}

}  // namespace

TEST_CASE("assemble_alpha_family: failed searches and failed grid evaluations are counted per cell") {
  const AlphaFamilyOptions options = three_at_degree_3();
  std::vector<FamilyTaskResult> results = thin_plate_tasks(options);
  CHECK(assemble_alpha_family(options, {"thin_plate"}, results).cells.at(0).grid_failed == 0);
  results[0].grid[4] = HUGE_VAL;  // an evaluation that failed (a null in a shard record)
  FamilyTaskResult failed;        // a search that failed: no α*, no grid
  failed.task = results[2].task;
  results[2] = failed;
  const AlphaFamilyCell cell = assemble_alpha_family(options, {"thin_plate"}, results).cells.at(0);
  CHECK(cell.failed == 1);
  CHECK(cell.grid_failed == 1);
  CHECK(cell.interior + cell.at_bound == 2);
}

TEST_CASE("assemble_alpha_family: a boundary whose own optimum is 0 has no relative loss and no say in the best alpha",
          "[study]") {
  // A family of one biquadratic repeated: its e3 is 5.7e-30 at alpha = -1/4 (rounding of 0), and
  // the relative excess (f - f*)/f* at the grid end -0.249999 read 1.2e24 %.
  const AlphaFamilyOptions options = three_at_degree_3();
  std::vector<FamilyTaskResult> results = thin_plate_tasks(options);
  const AlphaFamilyCell two = [&] {
    std::vector<FamilyTaskResult> others(results.begin() + 1, results.end());
    AlphaFamilyOptions o = options;
    o.count = 2;
    return assemble_alpha_family(o, {"thin_plate"}, others).cells.at(0);
  }();
  FamilyTaskResult& reproduced = results[0];
  reproduced.value = 5.7e-30;
  reproduced.grid.assign(reproduced.grid.size(), 1.0);
  reproduced.grid[0] = 7.4e-8;  // near alpha = -1/4
  const AlphaFamilyCell cell = assemble_alpha_family(options, {"thin_plate"}, results).cells.at(0);
  CHECK(cell.zero_optimum == 1);
  CHECK_FALSE(cell.loss[0].has_value());
  REQUIRE(cell.best_alpha);
  REQUIRE(two.best_alpha);
  CHECK(*cell.best_alpha == Approx(*two.best_alpha).margin(1e-12));  // that of the other two
  REQUIRE(cell.loss_mean);
  CHECK(*cell.loss_mean == Approx(*two.loss_mean).margin(1e-15));
  CHECK(cell.interior + cell.at_bound == 3);  // its alpha* still counts
}

TEST_CASE("family_task_status: the family fails exactly the searches the study of files fails") {
  AlphaSearchSummary s;
  s.parameter = -0.1;
  s.value = 1;
  // fixed expectations, not search_failed itself: a status moved in or out of either list fails here
  const std::pair<SearchStatus, FamilyTaskStatus> cases[] = {{SearchStatus::kSuccess, FamilyTaskStatus::kInterior},
                                                             {SearchStatus::kSolverFailed, FamilyTaskStatus::kFailed},
                                                             {SearchStatus::kNotConverged, FamilyTaskStatus::kInterior},
                                                             {SearchStatus::kFailedRegion, FamilyTaskStatus::kFailed},
                                                             {SearchStatus::kNotApplicable, FamilyTaskStatus::kFailed}};
  for (const auto& [status, expected] : cases) {
    s.status = status;
    INFO(to_string(status));
    CHECK(family_task_status(s) == expected);
    CHECK(search_failed(s) == (expected == FamilyTaskStatus::kFailed));
  }
  s.status = SearchStatus::kNotConverged;  // keeps its best α as α* (not a failure: exit 0)
  CHECK(family_task_status(s) == FamilyTaskStatus::kInterior);
  s.at_bound = true;
  CHECK(family_task_status(s) == FamilyTaskStatus::kAtBound);
  s.parameter.reset();  // no α* at all
  CHECK(family_task_status(s) == FamilyTaskStatus::kFailed);
  s.flat = true;
  CHECK(family_task_status(s) == FamilyTaskStatus::kFlat);
}
