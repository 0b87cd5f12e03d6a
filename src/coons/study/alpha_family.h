// Farin–Hansford's "no single α is best", quantified: over a seeded family of random smooth
// boundaries (random_boundary.h) and at each degree n (the sides elevated exactly to n), the
// optimum α* of every boundary and objective (the sine-basis search, alpha_search.h), its
// distribution (quantiles; how many are flat or on a bound), the single α that minimises the
// family's mean relative energy loss L(α) = mean_b (f_b(α) − f_b*)/f_b* (f_b tabulated on a logit
// grid of α and interpolated between its nodes), and what each boundary loses with it against
// its own optimum (mean, quantiles, max). Sizes: count boundaries × degrees × objectives searches,
// plus grid_points evaluations of every f_b. The work is a list of independent tasks
// (family_tasks.h), which `coons study --shard` splits and `--merge` assembles.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700 (the claim).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/objective.h"
#include "coons/curves/random_boundary.h"
#include "solvers/registry.h"

namespace coons {

//! The largest degree a family study elevates its boundaries to.
inline constexpr int kMaxFamilyDegree = 200;

struct AlphaFamilyOptions {
  std::vector<int> degrees = {3, 5, 8, 12, 20};  //!< increasing, each in [side_degree, kMaxFamilyDegree]
  std::vector<Objective> objectives;             //!< empty: thin_plate and e3
  int count = 200;                               //!< boundaries of the family, in [1, 100000]
  std::uint64_t seed = 1;
  RandomSmoothOptions generator;
  int grid_points = 161;                        //!< nodes of family_alpha_grid for the best single α
  const solvers::SolverInfo* solver = nullptr;  //!< nullptr: auto; else one check_search_backend accepts
  //! The perturbed family (`--family perturbed:NAME`) when not empty: boundary k is
  //! perturbed_boundary(base, amplitude, seed, k, generator) (random_boundary.h).
  std::string base_name;
  std::string base_content;      //!< a hash of the base's file (part of every task's key)
  std::optional<Boundary> base;  //!< the base itself (a merge, which makes no boundary, has none)
  double amplitude = 0.1;        //!< of the perturbation, times the base's bounding-box diagonal

  //! "random-smooth" or "perturbed:NAME".
  [[nodiscard]] std::string family_name() const;
  //! Whether the options describe a family study; if not, *why says why and *field names the
  //! member at fault ("degrees", "count", "amplitude", "grid_points", "generator", or "base": a
  //! base above kMaxFamilyDegree).
  bool is_valid(std::string* why, std::string* field = nullptr) const;
};

//! Boundary `index` of the family the options describe (random-smooth, or the perturbed base).
Boundary family_boundary(const AlphaFamilyOptions& options, int index);

//! Quantiles by linear interpolation between order statistics (q in [0, 1]); nullopt if empty.
std::optional<double> quantile(std::vector<double> values, double q);

struct Distribution {  //!< of a sample: its size and the quantiles 0, 0.1, 0.25, 0.5, 0.75, 0.9, 1
  int size = 0;
  double min = 0, q10 = 0, q25 = 0, median = 0, q75 = 0, q90 = 0, max = 0;
};
std::optional<Distribution> distribution_of(const std::vector<double>& values);

struct AlphaFamilyCell {
  int degree = 0;
  std::string objective;
  //! per boundary: α* when the search found an optimum (interior or on a bound), μ* when interior
  //! and α* < 0 (μ = −n²(1 + 4α)/(4α)), the relative loss at the best single α
  std::vector<std::optional<double>> alpha_star, mu_star, loss;
  int interior = 0, flat = 0, at_bound = 0, failed = 0;
  //! boundaries with an optimum whose own f* is 0 up to rounding (at most kZeroOptimum of the
  //! largest value of their grid: the mask reproduces them): a relative loss (f − f*)/f* means
  //! nothing for them (1.2e24 % for a family of one biquadratic), so they have none and the best
  //! single α is that of the others
  int zero_optimum = 0;
  //! evaluations of f_b on the best-single-α grid that failed, over the boundaries with an α*
  int grid_failed = 0;
  std::optional<Distribution> alpha, mu, losses;
  std::optional<double> loss_mean;
  std::optional<double> best_alpha;  //!< the single α minimising the mean loss over the family
  std::optional<double> best_mu;     //!< its μ
  bool best_at_grid_end = false;     //!< BestSingleAlpha::at_grid_end
  //! (α*_b + 1/4)/(best α + 1/4) over the boundaries with α* > −1/4: how far the best single α is
  //! from each boundary's own, as a factor on α + 1/4
  std::optional<Distribution> alpha_ratio;
};

struct AlphaFamilyResult {
  AlphaFamilyOptions options;
  std::vector<std::string> objectives;
  std::vector<AlphaFamilyCell> cells;  //!< objective-major, degrees in order
};

//! `progress` (may be empty) is told "degree n, objective" before each cell.
AlphaFamilyResult run_alpha_family(const AlphaFamilyOptions& options,
                                   const std::function<void(const std::string&)>& progress = {});

//! f* at most this fraction of the largest value of a boundary's grid counts as 0 (AlphaFamilyCell).
inline constexpr double kZeroOptimum = 1e-12;

//! How close the family grid comes to the ends of [−1/4, 1/4].
inline constexpr double kFamilyGridEnd = 1e-6;
//! The grid's name in a shard's study block (a merge refuses shards of another grid).
inline constexpr const char* kFamilyGridName = "logit";
//! Nodes of the Lagrange interpolation between grid values (a quintic).
inline constexpr int kGridInterpolationPoints = 6;

//! The α at fractional index s ∈ [0, grid_points − 1] of the logit grid of the best single α:
//! u = log((α + 1/4)/(1/4 − α)) uniform from −u_e to u_e, u_e = log((1/2 − ε)/ε), ε = kFamilyGridEnd,
//! so α runs from −1/4 + ε to 1/4 − ε. f_b(α) has its poles just beyond both ends of [−1/4, 1/4];
//! in u they lie about π off the real axis at either end, so one uniform step serves both.
double family_grid_alpha(double s, int grid_points);
//! family_grid_alpha at the nodes k = 0 … grid_points − 1.
std::vector<double> family_alpha_grid(int grid_points);

//! Values on that grid at the fractional index s ∈ [0, size − 1]: the Lagrange polynomial through
//! the kGridInterpolationPoints nearest nodes (all of them when there are fewer); the line through
//! the two bracketing nodes when one of those nodes is not finite (∞ when a bracketing one is not).
//! Exact at the nodes. On the family's f_b with 161 nodes it is within 2e−7 of f_b, relative to
//! its least value (measured to degree 60; docs/formats.md, `coons study --family`).
double interpolate_on_grid(const std::vector<double>& values, double s);

struct BestSingleAlpha {
  double alpha = 0;  //!< the α minimising the mean relative loss, in [−1/4, 1/4]
  double s = 0;      //!< its fractional grid index (for interpolate_on_grid)
  //! on the grid's first or last node (α = −1/4 + ε or 1/4 − ε): the mean loss still falls towards
  //! the end of the grid, so α is where the grid stops, not an interior minimum
  bool at_grid_end = false;
};

//! The α minimising mean_b (f_b(α) − f_b*)/f_b* where f_b is `values[b]` on family_alpha_grid
//! (interpolated between nodes) and f_b* = min(optimum[b], least of values[b]): the best node,
//! refined by golden sections between its neighbours. nullopt when there are no curves, no finite
//! mean, curves of different lengths or of fewer than 2 values, or not one optimum per curve.
//! Every family study (sharded or not) computes it from the same stored values.
std::optional<BestSingleAlpha> best_single_alpha_on_grid(const std::vector<std::vector<double>>& values,
                                                         const std::vector<double>& optimum);

//! best_single_alpha_on_grid of the curves f(b, α) (b in [0, count)) tabulated on a grid of
//! `grid_points`. Returns nullopt when count is 0.
std::optional<double> best_single_alpha(int count, const std::vector<double>& optimum,
                                        const std::function<double(int, double)>& f, int grid_points);

//! What names a family study's boundaries: family, seed, count, generator, degrees (and the
//! amplitude of a perturbed family). Shared by results.json and the shard records' study block.
nlohmann::json family_description_json(const AlphaFamilyOptions& options);
nlohmann::json alpha_family_json(const AlphaFamilyResult& result);
//! The tables, two per objective, and the conclusions computed from them; `figures` as
//! plot_alpha_family numbers them ("" where there is none).
std::string alpha_family_markdown(const AlphaFamilyResult& result, const std::vector<std::string>& figures);
//! The conclusions alone (each sentence only where the table supports it).
std::string alpha_family_conclusions(const AlphaFamilyResult& result);
//! Histograms on log bins, a step line per degree: for each objective i, png(i) of α* + 1/4 (the
//! best single α marked), png(n + i) of μ* (its μ marked), png(2n + i) of the relative excess at
//! the best single α (n objectives). Returns the errors ("" when made), one per figure.
std::vector<std::string> plot_alpha_family(const AlphaFamilyResult& result,
                                           const std::function<std::string(size_t)>& png);

}  // namespace coons
