#include "row_form.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "vector_clones.h"

namespace coons::solvers::detail {
namespace {

// R rows of width C, every one sparse with zero ends.
RowForm zero_form(int R, int C) {
  RowForm f;
  f.width = C;
  f.first.assign(std::size_t(R), 0.0);
  f.last.assign(std::size_t(R), 0.0);
  f.slot.assign(std::size_t(R), -1);
  return f;
}

}  // namespace

// An OR of the bits without the sign, which vectorises, unlike a compare-and-break loop.
COONS_VECTOR_CLONES bool has_interior(const double* row, int C) {
  std::uint64_t bits = 0;
  for (int j = 1; j + 1 < C; ++j) {
    std::uint64_t b;
    std::memcpy(&b, row + j, sizeof b);
    bits |= b << 1;
  }
  return bits != 0;
}

RowForm split_rows(const double* b, int R, int C, int stride) {
  RowForm f = zero_form(R, C);
  for (int i = 0; i < R; ++i) {
    const double* row = b + std::size_t(i) * std::size_t(stride);
    if (!has_interior(row, C)) {
      f.first[std::size_t(i)] = row[0];
      f.last[std::size_t(i)] = C >= 2 ? row[C - 1] : 0.0;
    } else {
      f.slot[std::size_t(i)] = int(f.dense_rows.size());
      f.dense_rows.push_back(i);
      f.values.insert(f.values.end(), row, row + C);
    }
  }
  return f;
}

RowForm join_rows(const std::vector<RowForm>& pieces) {
  RowForm f;
  if (pieces.empty()) return f;
  f.width = pieces.front().width;
  int rows = 0;
  for (const RowForm& p : pieces) {
    f.first.insert(f.first.end(), p.first.begin(), p.first.end());
    f.last.insert(f.last.end(), p.last.begin(), p.last.end());
    const int dense = int(f.dense_rows.size());
    for (const int s : p.slot) f.slot.push_back(s < 0 ? s : s + dense);
    for (const int i : p.dense_rows) f.dense_rows.push_back(i + rows);
    f.values.insert(f.values.end(), p.values.begin(), p.values.end());
    rows += int(p.slot.size());
  }
  return f;
}

double largest_magnitude(const double* v, std::size_t n) {
  double m = 0, z = 0;
  for (std::size_t k = 0; k < n; ++k) {
    m = std::max(m, std::abs(v[k]));
    z += 0 * v[k];  // 0 unless v[k] is a NaN or an infinity
  }
  return z == 0 ? m : std::numeric_limits<double>::quiet_NaN();
}

double largest_magnitude(const RowForm& f) {
  double m = 0;
  for (const std::vector<double>* v : {&f.first, &f.last, &f.values})
    m = larger_magnitude(m, largest_magnitude(v->data(), v->size()));
  return m;
}

RowForm combine(const std::vector<const RowForm*>& forms, const std::vector<double>& w, int R,
                const std::vector<double>& e0, const std::vector<double>& e1) {
  const int C = forms.empty() ? int(e0.size()) : forms[0]->width;
  RowForm out = zero_form(R, C);
  for (int i = 0; i < R; ++i) {
    bool dense = false;
    for (std::size_t r = 0; r < forms.size(); ++r) dense |= w[r] != 0 && forms[r]->slot[std::size_t(i)] >= 0;
    if (!dense) {
      for (std::size_t r = 0; r < forms.size(); ++r) {
        out.first[std::size_t(i)] += w[r] * forms[r]->first[std::size_t(i)];
        out.last[std::size_t(i)] += w[r] * forms[r]->last[std::size_t(i)];
      }
      continue;
    }
    out.slot[std::size_t(i)] = int(out.dense_rows.size());
    out.dense_rows.push_back(i);
    const std::size_t at = out.values.size();
    out.values.resize(at + std::size_t(C), 0.0);
    double* row = out.values.data() + at;
    for (std::size_t r = 0; r < forms.size(); ++r) {
      const RowForm& f = *forms[r];
      const int s = f.slot[std::size_t(i)];
      if (w[r] == 0) continue;
      if (s >= 0) {
        const double* v = f.values.data() + std::size_t(s) * std::size_t(C);
        for (int q = 0; q < C; ++q) row[q] += w[r] * v[q];
      } else {
        const double a = w[r] * f.first[std::size_t(i)], b = w[r] * f.last[std::size_t(i)];
        for (int q = 0; q < C; ++q) row[q] += a * e0[std::size_t(q)] + b * e1[std::size_t(q)];
      }
    }
  }
  return out;
}

}  // namespace coons::solvers::detail
