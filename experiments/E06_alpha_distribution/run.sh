#!/usr/bin/env bash
# E06: α* and μ* over 1,000 random smooth boundaries, run as 8 shards through GNU parallel
# (scripts/study-parallel.sh, 2 at a time) and merged; rewrites results/ (report.md, results.json,
# figures/), results/timing.md (wall time, CPU time per boundary, peak memory per shard, from
# /usr/bin/time -v and the shards' per-task seconds) and this experiment's README.md.
# usage: bash experiments/E06_alpha_distribution/run.sh [--resume]
#   --resume keeps out/e06-shards (a killed run goes on where it stopped; the timing then covers
#   only the last run's shards).
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=experiments/E06_alpha_distribution
shards=out/e06-shards
study=(--family random-smooth --count 1000 --seed 1 --degrees 3 5 8 12 20 32)
[ "${1:-}" = "--resume" ] || rm -rf "$shards"
mkdir -p "$shards"
rm -rf "$dir/results"
start=$(date +%s.%N)
scripts/study-parallel.sh -n 8 -j 2 --time --shards-dir "$shards" --out "$dir/results" -- "${study[@]}" \
  > "$shards/merge.log"
end=$(date +%s.%N)
python3 "$dir/summarize.py" "$shards" "$dir" "$start" "$end" "${study[*]}"
echo "wrote $dir/README.md, $dir/results/"
