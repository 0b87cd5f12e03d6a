#!/usr/bin/env bash
# The sharded family study through its two drivers, at a tiny size, against one unsharded run:
#   parallel: scripts/study-parallel.sh runs 3 shards through GNU parallel and merges; results.json
#             and report.md must equal the unsharded run's (prints "skipped" without `parallel`).
#   slurm:    scripts/slurm/study.sbatch's shard and merge modes as a 3-task array would run them,
#             and its submit mode against a stand-in sbatch (the array and the afterok merge job).
# usage: study_parallel_check.sh parallel|slurm COONS SOURCE_DIR
set -euo pipefail
mode=$1 coons=$2 src=$3
fail() { echo "FAIL: $*" >&2; exit 1; }
if [ "$mode" = parallel ] && ! command -v parallel >/dev/null; then
  echo "skipped: GNU parallel not installed (apt-get install parallel)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
args=(--family random-smooth --count 5 --seed 7 --degrees 3 5)
"$coons" study "${args[@]}" --out "$tmp/whole" >/dev/null
case "$mode" in
  parallel)
    COONS=$coons "$src/scripts/study-parallel.sh" -n 3 -j 2 --out "$tmp/sharded" -- "${args[@]}" >/dev/null
    ;;
  slurm)
    for i in 0 1 2; do
      SLURM_ARRAY_TASK_ID=$i COONS=$coons \
        "$src/scripts/slurm/study.sbatch" shard 3 "$tmp/sharded" -- "${args[@]}" >/dev/null
    done
    COONS=$coons "$src/scripts/slurm/study.sbatch" merge "$tmp/sharded" >/dev/null
    printf '#!/bin/sh\necho "$@" >> %s/sbatch.log\necho 4242\n' "$tmp" > "$tmp/sbatch"
    chmod +x "$tmp/sbatch"
    SBATCH=$tmp/sbatch COONS=$coons "$src/scripts/slurm/study.sbatch" submit 3 "$tmp/sub" -- "${args[@]}" >/dev/null
    grep -q -- "--array=0-2 .*study.sbatch shard 3 $tmp/sub -- ${args[*]}" "$tmp/sbatch.log" || fail "array: $(cat "$tmp/sbatch.log")"
    grep -q -- "--dependency=afterok:4242 .*study.sbatch merge $tmp/sub" "$tmp/sbatch.log" || fail "merge: $(cat "$tmp/sbatch.log")"
    ;;
  *) fail "unknown mode $mode" ;;
esac
[ "$(cat "$tmp"/sharded/shards/shard-*-of-3.jsonl | wc -l)" = 20 ] || fail "the shards do not hold 20 tasks"
cmp "$tmp/whole/results.json" "$tmp/sharded/results.json" || fail "results.json differs from the unsharded run"
cmp "$tmp/whole/report.md" "$tmp/sharded/report.md" || fail "report.md differs from the unsharded run"
echo "ok: $mode: 3 shards merged equal the unsharded run"
