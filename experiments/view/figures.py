#!/usr/bin/env python3
"""The figures of experiments/view/README.md, computed: writes figures.md from the standard output
of the `coons view` runs of run.sh (PAGES/*.json) and the energies `coons solve` gives at the
screenshots' parameters.
Usage: figures.py COONS PAGES_DIR OUT.md"""
import json
import subprocess
import sys
from pathlib import Path


def solve(coons, boundary, alpha):
    out = subprocess.run([coons, "solve", boundary, "--alpha", repr(alpha)], check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out)["metrics"]


def main():
    coons, pages, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    root = Path(__file__).resolve().parents[2]
    views = {name: json.loads((pages / f"{name}.json").read_text()) for name in ("dome", "cap", "dome_half")}
    lines = ["# Figures of the `coons view` pages (computed by figures.py; do not edit)", "",
             "From the standard output of `coons view` in the run that made the screenshots (`run.sh`):", "",
             "| page | degree | sliders | frames | samples | size | seconds (read + solve + write) |",
             "|---|---|---|---|---|---|---|"]
    for name, v in views.items():
        degree = v["degree"] if isinstance(v["degree"], int) else " × ".join(str(d) for d in v["degree"])
        seconds = sum(v["timing"].values())
        lines.append(f"| `{name}.html` | {degree} | {', '.join(v['sliders'])} | {v['frames']} | "
                     f"{v['samples']} × {v['samples']} | {v['bytes'] / 1e6:.1f} MB | {seconds:.2f} |")
    dome = str(root / "data/boundaries/dome.json")
    tri = str(root / "data/triangles/dome_half.json")
    e3 = {a: solve(coons, dome, a)["e3_energy"] for a in (-0.25, 0.2)}
    c_star = views["dome_half"]["optima"]["thin_plate"]
    thin = {c: solve(coons, tri, c)["thin_plate_energy"] for c in (-1 / 6, c_star)}
    w = views["cap"]["weight_optima"]
    lines += ["", "The values the screenshots' descriptions quote (`coons solve` at the same parameter):", "",
              f"- the dome's E3 energy: {e3[0.2]:.0f} at α = 0.2 against {e3[-0.25]:.0f} at α = −1/4;",
              f"- the sphere cap with ribbons, optimal C1 weight w*: thin plate {w['thin_plate']:.3f}, "
              f"E3 {w['e3']:.3f}, Dirichlet {w['dirichlet']:g}, twist {w['twist']:g};",
              f"- the triangle dome_half: thin-plate optimum c* = {c_star:.4f}, thin plate {thin[c_star]:.1f} "
              f"there against {thin[-1 / 6]:.1f} at c = −1/6.", ""]
    out.write_text("\n".join(lines))


if __name__ == "__main__":
    main()
