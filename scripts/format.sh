#!/usr/bin/env bash
# clang-format (Debian's clang-format 14) with the repository's .clang-format on the project's own
# C++ sources: src/, solvers/, tests/, experiments/benchmarks/ (tracked files only; nothing vendored).
#   scripts/format.sh            format every such file in place
#   scripts/format.sh --check    change nothing; list the files that need formatting, exit 1 if any
#   scripts/format.sh [--check] FILE...   only these files
set -euo pipefail
cd "$(dirname "$0")/.."

check=0
if [[ "${1:-}" == "--check" ]]; then
  check=1
  shift
fi
clang_format=$(command -v clang-format-14 || command -v clang-format || true)
if [[ -z "$clang_format" ]]; then
  echo "error: clang-format not found (apt-get install clang-format)" >&2
  exit 2
fi

if (($#)); then
  files=("$@")
else
  # tracked and new (untracked, not ignored) files
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- \
                         'src/*' 'solvers/*' 'tests/*' 'experiments/benchmarks/*' | grep -E '\.(cpp|cc|h|hpp)$' |
                       while read -r f; do [[ -f "$f" ]] && echo "$f"; done)
fi

if ((check == 0)); then
  "$clang_format" -i --style=file "${files[@]}"
  exit 0
fi

needs=()
for f in "${files[@]}"; do
  if ! "$clang_format" --dry-run --Werror --style=file "$f" >/dev/null 2>&1; then needs+=("$f"); fi
done
if ((${#needs[@]})); then
  printf '%s\n' "${needs[@]}"
  echo "format: ${#needs[@]} of ${#files[@]} files need clang-format (run scripts/format.sh)" >&2
  exit 1
fi
echo "format: ${#files[@]} files clean" >&2
