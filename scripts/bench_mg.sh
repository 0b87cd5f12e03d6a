#!/usr/bin/env bash
# Multigrid iteration counts (mg, mg-cg, hypre-smg, hypre-pfmg at 1e-10, N = 127..1023) and the
# 1- and 2-thread solves at N = 1023 of fast, dst and mg (α = 0, −0.1), of the 5×5 set (fast5,
# separable-banded), the 101-value α sweep of fast, fast and dst at N = 1000, 1024, 1030 (slow FFT
# lengths) and one end-to-end `coons solve` of a 1001×1001 net: every speed target of issues 11 and 14 in one run, with its verdict; rewrites the computed block of
# docs/solvers.md. About 10 minutes on the 2-core machine under load.
#   bash scripts/bench_mg.sh [--report-only]
set -euo pipefail
cd "$(dirname "$0")/.."
out=experiments/E03_solver_scaling/results
bench="${COONS_BUILD_DIR:-build}/bench_solvers"
# Medians of 5 repetitions (the memory pass too): on the shared machine a solve now and then takes
# several times its usual time, and one such in a repetition's mean moved a ratio by 20 %.
repeat=(--benchmark_repetitions=5 --benchmark_report_aggregates_only=true)
if [ "${1:-}" != "--report-only" ]; then
  rm -f "$out"/mg_iterations_*.json  # parts of earlier split runs (merged by --report-only)
  "$bench" --mg-iterations --sizes=127,255,511,1023 --benchmark_format=console \
    --benchmark_out="$out/mg_iterations.json" --benchmark_out_format=json
  "$bench" --large --sizes=1023 --alphas=0,-0.1 --backends=fast,dst,mg,fast5,separable-banded \
    --benchmark_filter='MemoryPass|BM_SineRows/|BM_Fast5Sweep/|BM_Solve/|BM_AlphaSweep(Threads)?/fast/|BM_Stencil5/(c1-coons|biharmonic|c1-family-0.5)/' \
    "${repeat[@]}" --benchmark_format=console --benchmark_out="$out/threads.json" --benchmark_out_format=json
  "$bench" --large --sizes=1000,1023,1024,1030 --backends=fast,dst \
    --benchmark_filter='MemoryPass|BM_Solve/(fast|dst)/N:[0-9]+/alpha:-0.100/min_time' \
    "${repeat[@]}" --benchmark_format=console --benchmark_out="$out/sizes.json" --benchmark_out_format=json
  for threads in 1 2; do
    python3 experiments/benchmarks/bench_solve_e2e.py --coons "${COONS_BUILD_DIR:-build}/coons" --threads $threads \
      --json "$out/solve_e2e_threads$threads.json"
  done
fi
shopt -s nullglob
e2e=("$out"/solve_e2e_threads*.json)  # none in a --report-only run before the first full one
python3 scripts/mg_report.py --iterations "$out"/mg_iterations*.json --threads "$out/threads.json" \
  ${e2e[@]:+--e2e "${e2e[@]}"} $([ -f "$out/sizes.json" ] && echo --sizes "$out/sizes.json") --docs docs/solvers.md
