#include "json_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "coons/io/input_error.h"

namespace coons {

namespace {

// Thrown by the parser callback to stop at the first container beyond the limit (the parser is
// iterative, so the depth is counted before anything deeper is built).
struct TooDeep {};
struct Underflow {
  std::string field;
};

// Thrown by the parser callback at the second copy of a key in one object (the parser would keep
// the last silently: a file with two "net" fields would be solved with one of them).
struct DuplicateKey {
  std::string field;
};

// The containers open around the parser: each object's keys so far, each array's element count;
// enough to name a repeated key by its path (`ribbons.left`, `sides[1].name`).
class KeyTracker {
 public:
  void open(bool object) {
    count_element();
    frames_.push_back(Frame{object, {}, {}, -1});
  }
  void close() {
    if (!frames_.empty()) frames_.pop_back();
  }
  void value() { count_element(); }
  void key(const std::string& name) {
    if (frames_.empty()) return;
    Frame& top = frames_.back();
    if (!top.keys.insert(name).second) throw DuplicateKey{path() + (frames_.size() > 1 ? "." : "") + name};
    top.key = name;
  }
  //! The path of the value the parser is reading now (`net[3][1][0]`, `sides.left`): where a
  //! number it cannot hold stands.
  [[nodiscard]] std::string next_value() const {
    std::string out = path();
    if (frames_.empty()) return out;
    const Frame& top = frames_.back();
    if (top.object) return out + (out.empty() ? "" : ".") + top.key;
    return out + "[" + std::to_string(top.index + 1) + "]";
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;  // the key being read (objects)
    long long index;  // the element being read (arrays)
  };
  void count_element() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  // The path of the innermost object: its enclosing keys and indices.
  [[nodiscard]] std::string path() const {
    std::string out;
    for (std::size_t k = 0; k + 1 < frames_.size(); ++k)
      out +=
          frames_[k].object ? (out.empty() ? "" : ".") + frames_[k].key : "[" + std::to_string(frames_[k].index) + "]";
    return out;
  }
  std::vector<Frame> frames_;
};

std::string describe(const nlohmann::json& j) {
  if (j.is_number_integer()) return j.dump();
  // as written (3.0 stays 3.0: a float, however integral, is not an integer here); an integer
  // beyond 64 bits is read as a double too, and is not "a float" to whoever wrote it
  if (j.is_number_float()) {
    const double x = j.get<double>();
    if (x != std::trunc(x)) return j.dump();
    return j.dump() + (std::abs(x) >= 0x1p63 ? " (beyond the 64-bit integers)" : " (a float)");
  }
  return fmt::format("a {}", j.type_name());
}

}  // namespace

bool JsonReadOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (max_depth < 1) return fail("max_depth must be at least 1");
  if (max_bytes < 1) return fail("max_bytes must be at least 1");
  return true;
}

namespace {

// For each number token of `text` that the parser reads as a double (a fraction or an exponent),
// in document order: whether it is a non-zero number below the smallest double, which the parser
// silently reads as 0 (1e-5000; the command line and Matrix Market refuse it). Strings are skipped.
std::vector<bool> underflowing_floats(const std::string& text) {
  std::vector<bool> out;
  const char* p = text.data();
  const char* const end = p + text.size();
  bool in_string = false;
  for (; p < end; ++p) {
    const char c = *p;
    if (in_string) {
      if (c == '\\')
        ++p;
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
      continue;
    }
    if (c != '-' && (c < '0' || c > '9')) continue;
    const char* const start = p;
    bool fraction_or_exponent = false, negative_exponent = false;
    for (; p < end; ++p) {
      const char d = *p;
      if (d >= '0' && d <= '9') continue;
      if (d == '.' || d == 'e' || d == 'E') {
        fraction_or_exponent = true;
      } else if (d == '-' || d == '+') {
        negative_exponent = negative_exponent || (d == '-' && p > start && (p[-1] == 'e' || p[-1] == 'E'));
      } else {
        break;
      }
    }
    const std::size_t length = std::size_t(p - start);
    --p;
    if (!fraction_or_exponent) {
      // an integer: the parser keeps it exact, unless it lies beyond 64 bits (then a double, which
      // the callback counts as a float: the two counts must stay in step). Below 19 digits none
      // is, so the integers of a large file cost no copy and no strtoll.
      if (length < 19) continue;
      const std::string token(start, length);
      errno = 0;
      if (token[0] == '-')
        (void)std::strtoll(token.c_str(), nullptr, 10);
      else
        (void)std::strtoull(token.c_str(), nullptr, 10);
      if (errno == ERANGE) out.push_back(false);
      continue;
    }
    // only a negative exponent or hundreds of digits reach below the doubles: almost every number
    // of a large net file needs no strtod
    bool below = false;
    if (negative_exponent || length > 300) {
      const std::string token(start, length);
      below = std::strtod(token.c_str(), nullptr) == 0 && !zero_digits(token);
    }
    out.push_back(below);
  }
  return out;
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& source, const JsonReadOptions& options) {
  if (std::string why; !options.is_valid(&why)) throw InputError(source, kDocumentField, why);
  if (text.size() > options.max_bytes)
    throw InputError(source, kDocumentField,
                     fmt::format("{} bytes, more than the limit of {} bytes", text.size(), options.max_bytes));
  // depth = the number of containers around the one being opened: the top level is depth 0.
  // Also refuses a key given twice in one object.
  KeyTracker keys;
  const std::vector<bool> underflows = underflowing_floats(text);
  std::size_t float_index = 0;
  const auto depth_guard = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    if ((event == Event::object_start || event == Event::array_start) && depth >= options.max_depth) throw TooDeep{};
    switch (event) {
      case Event::object_start:
        keys.open(true);
        break;
      case Event::array_start:
        keys.open(false);
        break;
      case Event::object_end:
      case Event::array_end:
        keys.close();
        break;
      case Event::key:
        keys.key(parsed.get<std::string>());
        break;
      case Event::value:
        if (parsed.is_number_float()) {
          if (float_index < underflows.size() && underflows[float_index] && parsed.get<double>() == 0)
            throw Underflow{keys.next_value()};
          ++float_index;
        }
        keys.value();
        break;
    }
    return true;
  };
  try {
    return nlohmann::json::parse(text, depth_guard);
  } catch (const Underflow& u) {
    throw InputError(source, u.field.empty() ? kDocumentField : u.field,
                     "a number below the smallest double, which would be read as 0 (write 0, or a value of at least "
                     "about 5e-324)");
  } catch (const TooDeep&) {
    throw InputError(source, kDocumentField, fmt::format("nesting deeper than {} levels", options.max_depth));
  } catch (const DuplicateKey& d) {
    throw InputError(source, d.field,
                     "the key appears twice in its object; a reader would silently keep only one of the two");
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(source, kDocumentField, fmt::format("malformed JSON at byte {}", e.byte));
  } catch (const nlohmann::json::out_of_range& e) {
    // 406: a number beyond the doubles; name its field and the number, not the library's wording
    if (e.id == 406) {
      const std::string what = e.what();
      const std::size_t open = what.find('\''), close = what.rfind('\'');
      const std::string number = open != std::string::npos && close > open ? what.substr(open, close - open + 1) : "";
      const std::string field = keys.next_value();
      throw InputError(source, field.empty() ? kDocumentField : field,
                       fmt::format("the number {} is beyond the range of doubles", number));
    }
    throw InputError(source, kDocumentField, fmt::format("unreadable JSON ({})", e.what()));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(source, kDocumentField, fmt::format("unreadable JSON ({})", e.what()));
  }
}

namespace {

// The text of inputs that are not regular files (a pipe, /dev/stdin, a FIFO, `<(...)`), kept per
// path for the rest of the process: a command may read its input twice (is_triangle_file, then
// the reader), and the second read of a pipe found it empty ("malformed JSON at byte 1") or, for a
// FIFO, waited for a writer that was gone (a hang).
std::mutex& stream_texts_mutex() {
  static std::mutex mutex;
  return mutex;
}
std::map<std::string, std::string>& stream_texts() {
  static std::map<std::string, std::string> texts;
  return texts;
}

}  // namespace

nlohmann::json read_json_file(const std::string& path, const JsonReadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "is a directory, not a file");
  const bool regular = std::filesystem::is_regular_file(path, ec);
  if (!regular) {
    const std::lock_guard<std::mutex> lock(stream_texts_mutex());
    if (const auto seen = stream_texts().find(path); seen != stream_texts().end())
      return parse_json_text(seen->second, path, options);  // which holds it to options.max_bytes
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the file");
  // The size is checked before the contents are read: a regular file by its length, anything else
  // (a pipe, a device) by reading at most max_bytes + 1 bytes.
  const std::uintmax_t size = regular ? std::filesystem::file_size(path, ec) : 0;
  if (!ec && size > options.max_bytes)
    throw InputError(path, kDocumentField,
                     fmt::format("{} bytes, more than the limit of {} bytes", size, options.max_bytes));
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (text.size() > options.max_bytes)
      throw InputError(path, kDocumentField, fmt::format("more than the limit of {} bytes", options.max_bytes));
  }
  if (in.bad()) throw InputError(path, "", "read error");
  if (!regular) {
    const std::lock_guard<std::mutex> lock(stream_texts_mutex());
    stream_texts()[path] = text;
  }
  return parse_json_text(text, path, options);
}

std::int64_t json_integer(const nlohmann::json& j, const std::string& source, const std::string& field, std::int64_t lo,
                          std::int64_t hi) {
  const std::string range = fmt::format("an integer in [{}, {}]", lo, hi);
  if (j.is_number_unsigned()) {
    const auto u = j.get<std::uint64_t>();
    if (hi >= 0 && u <= static_cast<std::uint64_t>(hi) && (lo <= 0 || u >= static_cast<std::uint64_t>(lo)))
      return static_cast<std::int64_t>(u);
    throw InputError(source, field, fmt::format("must be {}, not {}", range, j.dump()));
  }
  if (j.is_number_integer()) {
    const auto v = j.get<std::int64_t>();
    if (v >= lo && v <= hi) return v;
    throw InputError(source, field, fmt::format("must be {}, not {}", range, j.dump()));
  }
  throw InputError(source, field, fmt::format("must be {}, not {}", range, describe(j)));
}

int json_int(const nlohmann::json& j, const std::string& source, const std::string& field, int lo, int hi) {
  return static_cast<int>(json_integer(j, source, field, lo, hi));  // within [lo, hi]: an int
}

double json_coordinate(const nlohmann::json& j, const std::string& source, const std::string& field,
                       const std::string& what) {
  if (!j.is_number()) throw InputError(source, field, fmt::format("{} is not a number", what));
  const double x = j.get<double>();
  if (const std::string why = coordinate_problem(x); !why.empty()) throw InputError(source, field, what + " " + why);
  return x;
}

bool zero_digits(const std::string& number) {
  const bool hex = number.find_first_of("xX") != std::string::npos;
  const std::string digits = number.substr(0, number.find_first_of(hex ? "pP" : "eE"));
  return digits.find_first_of(hex ? "123456789abcdefABCDEF" : "123456789") == std::string::npos;
}

std::string coordinate_problem(double x) {
  if (!std::isfinite(x)) return "is not finite";
  if (std::abs(x) > kMaxCoordinate)
    return fmt::format(
        "is {:.17g}, beyond the bound |x| <= {:g} (energies scale as x^2 and would overflow; scale the "
        "model down)",
        x, kMaxCoordinate);
  return "";
}

void require_model_size(double largest, double min_size, const std::string& source, const std::string& field) {
  if (largest > 0 && largest < min_size)
    throw InputError(source, field,
                     fmt::format("the largest coordinate magnitude of the model is {:.3g}, below {:g}: energies "
                                 "(which scale as x^2) and curvatures (as 1/x and 1/x^2) would leave the doubles; "
                                 "scale the model up (optimal parameters and shapes do not depend on the scale)",
                                 largest, min_size));
}

}  // namespace coons
