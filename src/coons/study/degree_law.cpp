#include "degree_law.h"

#include <algorithm>
#include <cmath>

namespace coons {

std::optional<DegreeLawFit> fit_degree_law(const std::vector<std::pair<int, double>>& optima) {
  double num = 0, den = 0;
  for (auto [d, a] : optima) {
    num += (a + 0.25) / (double(d) * d);
    den += 1.0 / (double(d) * d * d * d);
  }
  if (optima.size() < 2 || !(den > 0)) return std::nullopt;
  DegreeLawFit fit;
  fit.c = num / den;
  for (auto [d, a] : optima)
    fit.misfit =
        std::max(fit.misfit, std::abs((a + 0.25) - fit.c / (double(d) * d)) / std::max(std::abs(a + 0.25), 1e-300));
  return fit;
}

}  // namespace coons
