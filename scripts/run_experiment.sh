#!/usr/bin/env bash
# Re-runs an experiment and rewrites its results and its README:
#   bash scripts/run_experiment.sh E01_farin_hansford | E02_degree_dependence [--dry-run]
#
# A title may be computed: `{headline}` in question.md's first line is replaced by the first bullet
# of the report's "## N. Headline" (degree-limit) or "## N. Conclusions" (study) section.
#
# The exact command is experiments/NAME/command: one line (or more, see below), the program and its arguments separated
# by spaces (no quoting, no shell syntax). It is run directly as an argument vector, never through
# a shell or `eval`, and it must write into experiments/NAME/results/ and nowhere else. The README
# is question.md (which shows the same command, checked here) followed by the sections of the fresh
# results/report.md that answer the question, and a line with the revision the run was made from
# (`git rev-parse HEAD`). The working tree must be clean outside experiments/NAME, so that this
# revision is what produced the numbers; COONS_ALLOW_DIRTY=1 runs anyway and says so in the README.
# --dry-run checks the experiment (command, question, output folder) and prints the command.
set -euo pipefail
cd "$(dirname "$0")/.."
name="${1:?usage: run_experiment.sh E01_farin_hansford|E02_degree_dependence [--dry-run]}"
dry_run="${2:-}"
dir="experiments/$name"
fail() { echo "error: $1" >&2; exit 2; }
[ -f "$dir/question.md" ] || fail "$dir/question.md: no such experiment"
[ -f "$dir/command" ] || fail "$dir/command: missing (the experiment's exact command, one line)"

# Each command as an argument vector: words separated by spaces, nothing a shell would interpret.
# The first line writes to $dir/results; a further line (a sub-study) writes to $dir/results/SUB,
# and its whole report.md is appended to the README after the first report's sections.
mapfile -t lines < <(grep -v '^[[:space:]]*\(#\|$\)' "$dir/command")
[ "${#lines[@]}" -ge 1 ] || fail "$dir/command: must hold at least one command line"
outs=()
for ((c = 0; c < ${#lines[@]}; ++c)); do
  line="${lines[c]}"
  case "$line" in
    *[\;\&\|\<\>\$\`\"\'\\\(\)\*\?\~]*) fail "$dir/command: only plain words are allowed (no quotes, globs or shell syntax)" ;;
  esac
  read -r -a argv <<< "$line"
  [ "${argv[0]}" = "./build/coons" ] || fail "$dir/command: must run ./build/coons, not ${argv[0]}"
  out=""
  for ((k = 1; k < ${#argv[@]}; ++k)); do
    if [ "${argv[k]}" = "--out" ] && [ $((k + 1)) -lt ${#argv[@]} ]; then out="${argv[k + 1]}"; fi
  done
  if [ $c -eq 0 ]; then
    [ "$out" = "$dir/results" ] || fail "$dir/command: must write to --out $dir/results (it writes to '${out:-nowhere}')"
  else
    case "$out" in
      "$dir"/results/[a-z]*) [[ "${out#"$dir"/results/}" =~ ^[a-z0-9_-]+$ ]] || fail "$dir/command: line $((c + 1)) must write to --out $dir/results/SUB" ;;
      *) fail "$dir/command: line $((c + 1)) must write to --out $dir/results/SUB (it writes to '${out:-nowhere}')" ;;
    esac
  fi
  outs+=("$out")
  grep -qxF "    $line" "$dir/question.md" || fail "$dir/question.md: does not show the command of $dir/command"
done

case "$name" in
  E01_*) sections='^## (1|3|5)\.' ;;
  E02_*) sections='^## (1|2|3|4)\.' ;;
  *) fail "$name: no sections chosen for its README (edit scripts/run_experiment.sh)" ;;
esac

if [ "$dry_run" = "--dry-run" ]; then
  for line in "${lines[@]}"; do printf 'would run: %s\n' "$line"; done
  exit 0
fi

revision=$(git rev-parse HEAD)
note=""
if [ -n "$(git status --porcelain --untracked-files=no -- . ":(exclude)$dir")" ]; then
  [ "${COONS_ALLOW_DIRTY:-}" = "1" ] || fail "the working tree has changes outside $dir: commit them first (or COONS_ALLOW_DIRTY=1)"
  note=" plus uncommitted changes"
fi

# COONS_NO_BUILD=1: use ./build as it is (the caller has just built it).
if [ "${COONS_NO_BUILD:-}" != "1" ]; then
  bash scripts/setup.sh
  bash scripts/build.sh >/dev/null
fi
for line in "${lines[@]}"; do
  read -r -a argv <<< "$line"
  "${argv[@]}" >/dev/null
done

# A question.md whose title holds {headline} gets the report's headline (the first bullet of its
# "## N. Headline" or "## N. Conclusions" section): a title computed from the data, never written by hand.
headline=$(awk '/^## [0-9]+\. (Headline|Conclusions)/{h = 1; next} /^## /{h = 0} h && /^- /{sub(/^- /, ""); sub(/\.$/, ""); print; exit}' \
  "$dir/results/report.md")
if grep -q '{headline}' "$dir/question.md" && [ -z "$headline" ]; then
  fail "$dir/results/report.md: no headline for the title of $dir/README.md"
fi
{
  awk -v h="$headline" '{gsub(/\{headline\}/, h); print}' "$dir/question.md"
  echo "**Result** ($(date -u +%Y-%m-%d), $(nproc) cores, made from revision \`$revision\`$note; the full report is [results/report.md](results/report.md)):"
  echo
  awk -v pat="$sections" '/^## /{keep = ($0 ~ pat)} keep' "$dir/results/report.md" | sed 's#(figures/#(results/figures/#g'
  for ((c = 1; c < ${#outs[@]}; ++c)); do
    sub="${outs[c]#"$dir"/results/}"
    echo
    sed "s#(figures/#(results/$sub/figures/#g" "${outs[c]}/report.md"
    echo
    echo "(Full report: [results/$sub/report.md](results/$sub/report.md).)"
  done
} > "$dir/README.md"
echo "wrote $dir/results/ and $dir/README.md (revision $revision$note)"
