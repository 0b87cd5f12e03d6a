#!/usr/bin/env bash
# Every test case of coons_tests that CTest should run is registered under its own name.
#   check_test_registration.sh COONS_TESTS BUILD_DIR [TEST_SPEC]
# catch_discover_tests turns the listed names into a CMake list: a ';' cuts a name, and an
# unbalanced '[' or ']' keeps the ';' after it from separating, so that several names become one
# test that matches nothing and passes having run nothing (15 names with ';' until 2026-11-25,
# then 123 tests behind the ']' of "(c*_n, 1/3]"). No name may hold ';' or '"' (balanced brackets,
# as in "[0, 1]", survive), and every listed name must be a CTest test.
set -euo pipefail
tests=$1 build=$2 spec=${3:-}
listed=$(mktemp) registered=$(mktemp)
trap 'rm -f "$listed" "$registered"' EXIT
# (Catch2 v2 exits with the number of tests listed, so the status says nothing: the count does)
{ "$tests" --list-test-names-only ${spec:+"$spec"} || true; } | sed '/^$/d' | sort >"$listed"
if [[ ! -s $listed ]]; then
  echo "$tests listed no test names" >&2
  exit 1
fi
ctest --test-dir "$build" -N | sed -n 's/^ *Test *#[0-9]*: //p' | sort >"$registered"
status=0
if grep -n '[;"]' "$listed"; then
  echo "test names above hold ';' or '\"', which CTest registration mangles" >&2
  status=1
fi
missing=$(comm -23 "$listed" "$registered")
if [[ -n $missing ]]; then
  echo "$(wc -l <<<"$missing") test cases are not registered with CTest under their names:" >&2
  echo "$missing" | head -20 >&2
  status=1
fi
echo "$(wc -l <"$listed") test names listed, all registered: $([[ $status == 0 ]] && echo yes || echo no)"
exit $status
