#!/usr/bin/env bash
# Fuzzing (issue 10): builds the libFuzzer targets of tests/fuzz with clang++
# (-fsanitize=fuzzer,address,undefined; -DCOONS_FUZZ=ON) in ./build-fuzz, then runs each for
# COONS_FUZZ_SECONDS seconds (default 20) from a seed corpus made of data/ and the saved
# regression inputs. Prints one line per target with its executions; a finding (crash, sanitizer
# report, escaping exception, timeout) is saved under build-fuzz/findings/<target>/ and makes the
# script fail: copy it to tests/fuzz/regressions/<target>/ with the fix.
# Usage: scripts/fuzz.sh [target ...]   (default: all six)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${COONS_FUZZ_SECONDS:-20}
build=build-fuzz
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_boundary_reader fuzz_surface_reader fuzz_matrix_market fuzz_tri_boundary_reader
                                      fuzz_stencil_problem fuzz_study_shard)

command -v clang++ >/dev/null || { echo "error: fuzz: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }
mkdir -p "$build"
cmake -S . -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCOONS_FUZZ=ON -DCOONS_BUILD_TESTS=OFF -DCOONS_WITH_OCCT=OFF \
      -DCOONS_BUILD_BENCHMARKS=OFF >"$build/configure.log" 2>&1 || { cat "$build/configure.log" >&2; exit 1; }
cmake --build "$build" -j"$(nproc)" --target "${targets[@]}"

# Seeds: the data files of each reader, its regression inputs, two tiny Matrix Market files.
seed_dir() {
  case "$1" in
    fuzz_boundary_reader) echo data/boundaries ;;
    fuzz_surface_reader) echo data/surfaces ;;
    fuzz_tri_boundary_reader) echo data/triangles ;;
    fuzz_stencil_problem) echo data/boundaries ;;
    *) echo "" ;;
  esac
}
dict_of() { [ "$1" = fuzz_matrix_market ] && echo tests/fuzz/matrix_market.dict || echo tests/fuzz/json.dict; }

failed=0
for t in "${targets[@]}"; do
  corpus=$build/corpus/$t
  findings=$build/findings/$t
  rm -rf "$corpus" "$findings"
  mkdir -p "$corpus" "$findings"
  seeds=$(seed_dir "$t")
  [ -n "$seeds" ] && cp "$seeds"/*.json "$corpus"/
  [ -d "tests/fuzz/regressions/$t" ] && cp "tests/fuzz/regressions/$t"/* "$corpus"/ 2>/dev/null || true
  if [ "$t" = fuzz_matrix_market ]; then
    printf '%%%%MatrixMarket matrix coordinate real general\n3 3 4\n1 1 4\n2 2 4\n3 3 4\n1 3 -1\n' >"$corpus/seed_sparse.mtx"
    printf '%%%%MatrixMarket matrix array real general\n% a comment\n3 2\n1\n2\n3\n4\n5\n6.5e-3\n' >"$corpus/seed_dense.mtx"
    printf '%%%%MatrixMarket matrix coordinate real symmetric\n3 3 4\n1 1 4\n2 1 -1\n2 2 4\n3 3 4\n' >"$corpus/seed_symmetric.mtx"
  fi
  # a shard record of a boundary-file study is about 30 kB
  max_len=16384
  [ "$t" = fuzz_study_shard ] && max_len=65536
  log=$build/$t.log
  status=0
  # -timeout: one input taking 10 s is a finding; -rss_limit_mb: so is using 2 GB.
  "$build/fuzz/$t" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" \
      -dict="$(dict_of "$t")" -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1 || status=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  found=$(find "$findings" -type f | wc -l)
  echo "fuzz: $t: $runs executions in ${seconds} s, $found findings (exit $status)"
  if [ "$status" -ne 0 ] || [ "$found" -ne 0 ]; then
    failed=1
    grep -E "ERROR|SUMMARY|runtime error|terminate|deadly" "$log" | head -5 >&2 || true
    ls "$findings" >&2
  fi
done
exit $failed
