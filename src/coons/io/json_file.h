// Reading a JSON document at the input edge, the one reader every input file goes through:
// an unreadable file, malformed JSON, a file larger than `max_bytes` or nesting deeper than
// `max_depth` is an InputError naming the file ("FILE: (document): reason"); nothing deeper than the
// limit is ever built, so no later recursive walk (copy, dump, compare) can exhaust the stack.
// Also the checked conversions of JSON values the readers share (integers in range, coordinates
// whose squares stay representable).
#pragma once

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace coons {

struct JsonReadOptions {
  //! Containers nested deeper than this are refused (the formats nest at most 4 levels).
  int max_depth = 64;
  //! Files larger than this are refused before they are read (256 MiB).
  std::uint64_t max_bytes = std::uint64_t{256} << 20;

  [[nodiscard]] bool is_valid(std::string* why = nullptr) const;
};

//! The field name of errors about the document as a whole.
inline constexpr const char* kDocumentField = "(document)";

//! Parse `text` read from `source` (the name errors carry), within the limits of `options`.
nlohmann::json parse_json_text(const std::string& text, const std::string& source, const JsonReadOptions& options = {});

//! Read and parse the file at `path` ("-" is not special: a path is a path).
nlohmann::json read_json_file(const std::string& path, const JsonReadOptions& options = {});

//! An integer field within [lo, hi]; anything else (a fraction, a string, a value out of range,
//! however large) is an InputError naming `field` and the bounds.
std::int64_t json_integer(const nlohmann::json& j, const std::string& source, const std::string& field, std::int64_t lo,
                          std::int64_t hi);

//! json_integer narrowed to int: the one reader of int fields (default bounds: every int).
int json_int(const nlohmann::json& j, const std::string& source, const std::string& field,
             int lo = std::numeric_limits<int>::min(), int hi = std::numeric_limits<int>::max());

//! The largest coordinate magnitude the readers accept. Energies and squared residuals scale as
//! s² for coordinates of size s, times constants up to ~1e5 (high degrees: products of m², n² and
//! binomial weights) and sums over up to ~1e7 terms: s²·1e12 < 1.8e308 needs s < ~1e148, and an
//! intermediate that multiplies two such quantities (s⁴) would need s < ~1e74. 1e60 keeps both
//! (s⁴·1e12 = 1e252) with margin and is far beyond any real model (measured: the dome scaled to
//! 1e59 solves with every energy finite, thin-plate 2.5e119).
inline constexpr double kMaxCoordinate = 1e60;

//! The smallest size of a model the searches accept (BoundaryReadOptions::min_model_size): its
//! largest coordinate magnitude is zero (every point at the origin) or at least this. Energies
//! scale as s², and for s below about 1e-150 they fall into subnormal numbers or to zero, where the
//! α search loses digits (the pillow scaled by 1e-160: α* = −0.0416679 for −0.0416667) or calls its
//! objective flat (1e-170). 1e-60 mirrors kMaxCoordinate. Nets, and solves, hold at any scale.
inline constexpr double kMinModelSize = 1e-60;

//! An InputError naming `field` (the point of largest magnitude) when 0 < largest < min_size.
void require_model_size(double largest, double min_size, const std::string& source, const std::string& field);

//! Why x cannot be a coordinate, or "" when it can: "is not finite", or "is <x>, beyond the bound
//! |x| <= 1e+60 (...)". The one rule every reader holds coordinates to (boundary and surface files,
//! analytic curves, targets, imported STEP poles); each puts its own subject in front.
std::string coordinate_problem(double x);

//! Whether a number as written has only zero digits before its exponent (0, -0.0e5, 0x0p3): a
//! number that strtod reads as 0 without them (1e-400) lies below the smallest double. Used by
//! every reader of numbers as text (command-line options, --target).
bool zero_digits(const std::string& number);

//! A coordinate that is a finite number with |x| <= kMaxCoordinate; `what` says which one
//! ("coordinate 2"), the InputError names `field` and coordinate_problem's reason.
double json_coordinate(const nlohmann::json& j, const std::string& source, const std::string& field,
                       const std::string& what);

}  // namespace coons
