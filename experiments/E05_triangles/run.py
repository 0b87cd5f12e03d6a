#!/usr/bin/env python3
"""E05 — Farin–Hansford's triangles: the best member c of the triangular mask family per shape,
objective and degree. Regenerates results/results.json, results/report.md and README.md:

    python3 experiments/E05_triangles/run.py [--coons ./build/coons]
    python3 experiments/E05_triangles/run.py --check   # the README's conclusions against results.json

For each bundled triangle (data/triangles/*.json) and each degree of DEGREES at or above the
file's own, the sides are degree-elevated exactly (a Bézier curve elevated; the triangle's
boundary is the same curves), written to a temporary file, and `coons search-alpha --objective X`
is run for X in OBJECTIVES (and `target` when the file has one). The conclusions are claims computed
from the table (claims()); each is rendered as a sentence only in the form its numbers support, and
--check recomputes every claim from results/results.json, fails when the README's conclusions
differ from the generated ones or a claim contradicts the table, and tampers the table once per
claim to show that the check can fail. Python 3 standard library only."""
import argparse
import copy
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


SAME_C = 0.02       # optima closer than this count as "the same c"
TWIST_FORMULA = 1e-8  # |c* - (-1/6 + 1/(4n - 6))| below this counts as "given by the formula"


def interior(rows, shape, objective, degree):
    """The interior optimum c* of a cell, or None (flat, on a bound, failed, absent)."""
    hit = [r for r in rows if r["boundary"] == shape and r["objective"] == objective and r["degree"] == degree]
    if not hit or hit[0]["c"] is None or hit[0]["at_bound"] or hit[0]["flat"]:
        return None
    return hit[0]["c"]


def measure(rows, claim):
    """Recomputes what a claim is about from the table: the claim's numbers and whether it holds."""
    kind, objective = claim["kind"], claim.get("objective")
    shapes = sorted({r["boundary"] for r in rows})
    if kind == "spread":  # the interior optima of one objective at one degree, over the shapes
        d = claim["degree"]
        values = {s: interior(rows, s, objective, d) for s in shapes}
        values = {s: c for s, c in values.items() if c is not None}
        if len(values) < 2:
            return {"low": None, "high": None, "holds": False}
        low, high = min(values, key=values.get), max(values, key=values.get)
        return {"low": [low, round(values[low], 5)], "high": [high, round(values[high], 5)],
                "holds": values[high] - values[low] > SAME_C}
    if kind == "toward_quadratic":  # |c* + 1/6| decreases with the degree, shape by shape
        out = {}
        for s in shapes:
            cs = [(d, interior(rows, s, objective, d)) for d in DEGREES]
            cs = [(d, c) for d, c in cs if c is not None]
            if len(cs) >= 2:
                gaps = [abs(c + 1 / 6) for _, c in cs]
                out[s] = all(b < a for a, b in zip(gaps, gaps[1:]))
        return {"shapes": sorted(out), "against": sorted(s for s, ok in out.items() if not ok),
                "holds": bool(out) and all(out.values())}
    if kind == "on_bound":  # cells of an objective whose optimum sits on a search bound
        cells = sorted([r["boundary"], r["degree"]] for r in rows if r["objective"] == objective and r["at_bound"])
        total = sum(1 for r in rows if r["objective"] == objective)
        return {"cells": cells, "total": total, "holds": bool(cells)}
    if kind == "flat":
        cells = sorted([r["boundary"], r["degree"]] for r in rows if r["objective"] == objective and r["flat"])
        return {"cells": cells, "holds": bool(cells)}
    if kind == "twist_formula":  # shapes whose twist optimum is -1/6 + 1/(4n - 6) at every degree
        exact = []
        for s in shapes:
            cs = [(d, interior(rows, s, "twist", d)) for d in DEGREES]
            cs = [(d, c) for d, c in cs if c is not None]
            if cs and all(abs(c - (-1 / 6 + 1 / (4 * d - 6))) < TWIST_FORMULA for d, c in cs):
                exact.append(s)
        return {"exact": exact, "others": [s for s in shapes if s not in exact], "holds": bool(exact)}
    raise ValueError(kind)


def claims(rows):
    """The claims of the conclusions, each with the numbers measure() gives for it."""
    out = []
    top = max(r["degree"] for r in rows)
    for objective in ("thin_plate", "twist", "discrete_thin_plate", "target"):
        out.append(dict({"kind": "spread", "objective": objective, "degree": top},
                        **measure(rows, {"kind": "spread", "objective": objective, "degree": top})))
    for objective in ("thin_plate", "twist", "discrete_thin_plate", "target"):
        out.append(dict({"kind": "toward_quadratic", "objective": objective},
                        **measure(rows, {"kind": "toward_quadratic", "objective": objective})))
    out.append(dict({"kind": "on_bound", "objective": "dirichlet"},
                    **measure(rows, {"kind": "on_bound", "objective": "dirichlet"})))
    out.append(dict({"kind": "flat", "objective": "target"}, **measure(rows, {"kind": "flat", "objective": "target"})))
    out.append(dict({"kind": "twist_formula"}, **measure(rows, {"kind": "twist_formula"})))
    return out


def sentence(claim):
    """A claim in words: the form of the sentence follows the measured `holds`."""
    k, o, h = claim["kind"], claim.get("objective"), claim["holds"]
    if k == "spread":
        if claim["low"] is None:
            return f"At n = {claim['degree']}, fewer than two shapes have an interior {o} optimum."
        (ls, lc), (hs, hc) = claim["low"], claim["high"]
        verdict = (f"no single c is best for {o}" if h else f"one c serves every shape for {o} (within {SAME_C})")
        return (f"At n = {claim['degree']}, {verdict}: its interior optima run from {lc:.5f} ({ls}) to "
                f"{hc:.5f} ({hs}).")
    if k == "toward_quadratic":
        if h:
            return (f"Every {o} optimum moves toward the quadratic-precision member −1/6 as the degree grows "
                    f"(|c* + 1/6| decreases from degree to degree for {', '.join(claim['shapes'])}).")
        return (f"The {o} optima do not all approach −1/6 monotonically as the degree grows (against it: "
                f"{', '.join(claim['against']) or 'no shape with two interior optima'}).")
    if k == "on_bound":
        where = ", ".join(f"{s} n = {d}" for s, d in claim["cells"]) or "none"
        if h:
            return (f"The {o} optimum lies on a search bound in {len(claim['cells'])} of {claim['total']} cells "
                    f"({where}): there the range does not contain its minimiser, and no best c is claimed.")
        return f"No {o} optimum lies on a search bound ({claim['total']} cells)."
    if k == "flat":
        if h:
            return (f"The {o} objective does not depend on c for " +
                    ", ".join(f"{s} n = {d}" for s, d in claim["cells"]) +
                    " (flat: every member keeps the planar net in its plane).")
        return f"No {o} objective is flat."
    if k == "twist_formula":
        if h:
            return (f"The twist optimum equals −1/6 + 1/(4n − 6) to {TWIST_FORMULA:g} at every degree for "
                    f"{', '.join(claim['exact'])}, and not for {', '.join(claim['others']) or 'any other shape'}: "
                    f"a pattern of these shapes, not a law.")
        return "No shape's twist optimum follows −1/6 + 1/(4n − 6) at every degree."
    raise ValueError(k)


def contradictions(rows, claim_list):
    """Claims whose numbers or verdict differ from what the table gives (empty: all consistent)."""
    bad = []
    for claim in claim_list:
        fresh = measure(rows, claim)
        for key, value in fresh.items():
            if claim.get(key) != value:
                bad.append(f"{claim['kind']} {claim.get('objective', '')}: {key} is {value}, the claim says "
                           f"{claim.get(key)}")
    return bad


def tampered(rows, claim):
    """A copy of the table changed so that `claim` no longer describes it (for the self-test)."""
    rows = copy.deepcopy(rows)
    k, o = claim["kind"], claim.get("objective")
    mine = [r for r in rows if r["objective"] == (o or "twist")]
    if k == "spread":
        for r in mine:
            if r["degree"] == claim["degree"] and r["c"] is not None and not r["at_bound"]:
                r["c"] = -0.15 if claim["holds"] else r["c"] + 0.1 * len(r["boundary"])
    elif k in ("toward_quadratic", "twist_formula"):
        for r in mine:
            if r["c"] is not None:
                r["c"] = -1 / 6 - 0.01 * r["degree"] if claim["holds"] else -1 / 6 + 1 / (4 * r["degree"] - 6)
    elif k == "on_bound":
        for r in mine:
            r["at_bound"] = not claim["holds"]
    elif k == "flat":
        for r in mine:
            r["flat"] = not claim["holds"]
    return rows


def conclusions_markdown(claim_list):
    return "\n".join(["## Conclusions, computed from the table", "",
                      "Each sentence is generated from `results/results.json` in the form its numbers support; "
                      "`run.py --check` recomputes them and fails on any contradiction.", ""] +
                     [f"- {sentence(c)}" for c in claim_list]) + "\n"


def check():
    rows = json.loads((HERE / "results" / "results.json").read_text())
    claim_list = claims(rows)
    problems = contradictions(rows, claim_list)
    readme = (HERE / "README.md").read_text()
    if conclusions_markdown(claim_list) not in readme:
        problems.append("README.md's conclusions are not those the table gives (rerun run.py)")
    for claim in claim_list:  # the check can fail: a table that contradicts each claim is caught
        if not contradictions(tampered(rows, claim), [claim]):
            problems.append(f"self-test: a table contradicting '{sentence(claim)}' was not caught")
    for p in problems:
        print("E05 check:", p)
    print(f"E05 check: {len(claim_list)} conclusions, {len(problems)} problems")
    raise SystemExit(1 if problems else 0)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--coons", default=str(ROOT / "build" / "coons"))
    parser.add_argument("--check", action="store_true", help="check README's conclusions against results.json")
    args = parser.parse_args()
    if args.check:
        check()
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
    report = "\n".join(lines) + "\n\n" + conclusions_markdown(claims(rows))
    (out / "report.md").write_text(report)
    question = (HERE / "question.md").read_text()
    (HERE / "README.md").write_text(question.rstrip() + "\n\n" + report)


if __name__ == "__main__":
    main()
