#!/usr/bin/env bash
# clang-tidy (Debian's clang-tidy 14) with the repository's .clang-tidy on the project's own .cpp files
# (src/, solvers/, tests/, experiments/benchmarks/), through the build's compile_commands.json, two at a
# time. Warnings are errors; in headers only the project's own (src/, solvers/) are checked, never
# Eigen, Ceres or Catch2. Prints each warning once and a count per check; exit 1 on any warning.
#   scripts/tidy.sh              every .cpp file in the compile database
#   scripts/tidy.sh FILE...      only these files
#   scripts/tidy.sh --since REF  only the .cpp files whose translation unit changed since commit REF:
#                                the file itself or any header its compiler depfile (<object>.d, written
#                                by the build) lists differs between REF and the working tree. Every
#                                file when .clang-tidy changed, when REF is not in the history (a shallow
#                                clone) or when a depfile is missing for that file. This is what .ci/run
#                                does, from the commit in .ci/tidy-base: the last one whose whole tree
#                                was checked clean (a whole run takes 25-45 min on 2 cores; see --record).
#   scripts/tidy.sh --record     every file (refused at once if the working tree has changes); if all
#                                are clean, write HEAD to .ci/tidy-base (commit that file afterwards).
#   scripts/tidy.sh --record-since
#                                the files of --since BASE, BASE the commit in .ci/tidy-base (known
#                                clean); if they are clean, so is HEAD's whole tree: write HEAD as
#                                --record does, in the minutes of a --since run instead of a whole one.
#                                It builds first, so that the compile database and the depfiles that
#                                select the files are HEAD's (a stale depfile could miss a new include).
# Compile flags: --record and --record-since also write to .ci/tidy-base a fingerprint of every
# distinct compile command (the command without its source and object, paths relative to the
# clone); --since then checks every file whose command has no fingerprint there too, since flags and
# definitions (a CMakeLists.txt change) alter a translation unit without changing a source.
# Environment: COONS_BUILD_DIR (default build), TIDY_JOBS (default 2).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd -P)
build=${COONS_BUILD_DIR:-build}
jobs=${TIDY_JOBS:-2}

clang_tidy=$(command -v clang-tidy-14 || command -v clang-tidy || true)
if [[ -z "$clang_tidy" ]]; then
  echo "error: clang-tidy not found (apt-get install clang-tidy)" >&2
  exit 2
fi
if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "error: $build/compile_commands.json: missing (configure with cmake -S . -B $build first)" >&2
  exit 2
fi

since=""
record=0
record_since=0
if [[ "${1:-}" == "--since" ]]; then
  [[ $# -eq 2 ]] || { echo "error: tidy.sh: --since takes one commit" >&2; exit 2; }
  since=$2
  set --
elif [[ "${1:-}" == "--record-since" ]]; then
  [[ $# -eq 1 ]] || { echo "error: tidy.sh: --record-since takes no argument (its base is .ci/tidy-base)" >&2; exit 2; }
  since=$(grep -v -e '^#' -e '^flags ' .ci/tidy-base | head -1 | tr -d '[:space:]')
  record=1
  record_since=1
  set --
elif [[ "${1:-}" == "--record" ]]; then
  [[ $# -eq 1 ]] || { echo "error: tidy.sh: --record takes no files" >&2; exit 2; }
  record=1
  set --
fi

if ((record)) && [[ -n "$(git status --porcelain --untracked-files=no)" ]]; then
  echo "error: tidy.sh: --record needs a working tree without changes (commit them first)" >&2
  exit 2
fi
if ((record_since)); then
  cmake --build "$build" -j"$jobs" >/dev/null || { echo "error: tidy.sh: the build failed" >&2; exit 2; }
fi

# The fingerprint of a compile command: sha1 of its words without the source, the object and the
# clone's paths (so that another clone, such as CI's, has the same fingerprints).
fingerprint_py='
import hashlib, shlex
def fingerprint(entry, root, build):
    words = shlex.split(entry["command"])
    out, skip = [], False
    for w in words:
        if skip:
            skip = False
            continue
        if w in ("-o", "-c"):
            skip = True
            continue
        out.append(w.replace(build, "<build>").replace(root, "<root>"))
    return hashlib.sha1(" ".join(out).encode()).hexdigest()
'
export fingerprint_py

if (($#)); then
  files=()
  for f in "$@"; do files+=("$(realpath "$f")"); done
else
  # The project's own .cpp files in the compile database; with --since only those whose translation
  # unit depends on a file changed since that commit.
  picked=$(python3 - "$build/compile_commands.json" "$root" "$since" "$(realpath "$build")" <<'PY'
import json, os, shlex, subprocess, sys
db, root, since, build_dir = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
exec(os.environ["fingerprint_py"])
own_dirs = ("src/", "solvers/", "tests/", "experiments/benchmarks/")
entries, seen = [], set()
for entry in json.load(open(db)):
    f = entry["file"]
    if f.endswith(".cpp") and f not in seen and any(f.startswith(root + "/" + d) for d in own_dirs):
        seen.add(f)
        entries.append(entry)

def git(*args):
    return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True)

changed = None  # None: every file
if since and git("rev-parse", "--verify", "--quiet", since + "^{commit}").returncode != 0:
    print(f"tidy: {since} is not in this clone's history: checking every file", file=sys.stderr)
elif since:
    names = git("diff", "--name-only", since).stdout.split()
    names += git("ls-files", "--others", "--exclude-standard").stdout.split()
    changed = {os.path.join(root, n) for n in names}
    if os.path.join(root, ".clang-tidy") in changed:
        print("tidy: .clang-tidy changed: checking every file", file=sys.stderr)
        changed = None

def depends_on_changed(entry):
    args = shlex.split(entry["command"])
    if "-o" not in args:
        return True
    depfile = os.path.join(entry["directory"], args[args.index("-o") + 1] + ".d")
    if not os.path.exists(depfile):
        return True
    words = open(depfile).read().replace("\\\n", " ").split()
    deps = {os.path.realpath(os.path.join(entry["directory"], w)) for w in words[1:] if w != "\\"}
    deps.add(os.path.realpath(entry["file"]))
    return not deps.isdisjoint(changed)

# compile commands the base was checked with (.ci/tidy-base: lines "flags SHA1"); none recorded: not compared
known = set()
if since and os.path.exists(os.path.join(root, ".ci/tidy-base")):
    known = {l.split()[1] for l in open(os.path.join(root, ".ci/tidy-base")) if l.startswith("flags ")}
if changed is not None and not known:
    print("tidy: .ci/tidy-base records no compile flags: changes of flags alone are not seen", file=sys.stderr)

def flags_changed(entry):
    return bool(known) and fingerprint(entry, root, build_dir) not in known

picked = [e["file"] for e in entries if changed is None or depends_on_changed(e) or flags_changed(e)]
if since:
    print(f"tidy: {len(picked)} of {len(entries)} files depend on what changed since {since[:12]}",
          file=sys.stderr)
for f in picked:
    print(f)
PY
) || { echo "error: tidy.sh: could not list the files to check" >&2; exit 2; }
  files=()
  [[ -n "$picked" ]] && mapfile -t files <<<"$picked"
  if ((${#files[@]} == 0)) && ((!record)); then
    echo "tidy: nothing to check" >&2
    exit 0
  fi
fi

escaped=$(printf '%s' "$root" | sed 's/[][\.*^$+?(){}|]/\\&/g')
header_filter="^$escaped/(src|solvers)/"
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
start=$(date +%s)
# each file's diagnostics to its own log, so that parallel runs do not interleave lines
export clang_tidy build header_filter logs
printf '%s\n' "${files[@]}" |
  xargs -P "$jobs" -I{} bash -c '"$clang_tidy" -p "$build" --quiet --header-filter="$header_filter" \
    --warnings-as-errors="*" --extra-arg=-Wno-unknown-warning-option "$1" >"$(mktemp -p "$logs")" 2>&1' _ {} &&
  status=0 || status=$?
log="$logs/all"
cat "$logs"/tmp.* >"$log" 2>/dev/null || true
seconds=$(($(date +%s) - start))

# one line per distinct diagnostic (a header's warning is reported once per file that includes it)
mapfile -t found < <(grep -E '^/.*:[0-9]+:[0-9]+: (warning|error): .*\[[a-z0-9.,-]+\]$' "$log" |
                     sed 's/,-warnings-as-errors\]$/]/' | sort -u)
if ((${#found[@]} == 0 && status != 0)); then
  tail -20 "$log" >&2
  echo "tidy: clang-tidy failed (exit $status) without a diagnostic" >&2
  exit 2
fi
if ((${#found[@]} == 0)); then
  echo "tidy: ${#files[@]} files clean (${seconds} s)" >&2
  if ((record)); then
    { echo "# The last commit whose whole tree scripts/tidy.sh checked clean (--record, or --record-since a clean one),"
      echo "# then the fingerprints of the compile commands it was checked with (tidy.sh, fingerprint_py)."
      git rev-parse HEAD
      python3 - "$build/compile_commands.json" "$root" "$(realpath "$build")" <<'PY'
import json, os, sys
db, root, build_dir = sys.argv[1], sys.argv[2], sys.argv[3]
exec(os.environ["fingerprint_py"])
own_dirs = ("src/", "solvers/", "tests/", "experiments/benchmarks/")
for f in sorted({fingerprint(e, root, build_dir) for e in json.load(open(db))
                 if e["file"].endswith(".cpp") and any(e["file"].startswith(root + "/" + d) for d in own_dirs)}):
    print("flags", f)
PY
    } >.ci/tidy-base
    echo "tidy: recorded $(git rev-parse --short HEAD) in .ci/tidy-base" >&2
  fi
  exit 0
fi
printf '%s\n' "${found[@]}" | sed "s|^$root/||"
echo "tidy: ${#found[@]} warnings in ${#files[@]} files (${seconds} s), by check:" >&2
printf '%s\n' "${found[@]}" | sed -E 's/.*\[([^]]+)\]$/\1/' | sort | uniq -c | sort -rn >&2
exit 1
