#!/usr/bin/env python3
"""Experiment E04's README from bench_solvers' BM_Hard JSON: tables and computed conclusions.

Usage: e04_report.py BENCH.json [MORE.json ...] EXPERIMENT_DIR
           writes EXPERIMENT_DIR/README.md: question.md, then the tables and the conclusions of
           these runs (a later file's entry replaces an earlier one's for the same problem,
           backend and N; each file's memory pass scales its own entries);
       e04_report.py --check README.md
           re-reads the README's tables and fails (exit 1, one line per contradiction) when a
           conclusion contradicts them;
       e04_report.py --self-test
           checks that --check catches a contradicting conclusion. Standard library only.
"""
import json
import os
import re
import sys
from collections import defaultdict


def seconds(b):
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return b["real_time"] * unit


def status_of(b):
    label = b.get("label", "")
    return label.split("status=")[-1] if "status=" in label else ("success" if b.get("ok", 1) else "failure")


def load(paths):
    """(problem, backend) -> N -> (ratio to the memory pass, bench entry); dates and CPU counts."""
    hard, dates = defaultdict(dict), []
    for path in paths:
        doc = json.load(open(path))
        dates.append((doc["context"].get("date", "")[:10], doc["context"].get("num_cpus", "?")))
        memory = {}
        for b in doc["benchmarks"]:
            if b.get("run_type", "iteration") == "iteration" and b["name"].startswith("BM_MemoryPass/"):
                memory[int(b.get("N", 0))] = seconds(b)
        for b in doc["benchmarks"]:
            if b.get("run_type", "iteration") != "iteration":
                continue
            m = re.match(r"BM_Hard/([^/]+)/([^/]+)/N:", b["name"])
            n = int(b.get("N", 0))
            if m and n in memory:
                hard[(m.group(1), m.group(2))][n] = (seconds(b) / memory[n], b)
    return hard, dates


def cell(ratio, b):
    st = status_of(b)
    if st != "success":
        return f"✗ {st}"
    it = int(b.get("iterations", 1))
    return f"{ratio:.1f}×" + (f", {it} it" if it > 1 else "") + f", res {b.get('residual', 0):.0e}"


def conclusions(problems, sizes, table):
    """table: problem -> backend -> N -> cell text. The conclusions, computed from the cells only."""
    lines = []
    for problem in problems:
        parts = []
        for n in sizes:
            done = sorted((ratio_of(c), backend) for backend, per_n in table[problem].items()
                          if (c := per_n.get(n)) and ratio_of(c) is not None)
            if not done:
                continue
            (best, backend), others = done[0], done[1:]
            runner = f"; next `{others[0][1]}` {others[0][0] / best:.1f}× slower" if others else ""
            parts.append(f"N = {n}: `{backend}` ({best:.1f}× mem{runner})")
        if parts:
            lines.append(f"- **{problem}** — fastest: " + "; ".join(parts) + ".")
    declined, stopped = defaultdict(list), defaultdict(list)
    for problem in problems:
        for backend, per_n in table[problem].items():
            if any(c == "✗ not_applicable" for c in per_n.values()):
                declined[backend].append(problem)
            bad = [str(n) for n, c in sorted(per_n.items()) if c.startswith("✗") and c != "✗ not_applicable"]
            if bad:
                stopped[backend].append(f"{problem} (N = {', '.join(bad)})")
    for backend, ps in sorted(declined.items()):
        lines.append(f"- `{backend}` declined (not_applicable): {', '.join(ps)}.")
    for backend, ps in sorted(stopped.items()):
        lines.append(f"- `{backend}` did not finish (status in the table): {'; '.join(ps)}.")
    return lines


def ratio_of(text):
    m = re.match(r"([0-9.]+)×", text)
    return float(m.group(1)) if m else None


def render(hard, dates, question):
    sizes = sorted({n for per_n in hard.values() for n in per_n})
    problems = list(dict.fromkeys(p for p, _ in hard))
    table = defaultdict(dict)
    for (p, backend), per_n in hard.items():
        table[p][backend] = {n: cell(r, b) for n, (r, b) in per_n.items()}
    runs = "; ".join(f"{d}, {c} CPUs" for d, c in dates)
    lines = [f"**Result** ({runs}; wall-clock time of one fresh solve as a multiple of the memory pass at "
             "the same N; `it` iterations; ✗ the status when not `success`; – not run):", ""]
    for problem in problems:
        lines += [f"### {problem}", "", "| backend | " + " | ".join(f"N={n}" for n in sizes) + " |",
                  "|" + "---|" * (len(sizes) + 1)]
        for backend, per_n in table[problem].items():
            lines.append(f"| {backend} | " + " | ".join(per_n.get(n, "–") for n in sizes) + " |")
        lines.append("")
    lines += ["## Conclusions (computed from the tables above)", ""]
    lines += conclusions(problems, sizes, table)
    return question + "\n".join(lines) + "\n"


def parse_tables(text):
    """The README's tables back: problems in order, sizes, problem -> backend -> N -> cell."""
    problems, sizes, table, current = [], [], defaultdict(dict), None
    for line in text.splitlines():
        if line.startswith("### "):
            current = line[4:].strip()
            problems.append(current)
        elif current and line.startswith("| backend |"):
            sizes = [int(c.strip()[2:]) for c in line.strip("|").split("|")[1:]]
        elif current and line.startswith("| ") and not line.startswith("|---"):
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            table[current][cells[0]] = {n: c for n, c in zip(sizes, cells[1:]) if c != "–"}
        elif line.startswith("## "):
            current = None
    return problems, sizes, table


def check(text):
    """The contradictions between the README's conclusions and its tables (empty when none)."""
    problems, sizes, table = parse_tables(text)
    written = text.split("## Conclusions (computed from the tables above)", 1)
    if len(written) != 2 or not problems:
        return ["no tables or no conclusions section"]
    stated = [l for l in written[1].splitlines() if l.startswith("- ")]
    expected = conclusions(problems, sizes, table)
    errors = [f"not supported by the tables: {l}" for l in stated if l not in expected]
    errors += [f"missing: {l}" for l in expected if l not in stated]
    return errors


def self_test():
    def entry(p, backend, n, t, label="success"):
        return {"name": f"BM_Hard/{p}/{backend}/N:{n}/real_time", "N": n, "real_time": t, "time_unit": "s",
                "label": f"{backend} status={label}", "iterations": 1, "residual": 1e-14}
    doc = {"context": {"date": "2026-11-22", "num_cpus": 2}, "benchmarks": [
        {"name": "BM_MemoryPass/N:8", "N": 8, "real_time": 1.0, "time_unit": "s"},
        entry("p", "fast", 8, 2.0), entry("p", "slow", 8, 6.0), entry("p", "never", 8, 9.0, "not_applicable")]}
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
        json.dump(doc, f)
    hard, dates = load([f.name])
    os.unlink(f.name)
    good = render(hard, dates, "")
    # explicit checks, not assert: `python3 -O` would drop those and pass
    failures = []
    if "`fast` (2.0× mem; next `slow` 3.0× slower)" not in good:
        failures.append("the winner line is missing from:\n" + good)
    if check(good):
        failures.append("a correct report is refused: " + "; ".join(check(good)))
    for wrong in [good.replace("`fast` (2.0×", "`slow` (2.0×"), good.replace("3.0× slower", "1.5× slower"),
                  good.replace("- `never` declined (not_applicable): p.\n", ""),
                  good + "- `fast` did not finish (status in the table): p (N = 8).\n"]:
        if wrong == good or not check(wrong):
            failures.append("a contradicting report is accepted:\n" + wrong)
    for f in failures:
        print(f"e04_report self-test: {f}", file=sys.stderr)
    if failures:
        return 1
    print("e04_report self-test: ok")
    return 0


def main():
    if sys.argv[1:2] == ["--self-test"]:
        return self_test()
    if sys.argv[1:2] == ["--check"]:
        errors = check(open(sys.argv[2]).read())
        for e in errors:
            print(f"error: {sys.argv[2]}: conclusions: {e}", file=sys.stderr)
        return 1 if errors else 0
    *paths, folder = sys.argv[1:]
    hard, dates = load(paths)
    text = render(hard, dates, open(os.path.join(folder, "question.md")).read())
    with open(os.path.join(folder, "README.md"), "w") as out:
        out.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
