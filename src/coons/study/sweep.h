// A sweep: every metric of the nets of a mask family on a grid of its parameter (α or μ), solved
// through the solver's sweep API (the right-hand side e_i·B_Ei + e_j·B_Ej + d·B_K has its three
// basis terms computed once); its JSON Lines and its plot.
// Based on: G. Farin, D. Hansford, Discrete Coons patches, CAGD 16 (1999) 691–700.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coons/alpha/alpha_search.h"
#include "coons/alpha/objective.h"
#include "coons/io/plot.h"
#include "coons/mask/mask9.h"
#include "coons/metrics/energies.h"
#include "solvers/registry.h"

namespace coons {

enum class SweepParameter { kAlpha, kMu };
const char* to_string(SweepParameter parameter);

struct SweepRow {
  double parameter = 0;
  Mask9 mask;
  solvers::SolveSummary summary;
  NetMetrics metrics;
  std::optional<double> rms_target;
};

//! count values from `from` to `to`, both included (count ≥ 1).
std::vector<double> linspace(double from, double to, int count);

//! The family of a sweep parameter on a boundary (μ: the anisotropic masks of degree (m, n)).
MaskFamily sweep_family(SweepParameter parameter, const Boundary& boundary);

//! Solves the family at every parameter value; `nets` (when given) receives each net;
//! `progress(k, count)` is called after each value. `options` go to the solver (with threads ≥ 2 a
//! backend with sweep workers, fast, solves whole members side by side; the rows are the same).
std::vector<SweepRow> run_sweep(const Boundary& boundary, const std::vector<double>& parameters,
                                const MaskFamily& family, const solvers::SolverInfo& solver,
                                const std::optional<Target>& target,
                                const std::function<void(size_t, size_t)>& progress = {},
                                std::vector<ControlNet>* nets = nullptr, const solvers::SolverOptions& options = {});

//! One JSON line of `coons sweep` (docs/formats.md): the parameter, α, β, μ, every metric, the
//! solver block and, with a target, rms_target.
nlohmann::json sweep_line(const Boundary& boundary, SweepParameter parameter, const SweepRow& row);

//! A searched optimum of one energy: where the plot of a sweep marks its minimum.
struct SweepOptimum {
  double parameter = 0, value = 0;
};

//! The curves of plot_sweep below (each energy, and the rms to a target, over the solved rows),
//! each divided by its largest value, with its minimum as the marker.
std::vector<PlotSeries> sweep_series(const std::vector<SweepRow>& rows,
                                     const std::map<std::string, SweepOptimum>& optima = {});

//! Energy curves, each divided by its largest value, with each curve's minimum marked: the
//! searched optimum where `optima` has one for it (keys thin_plate, e3, twist, dirichlet; the
//! study's α*, which lies between the sweep's values: the dome's E3 optimum −0.2447 was drawn at
//! the grid point −0.25, on the bound), else the lowest value of the sweep. Returns an empty string
//! or why the plot could not be made.
std::string plot_sweep(const std::string& png, const Boundary& boundary, SweepParameter parameter,
                       const std::vector<SweepRow>& rows, const std::map<std::string, SweepOptimum>& optima = {});

//! An α* this close to 0 is 0 found with rounding: the discrete Dirichlet optimum is α = 0 exactly,
//! and the search returned −6.4e−17, which made μ = 3.5e16 out of a rounding error's sign.
inline constexpr double kAlphaZeroWithinRounding = 1e-12;

//! μ of α at degree n when m = n and α ∈ [−1/4, −kAlphaZeroWithinRounding) (docs/math.md §4),
//! else nullopt (α = 0, the Laplace mask, has no μ).
std::optional<double> mu_of_alpha(const Boundary& boundary, std::optional<double> alpha);

}  // namespace coons
