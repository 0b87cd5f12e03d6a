#!/usr/bin/env bash
# Runs the solver benchmark suite and writes a Markdown table, log-log plots and scaling exponents.
#   bash scripts/bench.sh [--quick] [--no-build] [--report-only] [--out DIR] [bench_solvers flags...]
# --quick: tiny sizes (CI runs this so the benchmarks never rot). Default output folder:
# experiments/E03_solver_scaling/results (or build/bench-quick with --quick).
# --report-only: no build and no run; the tables, README and conclusions are made again from the
# committed DIR/bench.json (the plots are kept as they are).
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0; build=1; run=1; out=""; extra=()
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --no-build) build=0 ;;
    --report-only) build=0; run=0 ;;
    --out) out="$2"; shift ;;
    *) extra+=("$1") ;;
  esac
  shift
done
if [ $build -eq 1 ]; then bash scripts/setup.sh; bash scripts/build.sh >/dev/null; fi
if [ -z "$out" ]; then
  if [ $quick -eq 1 ]; then out=build/bench-quick; else out=experiments/E03_solver_scaling/results; fi
fi
mkdir -p "$out"
args=(--benchmark_format=console --benchmark_out="$out/bench.json" --benchmark_out_format=json)
[ $quick -eq 1 ] && args+=(--quick)
if [ $run -eq 1 ]; then
  "${COONS_BUILD_DIR:-build}/bench_solvers" "${args[@]}" ${extra[@]+"${extra[@]}"} > "$out/bench.log"
  python3 scripts/bench_report.py "$out/bench.json" "$out"
else
  COONS_NO_PLOTS=1 python3 scripts/bench_report.py "$out/bench.json" "$out" > /dev/null
fi
# The default (full) run rewrites E03's README: its question, then this run's computed tables.
if [ "$out" = experiments/E03_solver_scaling/results ]; then
  readme=experiments/E03_solver_scaling/README.md
  if [ $run -eq 1 ]; then
    result="**Result** ($(date -u +%Y-%m-%d), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')):"
  else
    result="$(grep -m1 '^\*\*Result\*\*' "$readme")"
  fi
  {
    cat experiments/E03_solver_scaling/question.md
    echo "$result"
    echo
    sed 's/^# /### /; s/^## /### /' "$out/table.md"
    echo
    for png in "$out"/scaling_alpha*.png; do echo "![$(basename "$png")](results/$(basename "$png"))"; echo; done
  } > "$readme.new"
  mv "$readme.new" "$readme"
  # the conclusions, computed from the tables just written (and checked by ctest: e03_conclusions_*)
  python3 scripts/bench_conclusions.py --write "$readme"
  echo "wrote $readme"
  # docs/solvers.md's summary of the run (every backend at its largest N), between its markers
  python3 - "$out/summary.md" docs/solvers.md <<'PY'
import sys
summary, docs = open(sys.argv[1]).read(), open(sys.argv[2]).read()
begin, end = "<!-- e03-summary:begin -->", "<!-- e03-summary:end -->"
a, b = docs.index(begin) + len(begin), docs.index(end)
open(sys.argv[2], "w").write(docs[:a] + "\n" + summary + docs[b:])
PY
  echo "wrote docs/solvers.md (E03 summary)"
fi
