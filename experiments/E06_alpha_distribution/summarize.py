#!/usr/bin/env python3
"""E06: results/timing.md and README.md from the shards' files (called by run.sh, which measures
the wall time): usage summarize.py SHARDS_DIR EXPERIMENT_DIR START END STUDY_OPTIONS."""
import glob, json, os, re, sys
from collections import defaultdict

shards, out, start, end, study = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), sys.argv[5]
rows = []
for path in sorted(glob.glob(os.path.join(shards, "time-*-of-*.txt"))):
    text = open(path).read()
    def field(name):
        return re.search(re.escape(name) + r":\s*(\S+)", text).group(1)
    rows.append((os.path.basename(path), float(field("User time (seconds)")) + float(field("System time (seconds)")),
                 field("Elapsed (wall clock) time (h:mm:ss or m:ss)"), int(field("Maximum resident set size (kbytes)"))))
task = defaultdict(float)
count = set()
for path in glob.glob(os.path.join(shards, "shard-*-of-*.jsonl")):
    for line in open(path):
        r = json.loads(line)
        task[(r["objective"], r["degree"])] += r["seconds"]
        count.add(r["index"])
n = len(count)
wall = end - start
cpu = sum(r[1] for r in rows)
md = ["# E06 timing (computed by run.sh)", "",
      f"`coons study {study}` as {len(rows)} shards, 2 at a time (GNU parallel), then `--merge`, on this machine "
      f"(2 cores shared with other jobs: wall times are upper bounds).", "",
      f"- wall time, shards and merge: {wall:.1f} s for {n} boundaries ({wall / n * 1000:.1f} ms per boundary)",
      f"- CPU time of the shard processes (user + system): {cpu:.1f} s ({cpu / n * 1000:.1f} ms per boundary, all degrees and objectives)",
      f"- peak resident memory of a shard: {max(r[3] for r in rows) / 1024:.1f} MiB (largest of {len(rows)})", "",
      "| shard | CPU s | wall | peak RSS (MiB) |", "|---|---|---|---|"]
md += [f"| {name} | {c:.1f} | {w} | {kb / 1024:.1f} |" for name, c, w, kb in rows]
tasks = sum(task.values())
md += ["", f"Task time per boundary (the shards' `seconds`: the wall-clock time of one boundary's search and "
       f"grid; with the machine shared, their sum is {tasks / cpu:.2g}× the shards' CPU time):", "",
       "| objective | degree | wall ms per boundary | ≈ CPU ms per boundary (wall scaled by the ratio) |",
       "|---|---|---|---|"]
md += [f"| {o} | {d} | {s / n * 1000:.2f} | {s / n * 1000 * cpu / tasks:.2f} |"
       for (o, d), s in sorted(task.items(), key=lambda x: (x[0][0], x[0][1]))]
open(os.path.join(out, "results", "timing.md"), "w").write("\n".join(md) + "\n")

report = open(os.path.join(out, "results", "report.md")).read()
report = re.sub(r"\]\(figures/", "](results/figures/", report)
report = re.sub(r"^## ", "### ", report, flags=re.M)
report = re.sub(r"^### (thin_plate|e3)$", r"#### \1", report, flags=re.M)
head = open(os.path.join(out, "question.md")).read()
timing = "\n".join(md[2:]).replace("# E06 timing", "")
open(os.path.join(out, "README.md"), "w").write(
    head + "\n## Cost (measured)\n\n" + timing + "\n\n## Results (computed by the run)\n\n" + report)
