// Output files are written whole or not at all, and only inside the folder they were asked for.
// Each file goes to a staging name unique to the process (path + ".tmp-<pid>-<counter>") beside its
// target, every write is checked (a full disk is an error with the OS reason), and it is renamed
// into place (atomically) when complete. An OutputSet stages the files of one command and
// publishes them together, or removes every file and folder it started on any failure path,
// exceptions included. A process stopped by SIGINT, SIGTERM or SIGHUP removes its staging files
// before it dies (a handler installed with the first staging name, unless the signal is ignored
// or handled already); the folders it created may remain, empty.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace coons {

//! A name from an input file made safe as one component of a file name: letters, digits, '-',
//! '_', '.' and UTF-8 letters kept, every other byte (separators, control characters, quotes) as
//! '_', no leading '.', at most kMaxFileStemBytes bytes, "unnamed" when nothing is left.
inline constexpr std::size_t kMaxFileStemBytes = 80;
std::string safe_file_stem(std::string_view name);

//! True when the two paths name one file: compared after making them absolute, resolving the part
//! of each that exists (symbolic links included) and removing "." and "..", so that "x.obj",
//! "./x.obj" and "d/../x.obj" are one file.
bool same_file_path(const std::string& a, const std::string& b);

//! The name under which `path` is staged: path + ".tmp-<pid>-<counter>" (unique per process).
std::string staging_path(const std::string& path);

//! Calls write(stream) on a staging file, checks the stream, then renames it to `path` (a
//! symbolic link: to the file it names). Throws InputError (naming `path` and the OS reason) when
//! the file cannot be written, and when `path` is a device, pipe or socket.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

//! The files of one command: staged, then published together (or all removed).
class OutputSet {
 public:
  //! `folder` is where every file goes (created when the first file is staged); `field` names it
  //! in error messages (the CLI: the option that gave it, e.g. "--out").
  OutputSet(std::string folder, std::string field);
  ~OutputSet();  //!< removes everything staged and every folder it created unless commit() ran
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  //! The final path of a file `relative` to the folder. Throws InputError when `relative` would
  //! leave the folder (absolute, "..").
  [[nodiscard]] std::string path_of(const std::string& relative) const;

  //! Reserves `relative` and returns the staging path to write it to (its folders are created).
  //! Throws InputError when `relative` was already staged in this set.
  std::string stage(const std::string& relative);

  //! Stages `relative` and writes it through `write` (stream checked).
  void write(const std::string& relative, const std::function<void(std::ostream&)>& write);

  //! Stages a file at a path chosen on the command line (not from an input file's data): any
  //! folder, which must exist; through a symbolic link to its target; a device, pipe or socket is
  //! an InputError. Returns the staging path.
  std::string stage_path(const std::string& path);
  void write_path(const std::string& path, const std::function<void(std::ostream&)>& write);

  //! Gives up one staged file (removes its staging file, if any); commit() then removes a file an
  //! earlier run left under that name, as remove_stale() does.
  void discard(const std::string& relative);

  //! Marks `relative` as an output this run does not have: commit() removes a file an earlier run
  //! left under that name (a failed solve's OBJ files, a plot that could not be drawn), so that
  //! no earlier run's file stands beside this run's report; undone with the rest on a failure.
  void remove_stale(const std::string& relative);

  //! Renames every staged file into place; returns the final paths in the order staged. A file
  //! it replaces first gets a second name (a hard link; moved there where links are not
  //! possible), so on a failure (a target that is a folder, say) it puts the replaced files back
  //! and removes what it had published, throws InputError, and the folder is as before. The
  //! second names go when the set is destroyed, or with the staging files on a signal.
  std::vector<std::string> commit();

  //! commit(), then announce() (e.g. print the report); when announce throws (a failed write to
  //! standard output), the commit is undone as above and the exception passes on. So a command
  //! either publishes its files and prints its report, or does neither.
  std::vector<std::string> publish(const std::function<void()>& announce);

  //! Removes what was staged (and created folders that are empty); the destructor does this.
  void rollback() noexcept;

 private:
  struct Entry {
    std::string final_path, staging;
    std::string aside;         //!< a second name commit() gave the file it replaced (empty: none)
    bool aside_moved = false;  //!< the file was moved there (no hard links), not linked
    bool published = false;
    bool removal = false;  //!< remove_stale(): no staging file; commit() takes the old file away
  };
  std::string folder_, field_;
  std::vector<Entry> entries_;
  std::vector<std::string> created_folders_;  //!< in the order created
  bool committed_ = false;

  void make_folders(const std::string& folder);
  void undo_commit() noexcept;  // the published files removed, the replaced ones back
  static void write_staged(const std::string& path, const std::string& staging,
                           const std::function<void(std::ostream&)>& write);
};

}  // namespace coons
