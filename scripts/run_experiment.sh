#!/usr/bin/env bash
# Re-runs an experiment and rewrites its README from the run's report:
#   bash scripts/run_experiment.sh E01_farin_hansford | E02_degree_dependence
# The README is question.md (question and command) followed by the sections of the fresh
# results/report.md that answer it; every number there is computed by the run.
set -euo pipefail
cd "$(dirname "$0")/.."
name="${1:?usage: run_experiment.sh E01_farin_hansford|E02_degree_dependence}"
dir="experiments/$name"
[ -f "$dir/question.md" ] || { echo "error: $dir/question.md: no such experiment" >&2; exit 2; }
bash scripts/setup.sh
bash scripts/build.sh >/dev/null
command=$(grep -E '^    \./build/coons ' "$dir/question.md" | sed 's/^    //')
eval "$command" >/dev/null
case "$name" in
  E01_*) sections='^## (1|3)\.' ;;
  E02_*) sections='^## 2\.' ;;
esac
{
  cat "$dir/question.md"
  echo "**Result** ($(date -u +%Y-%m-%d), $(nproc) cores; the full report is [results/report.md](results/report.md)):"
  echo
  awk -v pat="$sections" '/^## /{keep = ($0 ~ pat)} keep' "$dir/results/report.md" | sed 's#(figures/#(results/figures/#g'
} > "$dir/README.md"
echo "wrote $dir/README.md"
