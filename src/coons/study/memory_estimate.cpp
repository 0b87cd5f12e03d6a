#include "memory_estimate.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "coons/net/banded_gram.h"

namespace coons {

std::optional<double> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream fields(line.substr(13));
    double kib = 0;
    if (fields >> kib && kib > 0) return kib * 1024;
  }
  return std::nullopt;
}

double default_memory_limit() {
  const auto available = available_memory_bytes();
  return available ? *available / 2 : 8.0 * (1ull << 30);
}

std::optional<double> parse_memory_size(const std::string& text) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  // decimal only: stod also reads "0x10" (16), leading spaces, "inf" and "nan"
  if (!(std::isdigit(static_cast<unsigned char>(text[0])) || text[0] == '.') || text.find_first_of("xX") < used)
    return std::nullopt;
  std::string unit = text.substr(used);
  for (char& c : unit) c = char(std::toupper(static_cast<unsigned char>(c)));
  double scale = 0;
  if (unit.empty() || unit == "B")
    scale = 1;
  else if (unit == "K" || unit == "KB" || unit == "KIB")
    scale = 1024.0;
  else if (unit == "M" || unit == "MB" || unit == "MIB")
    scale = 1024.0 * 1024;
  else if (unit == "G" || unit == "GB" || unit == "GIB")
    scale = 1024.0 * 1024 * 1024;
  else if (unit == "T" || unit == "TB" || unit == "TIB")
    scale = 1024.0 * 1024 * 1024 * 1024;
  // at least one byte: "1e-3" was taken for a thousandth of a byte
  if (scale == 0 || !std::isfinite(value) || !(value * scale >= 1)) return std::nullopt;
  return value * scale;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB", "PB"};
  int u = 0;
  while (bytes >= 1024 && u < 5) {
    bytes /= 1024;
    ++u;
  }
  return fmt::format("{:.3g} {}", bytes, units[u]);
}

double net_solve_bytes(int m, int n, const solvers::SolverInfo* solver, int stencil_nonzeros) {
  const double points = (double(m) + 1) * (double(n) + 1);
  const double interior = std::max(0.0, double(m) - 1) * std::max(0.0, double(n) - 1);
  const double width = double(stencil_nonzeros) / kMask3Nonzeros;  // of the fill, against a 3×3 mask's
  double bytes = points * 3 * 8 * 10;
  if (!solver || solver->family == solvers::SolverFamily::kStructured) bytes += interior * 8 * 8 * 3;
  if (!solver || solver->needs_matrix) bytes += interior * stencil_nonzeros * 16;
  if (!solver || solver->family == solvers::SolverFamily::kDirect)
    bytes += interior * 8 * std::log2(std::max(interior, 2.0)) * 16 * width;
  return bytes;
}

double banded_gram_entries(int k) {
  if (k < 0) return 0;
  const double rows = double(k) + 1;
  return rows * std::min(rows, 11 * std::sqrt(double(k)) + BandedGram::kBlockRows);
}

double net_metrics_bytes(int m, int n) {
  const double points = (double(m) + 1) * (double(n) + 1);
  double grams = 0;
  for (int order = 0; order <= 3; ++order) grams += banded_gram_entries(m - order) + banded_gram_entries(n - order);
  return 8 * grams + points * 8 * (10 + 3);
}

double samples_bytes(long long k) { return double(k) * double(k) * 400; }

double target_samples_bytes(long long k) { return double(k) * double(k) * 16 * 8; }

}  // namespace coons
