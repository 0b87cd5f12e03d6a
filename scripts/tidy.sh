#!/usr/bin/env bash
# clang-tidy (Debian's clang-tidy 14) with the repository's .clang-tidy on the project's own .cpp files
# (src/, solvers/, tests/, experiments/benchmarks/), through the build's compile_commands.json, two at a
# time. Warnings are errors; in headers only the project's own (src/, solvers/) are checked, never
# Eigen, Ceres or Catch2. Prints each warning once and a count per check; exit 1 on any warning.
#   scripts/tidy.sh              every .cpp file in the compile database
#   scripts/tidy.sh FILE...      only these files
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

if (($#)); then
  files=()
  for f in "$@"; do files+=("$(realpath "$f")"); done
else
  mapfile -t files < <(python3 - "$build/compile_commands.json" "$root" <<'PY'
import json, sys
root = sys.argv[2] + "/"
seen = set()
for entry in json.load(open(sys.argv[1])):
    f = entry["file"]
    own = any(f.startswith(root + d) for d in ("src/", "solvers/", "tests/", "experiments/benchmarks/"))
    if own and f.endswith(".cpp") and f not in seen:
        seen.add(f)
        print(f)
PY
)
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
  exit 0
fi
printf '%s\n' "${found[@]}" | sed "s|^$root/||"
echo "tidy: ${#found[@]} warnings in ${#files[@]} files (${seconds} s), by check:" >&2
printf '%s\n' "${found[@]}" | sed -E 's/.*\[([^]]+)\]$/\1/' | sort | uniq -c | sort -rn >&2
exit 1
