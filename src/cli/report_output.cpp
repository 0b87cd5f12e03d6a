#include "report_output.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "coons/io/input_error.h"
#include "coons/io/net_json.h"

namespace coons::cli {

namespace {

// Checked writes to standard output; the first failure is an InputError naming the OS reason.
void write_out(std::string_view text) {
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), stdout) == text.size()) return;
  const int error = errno;
  std::clearerr(stdout);
  throw InputError("<stdout>", "", std::string("write failed: ") + (error ? std::strerror(error) : "unknown error"));
}

void flush_out() {
  errno = 0;
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return;
  const int error = errno;
  std::clearerr(stdout);
  throw InputError("<stdout>", "", std::string("write failed: ") + (error ? std::strerror(error) : "unknown error"));
}

// A top-level value of a report dumped with indent 2: "\n  \"KEY\": VALUE" (deeper keys have more
// spaces, and a newline inside a string is escaped, so this names the top-level key only).
std::string top_level(const std::string& key, const std::string& value) { return "\n  \"" + key + "\": " + value; }

}  // namespace

void print_net_report(nlohmann::json report, const ControlNet* net, Phases& phases, bool points_inline) {
  phases.start("write");
  const std::string placeholder = "\"coons-placeholder\"";
  if (net) report["net"] = "coons-placeholder";
  report["timing"] = "coons-placeholder";
  const std::string text = (points_inline ? dump_points_inline(report) : dump(report, 2)) + '\n';

  enum class Part { kNet, kTiming };
  std::vector<std::pair<std::size_t, Part>> parts;  // where each placeholder starts
  const std::string timing_key = top_level("timing", placeholder), net_key = top_level("net", placeholder);
  parts.emplace_back(text.find(timing_key) + timing_key.size() - placeholder.size(), Part::kTiming);
  if (net) parts.emplace_back(text.find(net_key) + net_key.size() - placeholder.size(), Part::kNet);
  std::sort(parts.begin(), parts.end());

  std::size_t at = 0;
  for (const auto& [where, part] : parts) {
    write_out(std::string_view(text).substr(at, where - at));
    if (part == Part::kNet) {
      write_net_json(*net, 1, write_out);
    } else {
      flush_out();  // the net is out: the write phase ends here
      std::string timing = dump(phases.timing(), 2);
      for (std::size_t p = timing.find('\n'); p != std::string::npos; p = timing.find('\n', p + 1))
        timing.insert(p + 1, "  ");
      write_out(timing);
    }
    at = where + placeholder.size();
  }
  write_out(std::string_view(text).substr(at));
  flush_out();
}

}  // namespace coons::cli
