#include "write_files.h"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>

#include "coons/io/input_error.h"

namespace coons {

namespace fs = std::filesystem;

namespace {

std::atomic<unsigned long> staging_counter{0};

// Length of the UTF-8 sequence starting at s[i] that is valid and encodes a letter-like
// character (any code point ≥ U+00A0), else 0.
size_t utf8_letter(std::string_view s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  size_t len = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
  if (len == 0 || i + len > s.size()) return 0;
  for (size_t k = 1; k < len; ++k)
    if ((static_cast<unsigned char>(s[i + k]) & 0xC0) != 0x80) return 0;
  if (len == 2 && c == 0xC2 && static_cast<unsigned char>(s[i + 1]) < 0xA0) return 0;   // C1 controls
  if (len == 3 && c == 0xE0 && static_cast<unsigned char>(s[i + 1]) < 0xA0) return 0;   // overlong
  if (len == 3 && c == 0xED && static_cast<unsigned char>(s[i + 1]) >= 0xA0) return 0;  // surrogates
  if (len == 4 && c == 0xF0 && static_cast<unsigned char>(s[i + 1]) < 0x90) return 0;   // overlong
  if (len == 4 && c == 0xF4 && static_cast<unsigned char>(s[i + 1]) >= 0x90) return 0;  // > U+10FFFF
  return len;
}

std::string os_reason(int error) { return error ? std::strerror(error) : "write failed"; }

// Flushes and closes a stream written with errno cleared before, and returns the reason of its
// first failure: the errno of the write that failed while the writer ran (a full disk fails one of
// the buffered writes long before the flush; reading errno only around the flush printed "write
// failed: write failed"), else of the flush or the close.
int finish_stream(std::ofstream& out) {
  int error = out ? 0 : errno;
  if (error == 0) errno = 0;
  out.flush();
  if (error == 0 && !out) error = errno;
  out.close();
  if (error == 0 && !out) error = errno;
  return error;
}

// Staging files removed when the process is interrupted (SIGINT, SIGTERM, SIGHUP): a command
// stopped with Ctrl-C while writing left its PATH.tmp-PID-N files (43 MB for an OBJ) behind. The
// handler unlinks every staging name this process has made (a name already renamed into place or
// removed is simply not found: names are never reused), then dies of the signal as before. The
// names are kept in a fixed table of atomic pointers, which is all an async-signal handler may read.
constexpr std::size_t kTrackedStagings = std::size_t(1) << 16;
std::array<std::atomic<char*>, kTrackedStagings> tracked_stagings{};
std::atomic<std::size_t> next_tracked{0};

extern "C" void remove_stagings_and_die(int signal_number) {
  for (std::atomic<char*>& slot : tracked_stagings)
    if (const char* name = slot.load(std::memory_order_relaxed)) ::unlink(name);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);
}

void track_staging(const std::string& staging) {
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction previous {};
      if (sigaction(signal_number, nullptr, &previous) != 0 || previous.sa_handler != SIG_DFL)
        continue;  // ignored (nohup) or handled by someone else: left alone
      struct sigaction action {};
      action.sa_handler = remove_stagings_and_die;
      sigemptyset(&action.sa_mask);
      sigaction(signal_number, &action, nullptr);
    }
  });
  // (a name 65,536 stagings old, long renamed or removed, makes room; it is freed here, never in the handler)
  char* old = tracked_stagings[next_tracked.fetch_add(1) % kTrackedStagings].exchange(strdup(staging.c_str()));
  std::free(old);
}

// Where a file named on the command line is written: through a symbolic link to the file it names
// (renaming the staged file over the link replaced the link and left its target as it was), and
// never over something that is not a regular file: `--out /dev/full --force` replaced the device
// with a regular file. A folder is left to the rename, which refuses it.
std::string command_line_target(const std::string& path) {
  std::error_code ec;
  fs::path target = path;
  // link by link, so that a link to a file that does not exist yet (dangling) is written through
  // too: weakly_canonical stopped there and the link was replaced
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    if (hops == 40) throw InputError(path, "", "too many levels of symbolic links");
    const fs::path next = fs::read_symlink(target, ec);
    if (ec) throw InputError(path, "", "cannot follow the symbolic link: " + ec.message());
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  const fs::file_status status = fs::status(target, ec);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status))
    throw InputError(path, "",
                     "not a regular file (a device, pipe or socket): coons writes a whole file and renames it into "
                     "place; give the path of a file");
  return target.string();
}

}  // namespace

std::string safe_file_stem(std::string_view name) {
  std::string out;
  for (size_t i = 0; i < name.size() && out.size() < kMaxFileStemBytes;) {
    const auto c = static_cast<unsigned char>(name[i]);
    if ((std::isalnum(c) && c < 0x80) || c == '-' || c == '_' || c == '.') {
      out += char(c);
      ++i;
    } else if (const size_t len = utf8_letter(name, i); len > 0) {
      if (out.size() + len > kMaxFileStemBytes) break;
      out.append(name.substr(i, len));
      i += len;
    } else {
      out += '_';
      ++i;
    }
  }
  while (!out.empty() && out.front() == '.') out.front() = '_';
  if (out.empty()) out = "unnamed";
  return out;
}

bool same_file_path(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const auto resolved = [](const std::string& p) {
    std::error_code ec;
    fs::path full = fs::absolute(p, ec);
    if (ec) return fs::path(p).lexically_normal();
    fs::path canonical = fs::weakly_canonical(full, ec);
    return ec ? full.lexically_normal() : canonical;
  };
  return resolved(a) == resolved(b);
}

std::string staging_path(const std::string& path) {
  std::string staging = fmt::format("{}.tmp-{}-{}", path, static_cast<long>(getpid()), staging_counter.fetch_add(1));
  track_staging(staging);
  return staging;
}

void write_file_atomically(const std::string& given, const std::function<void(std::ostream&)>& write) {
  const std::string path = command_line_target(given);
  const std::string temporary = staging_path(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "", "cannot create the file: " + os_reason(errno));
    errno = 0;
    try {
      write(out);
    } catch (...) {
      out.close();
      std::remove(temporary.c_str());
      throw;
    }
    const int error = finish_stream(out);
    if (!out) {
      std::remove(temporary.c_str());
      throw InputError(path, "", "write failed: " + os_reason(error));
    }
  }
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw InputError(path, "", "cannot rename into place: " + ec.message());
  }
}

OutputSet::OutputSet(std::string folder, std::string field) : folder_(std::move(folder)), field_(std::move(field)) {
  if (folder_.empty()) folder_ = ".";
}

OutputSet::~OutputSet() {
  if (!committed_) rollback();
  for (const Entry& e : entries_)
    if (!e.aside.empty()) std::remove(e.aside.c_str());
}

std::string OutputSet::path_of(const std::string& relative) const {
  const fs::path rel(relative);
  if (relative.empty() || rel.is_absolute() || rel.has_root_name())
    throw InputError(folder_, field_, "the output name '" + relative + "' is not a relative file name");
  for (const auto& part : rel)
    if (part == ".." || part == ".")
      throw InputError(folder_, field_, "the output name '" + relative + "' would leave the folder");
  return (fs::path(folder_) / rel).string();
}

void OutputSet::make_folders(const std::string& folder) {
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = folder; !p.empty(); p = p.parent_path()) {
    const bool there = fs::exists(p, ec);
    if (ec)  // not "does not exist": a loop of symbolic links, a folder we may not search, ...
      throw InputError(p.string(), field_, "cannot use the folder: " + ec.message());
    if (there) {
      if (!fs::is_directory(p, ec)) throw InputError(p.string(), field_, "exists and is not a folder");
      break;
    }
    if (fs::is_symlink(fs::symlink_status(p, ec)))
      throw InputError(p.string(), field_, "is a symbolic link to a missing target; cannot create the folder there");
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!fs::create_directory(*it, ec) && ec)
      throw InputError(it->string(), field_, "cannot create the folder: " + ec.message());
    created_folders_.push_back(it->string());
  }
}

std::string OutputSet::stage(const std::string& relative) {
  const std::string path = path_of(relative);
  for (const Entry& e : entries_)
    if (same_file_path(e.final_path, path))
      throw InputError(path, field_, "two outputs of this command would have the same name");
  make_folders(fs::path(path).parent_path().string());
  entries_.push_back({path, staging_path(path), "", false});
  return entries_.back().staging;
}

std::string OutputSet::stage_path(const std::string& given) {
  const std::string path = command_line_target(given);
  for (const Entry& e : entries_)
    if (same_file_path(e.final_path, path))
      throw InputError(path, field_, "two outputs of this command would have the same name");
  entries_.push_back({path, staging_path(path), "", false});
  return entries_.back().staging;
}

void OutputSet::write_path(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string staging = stage_path(path);
  write_staged(entries_.back().final_path, staging, write);
}

void OutputSet::write(const std::string& relative, const std::function<void(std::ostream&)>& write) {
  const std::string path = path_of(relative);
  write_staged(path, stage(relative), write);
}

void OutputSet::write_staged(const std::string& path, const std::string& staging,
                             const std::function<void(std::ostream&)>& write) {
  std::ofstream out(staging, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path, "", "cannot create the file: " + os_reason(errno));
  errno = 0;
  write(out);
  const int error = finish_stream(out);
  if (!out) throw InputError(path, "", "write failed: " + os_reason(error));
}

void OutputSet::discard(const std::string& relative) {
  const std::string path = (fs::path(folder_) / relative).string();
  for (Entry& e : entries_)
    if (e.final_path == path) {
      std::remove(e.staging.c_str());
      e.removal = true;  // an earlier run's file of that name does not belong beside this run's
      return;
    }
}

void OutputSet::remove_stale(const std::string& relative) {
  const std::string path = path_of(relative);
  for (const Entry& e : entries_)
    if (same_file_path(e.final_path, path))
      throw InputError(path, field_, "two outputs of this command would have the same name");
  Entry e{path, staging_path(path), "", false};
  e.removal = true;
  entries_.push_back(e);
}

std::vector<std::string> OutputSet::commit() {
  std::vector<std::string> published;
  const auto fail = [&](const Entry& e, const std::string& why) {
    undo_commit();
    throw InputError(e.final_path, "", why);
  };
  for (Entry& e : entries_) {
    std::error_code ec;
    if (e.removal) {
      // Moved aside (undo_commit() moves it back; the destructor removes the second name).
      if (!fs::is_regular_file(e.final_path, ec)) continue;
      const std::string aside = e.staging + ".replaced";
      track_staging(aside);
      fs::rename(e.final_path, aside, ec);
      if (ec) fail(e, "cannot remove the file an earlier run left: " + ec.message());
      e.aside = aside;
      e.aside_moved = true;
      e.published = true;
      continue;
    }
    if (!fs::exists(e.staging, ec)) fail(e, "was not written");
    if (fs::is_directory(e.final_path, ec)) fail(e, "cannot rename into place: it is a folder");
    if (fs::exists(e.final_path, ec)) {
      // The file it replaces is kept under a second name, a hard link, so that the final name
      // always holds a whole file, the old one until the rename below. A signal in between
      // (the handler removes the link, a tracked name) leaves the old file in place; moving it
      // aside, as before, left the name missing and the old file under *.replaced. Where the
      // file system has no hard links, it is moved aside.
      const std::string aside = e.staging + ".replaced";
      track_staging(aside);
      if (::link(e.final_path.c_str(), aside.c_str()) != 0) {
        fs::rename(e.final_path, aside, ec);
        if (ec) fail(e, "cannot move the existing file aside: " + ec.message());
        e.aside_moved = true;
      }
      e.aside = aside;
    }
    fs::rename(e.staging, e.final_path, ec);
    if (ec) fail(e, "cannot rename into place: " + ec.message());
    e.published = true;
    published.push_back(e.final_path);
  }
  committed_ = true;
  return published;
}

std::vector<std::string> OutputSet::publish(const std::function<void()>& announce) {
  std::vector<std::string> published = commit();
  try {
    announce();
  } catch (...) {
    undo_commit();
    throw;
  }
  return published;
}

void OutputSet::undo_commit() noexcept {
  for (auto it = entries_.rbegin(); it != entries_.rend(); ++it) {
    std::error_code ec;
    if (it->aside.empty()) {
      if (it->published) fs::remove(it->final_path, ec);
    } else if (it->published || it->aside_moved) {
      fs::rename(it->aside, it->final_path, ec);  // the old file back, in one step
    } else {
      fs::remove(it->aside, ec);  // its final name still holds the old file
    }
    it->aside.clear();
    it->aside_moved = false;
    it->published = false;
  }
  committed_ = false;  // the destructor removes the staging files that remain and the new folders
}

void OutputSet::rollback() noexcept {
  for (const Entry& e : entries_) std::remove(e.staging.c_str());
  entries_.clear();
  for (auto it = created_folders_.rbegin(); it != created_folders_.rend(); ++it) {
    std::error_code ec;
    fs::remove(*it, ec);  // only removes an empty folder
  }
  created_folders_.clear();
}

}  // namespace coons
