#!/usr/bin/env bash
# A sharded study (a family, or boundary files) on one machine: runs `coons study … --shard I/N` for I = 0 … N−1 through
# GNU parallel (Debian package `parallel`), JOBS at a time, then `coons study --merge` into the
# report folder. A rerun resumes: every shard skips the tasks already in its file.
#
# usage: scripts/study-parallel.sh [-n SHARDS] [-j JOBS] [--shards-dir DIR] [--time] --out REPORT_DIR \
#          -- STUDY_OPTIONS...
#   -n SHARDS        how many shards (default: 4 × JOBS)
#   -j JOBS          shards at once (default: the number of CPUs)
#   --shards-dir DIR where the shard files go (default: REPORT_DIR/shards)
#   --time           run each shard under /usr/bin/time -v (DIR/time-I-of-N.txt: peak memory, CPU seconds)
#   STUDY_OPTIONS    the inputs and options of `coons study` (--family … or boundary files; not --shard,
#                    not --out)
# Environment: COONS (the binary, default build/coons).
# e.g. scripts/study-parallel.sh -n 6 -j 2 --out out/family -- --family random-smooth --count 1000 --degrees 8
#      scripts/study-parallel.sh -n 4 -j 2 --out out/study -- data/boundaries/*.json --degrees 3 4 6 8
set -euo pipefail

fail() { echo "error: study-parallel: $*" >&2; exit 2; }
coons=${COONS:-build/coons}
jobs=$(nproc)
shards=""
shards_dir=""
out=""
timed=0
while [ $# -gt 0 ]; do
  case "$1" in
    -n) shards=${2:?}; shift 2 ;;
    -j) jobs=${2:?}; shift 2 ;;
    --shards-dir) shards_dir=${2:?}; shift 2 ;;
    --out) out=${2:?}; shift 2 ;;
    --time) timed=1; shift ;;
    --) shift; break ;;
    *) fail "unknown option '$1' (see the usage at the top of $0)" ;;
  esac
done
[ -n "$out" ] || fail "--out REPORT_DIR is required"
[ $# -gt 0 ] || fail "no study options after -- (e.g. -- --family random-smooth --count 1000)"
command -v parallel >/dev/null || fail "GNU parallel is not installed (apt-get install parallel)"
[ -x "$coons" ] || fail "$coons is not an executable (build it, or set COONS)"
[[ "$jobs" =~ ^[1-9][0-9]*$ ]] || fail "-j: '$jobs' is not a positive whole number"
shards=${shards:-$((4 * jobs))}
[[ "$shards" =~ ^[1-9][0-9]*$ ]] || fail "-n: '$shards' is not a positive whole number"
shards_dir=${shards_dir:-$out/shards}
mkdir -p "$shards_dir"

prefix=()
if [ "$timed" = 1 ]; then
  [ -x /usr/bin/time ] || fail "--time needs /usr/bin/time (apt-get install time)"
  prefix=(/usr/bin/time -v -o "$shards_dir/time-{}-of-$shards.txt")
fi
# -q: every argument is passed as it is (no shell word splitting); {} is the shard index.
seq 0 $((shards - 1)) | parallel --will-cite -q -j "$jobs" --halt now,fail=1 \
  ${prefix[@]+"${prefix[@]}"} "$coons" study "$@" --shard "{}/$shards" --out "$shards_dir"
"$coons" study --merge "$shards_dir" --out "$out"
