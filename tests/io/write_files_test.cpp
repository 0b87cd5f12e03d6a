// Output files: staged, checked, published together or not at all, only inside their folder
// (coons/io/write_files.h).
#include "coons/io/write_files.h"

#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "coons/io/input_error.h"
#include "support/fixtures.h"

using namespace coons;
using namespace coons::test;
namespace fs = std::filesystem;

namespace {
std::vector<std::string> files_under(const fs::path& root) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root)) out.push_back(fs::relative(e.path(), root).string());
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

TEST_CASE("safe_file_stem: names are data, never paths", "[io]") {
  CHECK(safe_file_stem("dome") == "dome");
  CHECK(safe_file_stem("quarter_cylinder-2.v1") == "quarter_cylinder-2.v1");
  CHECK(safe_file_stem("../escaped") == "_._escaped");
  CHECK(safe_file_stem("/tmp/x") == "_tmp_x");
  CHECK(safe_file_stem("a\\b") == "a_b");
  CHECK(safe_file_stem("line\nbreak\ttab\x01") == "line_break_tab_");
  CHECK(safe_file_stem("") == "unnamed");
  CHECK(safe_file_stem(".hidden") == "_hidden");
  CHECK(safe_file_stem("..") == "_.");
  CHECK(safe_file_stem("Kegel \xC3\xBC") == "Kegel_\xC3\xBC");  // UTF-8 letters stay
  CHECK(safe_file_stem("bad \xFF\xFE") == "bad___");            // invalid UTF-8 does not
  CHECK(safe_file_stem(std::string(1000, 'x')).size() == 80);
  for (const std::string& name :
       std::vector<std::string>{"../escaped", "/tmp/x", "a/b", std::string(1, '\0') + "x", std::string(1000, '/')}) {
    const std::string stem = safe_file_stem(name);
    CHECK(stem.find('/') == std::string::npos);
    CHECK(stem != "..");
    CHECK(stem != ".");
    CHECK(!stem.empty());
  }
}

TEST_CASE("staging_path: unique per call and per process", "[io]") {
  const std::string a = staging_path("x.obj"), b = staging_path("x.obj");
  CHECK(a != b);
  CHECK(a.rfind("x.obj.tmp-", 0) == 0);
}

TEST_CASE("OutputSet: publishes every file together, or removes files and folders it created", "[io]") {
  TempDir dir;
  {
    OutputSet out((dir.path / "new" / "deeper").string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "a\n"; });
    out.write("sub/b.txt", [](std::ostream& o) { o << "b\n"; });
    CHECK(!fs::exists(dir.path / "new" / "deeper" / "a.txt"));  // staged only
  }  // no commit: everything goes, the folders it created too
  CHECK(files_under(dir.path).empty());

  OutputSet out((dir.path / "out").string(), "--out");
  out.write("a.txt", [](std::ostream& o) { o << "a\n"; });
  out.write("sub/b.txt", [](std::ostream& o) { o << "b\n"; });
  const auto published = out.commit();
  CHECK(published.size() == 2);
  CHECK(files_under(dir.path / "out") == std::vector<std::string>{"a.txt", "sub", "sub/b.txt"});
}

TEST_CASE("OutputSet: names that leave the folder and repeated names are refused", "[io]") {
  TempDir dir;
  OutputSet out((dir.path / "out").string(), "--out");
  CHECK_THROWS_AS(out.stage("../x.txt"), InputError);
  CHECK_THROWS_AS(out.stage("/tmp/x.txt"), InputError);
  CHECK_THROWS_AS(out.stage("a/../../x.txt"), InputError);
  out.stage("x.txt");
  CHECK_THROWS_AS(out.stage("x.txt"), InputError);
  out.rollback();
  CHECK(files_under(dir.path).empty());
}

TEST_CASE("OutputSet: a loop of symbolic links or a broken link as the folder is named with its reason", "[io]") {
  // both once fell through to create_directory, whose error was "File exists"
  TempDir dir;
  fs::create_symlink(dir.path / "loop", dir.path / "loop");
  fs::create_symlink(dir.path / "nowhere", dir.path / "broken");
  const auto write_into = [&](const std::string& folder) {
    OutputSet out((dir.path / folder).string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "a\n"; });
  };
  CHECK_THROWS_WITH(write_into("loop"),
                    Catch::Contains("--out: cannot use the folder: Too many levels of symbolic links"));
  CHECK_THROWS_WITH(write_into("loop/sub"),
                    Catch::Contains("cannot use the folder: Too many levels of symbolic links"));
  CHECK_THROWS_WITH(write_into("broken"), Catch::Contains("--out: is a symbolic link to a missing target"));
  CHECK(!fs::exists(dir.path / "nowhere"));
  std::vector<std::string> names;  // files_under would follow the loop
  for (const auto& e : fs::directory_iterator(dir.path)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"broken", "loop"});
}

TEST_CASE("OutputSet: an exception inside a write removes what was started", "[io]") {
  TempDir dir;
  try {
    OutputSet out((dir.path / "out").string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "a\n"; });
    out.write("b.txt", [](std::ostream& o) {
      o << "half";
      throw std::runtime_error("interrupted");
    });
    out.commit();
  } catch (const std::runtime_error&) {
  }
  CHECK(files_under(dir.path).empty());
}

namespace {
std::string contents(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("OutputSet::commit: a target that is a folder leaves the output folder as it was", "[io]") {
  TempDir dir;
  const fs::path out_dir = dir.path / "out";
  fs::create_directories(out_dir / "b.txt");  // a folder where a file is to go
  std::ofstream(out_dir / "a.txt") << "old\n";
  {
    OutputSet out(out_dir.string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "new\n"; });
    out.write("b.txt", [](std::ostream& o) { o << "b\n"; });
    CHECK_THROWS_AS(out.commit(), InputError);
  }
  CHECK(contents(out_dir / "a.txt") == "old\n");  // replaced, then put back
  CHECK(files_under(out_dir) == std::vector<std::string>{"a.txt", "b.txt"});
  CHECK(fs::is_directory(out_dir / "b.txt"));
}

TEST_CASE("OutputSet::publish: an announcement that fails undoes the commit", "[io]") {
  TempDir dir;
  const fs::path out_dir = dir.path / "out";
  fs::create_directories(out_dir);
  std::ofstream(out_dir / "a.txt") << "old\n";
  {
    OutputSet out(out_dir.string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "new\n"; });
    out.write("c.txt", [](std::ostream& o) { o << "c\n"; });
    CHECK_THROWS_AS(out.publish([] { throw InputError("<stdout>", "", "write failed"); }), InputError);
  }
  CHECK(contents(out_dir / "a.txt") == "old\n");
  CHECK(files_under(out_dir) == std::vector<std::string>{"a.txt"});
  {
    OutputSet out(out_dir.string(), "--out");
    out.write("a.txt", [](std::ostream& o) { o << "new\n"; });
    bool announced = false;
    CHECK(out.publish([&] { announced = true; }).size() == 1);
    CHECK(announced);
  }
  CHECK(contents(out_dir / "a.txt") == "new\n");
  CHECK(files_under(out_dir) == std::vector<std::string>{"a.txt"});  // the replaced file is gone
}

TEST_CASE(
    "OutputSet::remove_stale: an earlier run's file of a name this run does not write goes, and comes back on undo",
    "[io]") {
  TempDir dir;
  const fs::path out_dir = dir.path / "out";
  fs::create_directories(out_dir);
  std::ofstream(out_dir / "a.obj") << "earlier surface\n";
  std::ofstream(out_dir / "a.png") << "earlier plot\n";
  {  // an announcement that fails: both files as they were
    OutputSet out(out_dir.string(), "--out");
    out.write("a.json", [](std::ostream& o) { o << "failed\n"; });
    out.remove_stale("a.obj");
    (void)out.stage("a.png");
    out.discard("a.png");  // a plot that could not be drawn
    CHECK_THROWS_AS(out.publish([] { throw InputError("<stdout>", "", "write failed"); }), InputError);
  }
  CHECK(contents(out_dir / "a.obj") == "earlier surface\n");
  CHECK(contents(out_dir / "a.png") == "earlier plot\n");
  CHECK(files_under(out_dir) == std::vector<std::string>{"a.obj", "a.png"});
  {
    OutputSet out(out_dir.string(), "--out");
    out.write("a.json", [](std::ostream& o) { o << "failed\n"; });
    out.remove_stale("a.obj");
    out.remove_stale("b.obj");  // nothing there: nothing to do
    (void)out.stage("a.png");
    out.discard("a.png");
    CHECK(out.publish([] {}) == std::vector<std::string>{(out_dir / "a.json").string()});
  }
  CHECK(files_under(out_dir) == std::vector<std::string>{"a.json"});
}

TEST_CASE("write_file_atomically: a symbolic link is written through and a pipe or device is refused", "[io]") {
  // The staged file used to be renamed over the path itself: over a link it replaced the link and
  // left the file it named as it was; over /dev/full (with --force) it replaced the device.
  TempDir dir;
  const std::string target = dir.write("target.json", "old");
  const std::string link = dir.file("link.json");
  fs::create_symlink(target, link);
  write_file_atomically(link, [](std::ostream& out) { out << "new"; });
  CHECK(fs::is_symlink(link));
  std::ifstream in(target);
  std::string text;
  in >> text;
  CHECK(text == "new");
  // the same through an OutputSet's command-line path
  {
    OutputSet set(dir.file("unused"), "--out");
    set.write_path(link, [](std::ostream& out) { out << "newer"; });
    set.commit();
  }
  CHECK(fs::is_symlink(link));
  std::ifstream again(target);
  again >> text;
  CHECK(text == "newer");
  // a link to a file that does not exist yet, by a relative path: written through, the link kept
  const std::string dangling = dir.file("dangling.json");
  fs::create_symlink("later.json", dangling);
  write_file_atomically(dangling, [](std::ostream& out) { out << "first"; });
  CHECK(fs::is_symlink(dangling));
  std::ifstream later(dir.file("later.json"));
  later >> text;
  CHECK(text == "first");
  fs::remove(dangling);
  fs::remove(dir.file("later.json"));
  // a named pipe stands for every file that is not regular (devices, sockets): refused, kept
  const std::string pipe = dir.file("pipe");
  REQUIRE(mkfifo(pipe.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(write_file_atomically(pipe, [](std::ostream& out) { out << "x"; }),
                    Catch::Contains("not a regular file"));
  OutputSet set(dir.file("unused"), "--out");
  CHECK_THROWS_WITH(set.write_path(pipe, [](std::ostream& out) { out << "x"; }), Catch::Contains("not a regular file"));
  CHECK(fs::is_fifo(pipe));
  std::vector<std::string> names;  // (not files_under: fs::relative follows the link)
  for (const auto& e : fs::directory_iterator(dir.path)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  CHECK(names == std::vector<std::string>{"link.json", "pipe", "target.json"});  // no staging file left
}

TEST_CASE("write_file_atomically and OutputSet: a write that fails while the writer runs is named by its reason",
          "[io]") {
  // A full disk fails one of the buffered writes long before the flush; errno was read only
  // around the flush, and the error read "write failed: write failed". The writer here fails as
  // such a write does: errno set, the stream bad.
  TempDir dir;
  const auto fail_like_a_full_disk = [](std::ostream& o) {
    o << "partial\n";
    errno = ENOSPC;
    o.setstate(std::ios::badbit);
  };
  const std::string file = (dir.path / "f.txt").string();
  CHECK_THROWS_WITH(write_file_atomically(file, fail_like_a_full_disk),
                    Catch::StartsWith(file) && Catch::EndsWith("write failed: " + std::string(std::strerror(ENOSPC))));
  CHECK(files_under(dir.path).empty());
  OutputSet out((dir.path / "out").string(), "--out");
  CHECK_THROWS_WITH(out.write("a.txt", fail_like_a_full_disk),
                    Catch::EndsWith("write failed: " + std::string(std::strerror(ENOSPC))));
}
