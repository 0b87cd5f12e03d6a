#!/usr/bin/env bash
# Experiment E04 (hard systems) in one run: every backend on the 5×5 problems and free sets, each up
# to its size cap (hard_size_cap in experiments/benchmarks/bench_solvers.cpp), then the README with
# its tables and computed conclusions. About 20 minutes on 2 cores.
#   bash scripts/e04.sh [--report-only]
# --report-only: no run; the README is made again from the committed results/bench.json.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=experiments/E04_hard_systems
bench="${COONS_BUILD_DIR:-build}/bench_solvers"
if [ "${1:-}" != "--report-only" ]; then
  [ -x "$bench" ] || { echo "error: $bench: not built (bash scripts/build.sh)" >&2; exit 2; }
  "$bench" --hard --benchmark_filter='MemoryPass|Hard' --benchmark_format=console \
    --benchmark_out="$dir/results/bench.json.tmp" --benchmark_out_format=json
  mv "$dir/results/bench.json.tmp" "$dir/results/bench.json"
  rm -f "$dir/results/bench1023.json"  # the second part of the committed two-run result
fi
parts=("$dir/results/bench.json")
[ -f "$dir/results/bench1023.json" ] && parts+=("$dir/results/bench1023.json")
python3 scripts/e04_report.py "${parts[@]}" "$dir"
