#!/usr/bin/env python3
"""E05 — Farin–Hansford's triangles: the best member c of the triangular mask family per shape,
objective and degree. Regenerates results/results.json, results/report.md and README.md:

    python3 experiments/E05_triangles/run.py [--coons ./build/coons]

For each bundled triangle (data/triangles/*.json) and each degree of DEGREES at or above the
file's own, the sides are degree-elevated exactly (a Bézier curve elevated; the triangle's
boundary is the same curves), written to a temporary file, and `coons search-alpha --objective X`
is run for X in OBJECTIVES (and `target` when the file has one). Python 3 standard library only."""
import argparse
import datetime
import json
import pathlib
import subprocess
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
DEGREES = [6, 8, 12, 16]
OBJECTIVES = ["thin_plate", "dirichlet", "twist", "discrete_thin_plate"]


def elevate(points, times):
    for _ in range(times):
        n = len(points) - 1
        new = [points[0]]
        for i in range(1, n + 1):
            a = i / (n + 1)
            new.append([a * points[i - 1][c] + (1 - a) * points[i][c] for c in range(3)])
        new.append(points[n])
        points = new
    return points


def search(coons, path, objective):
    r = subprocess.run([coons, "search-alpha", str(path), "--objective", objective], capture_output=True, text=True)
    if r.returncode not in (0, 3):
        raise SystemExit(f"{path} {objective}: exit {r.returncode}: {r.stderr.strip()}")
    return json.loads(r.stdout)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coons", default=str(ROOT / "build" / "coons"))
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for file in sorted((ROOT / "data" / "triangles").glob("*.json")):
            doc = json.loads(file.read_text())
            n0 = len(doc["sides"][0]) - 1
            objectives = OBJECTIVES + (["target"] if "target" in doc else [])
            for n in [d for d in DEGREES if d >= n0]:
                elevated = dict(doc, degree=n, sides=[elevate(s, n - n0) for s in doc["sides"]])
                path = pathlib.Path(tmp) / f"{doc['name']}-{n}.json"
                path.write_text(json.dumps(elevated))
                for objective in objectives:
                    report = search(args.coons, path, objective)
                    rows.append({"boundary": doc["name"], "degree": n, "objective": objective,
                                 "c": report["alpha"], "value": report["value"], "bounds": report["bounds"],
                                 "flat": report["flat"], "at_bound": report["at_bound"],
                                 "status": report["status"], "evaluations": report["evaluations"]})
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    (out / "results.json").write_text(json.dumps(rows, indent=1) + "\n")

    def fmt(row):
        if row["c"] is None:
            return row["status"]
        mark = " (bound)" if row["at_bound"] else ""
        return f"{row['c']:.5f}{mark}"

    lines = ["## Results", "",
             f"Computed {datetime.date.today().isoformat()} by `python3 experiments/E05_triangles/run.py` "
             f"(every number below is in `results/results.json`). The optimal c per shape, objective "
             f"(rows) and degree (columns); `target` is the mean squared distance to the file's analytic surface.", ""]
    shapes = sorted({r["boundary"] for r in rows})
    for shape in shapes:
        mine = [r for r in rows if r["boundary"] == shape]
        degrees = sorted({r["degree"] for r in mine})
        lines += [f"### {shape}", "", "| objective | " + " | ".join(f"n = {d}" for d in degrees) + " |",
                  "|---|" + "---|" * len(degrees)]
        for objective in dict.fromkeys(r["objective"] for r in mine):
            cells = []
            for d in degrees:
                hit = [r for r in mine if r["degree"] == d and r["objective"] == objective]
                cells.append(fmt(hit[0]) if hit else "")
            lines.append(f"| {objective} | " + " | ".join(cells) + " |")
        bounds = sorted({tuple(r["bounds"]) for r in mine})
        lines += ["", "Search bounds: " + ", ".join(f"n = {d}: [{b[0]:.4f}, {b[1]:.4f}]" for d, b in
                                                     sorted({(r['degree'], tuple(r['bounds'])) for r in mine})), ""]
    # Patterns looked for in the numbers above (computed, not assumed).
    lines += ["## Checks", "",
              "Distance of each optimum from −1/6 (the quadratic-precision member), and of the twist optimum from "
              "−1/6 + 1/(4n − 6), a formula read off the monkey saddle and the planar triangle; a dash marks a "
              "search without an interior optimum (flat or at a bound).", "",
              "| shape | objective | " + " | ".join(f"n = {d}" for d in DEGREES) + " |",
              "|---|---|" + "---|" * len(DEGREES)]
    for shape in shapes:
        for objective in ("thin_plate", "twist", "twist vs -1/6+1/(4n-6)", "target"):
            name = objective.split(" ")[0]
            cells, any_hit = [], False
            for d in DEGREES:
                hit = [r for r in rows if r["boundary"] == shape and r["degree"] == d and r["objective"] == name]
                if not hit:
                    cells.append("")
                    continue
                any_hit = True
                r = hit[0]
                if r["c"] is None or r["at_bound"]:
                    cells.append("–")
                    continue
                reference = -1 / 6 + (1 / (4 * d - 6) if " vs " in objective else 0)
                cells.append(f"{r['c'] - reference:+.2e}")
            if any_hit:
                lines.append(f"| {shape} | {objective} | " + " | ".join(cells) + " |")
    report = "\n".join(lines) + "\n"
    (out / "report.md").write_text(report)
    question = (HERE / "question.md").read_text()
    (HERE / "README.md").write_text(question.rstrip() + "\n\n" + report)


if __name__ == "__main__":
    main()
