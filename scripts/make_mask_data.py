#!/usr/bin/env python3
"""Writes the bundled data of the masks beyond one ring (docs/formats.md, 'Boundary data beyond one
ring'): boundaries with ribbons of known smooth surfaces (data/boundaries/*_ribbons.json) and nets
with free grids (data/free_sets/*.json). Standard library only; run from anywhere:

    python3 scripts/make_mask_data.py          # rewrite the files
    python3 scripts/make_mask_data.py --check  # exit 1 when a file differs from what it would write

Each surface p(u, v) on [0, 1]^2 is fitted by a tensor-product Bezier net of degree (m, n) by least
squares on a (4m+1) x (4n+1) grid of uniform parameters (the problem separates: N = Bu^+ S Bv^+^T per
coordinate, Bu^+ = (Bu^T Bu)^-1 Bu^T). The outer ring of that net is written as the sides, the second
ring as the ribbons (so the sides and ribbons agree exactly: every shared point is written once);
the free-set files hold the whole fitted net, the free grid marking the points to solve for.
"""
import json
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def bernstein(k, t):
    return [math.comb(k, i) * t**i * (1 - t) ** (k - i) for i in range(k + 1)]


def solve(A, B):
    """Gaussian elimination with partial pivoting: A X = B, A square (lists), B a list of rows."""
    n = len(A)
    M = [list(A[r]) + list(B[r]) for r in range(n)]
    w = len(M[0])
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(M[r][c]))
        M[c], M[p] = M[p], M[c]
        for r in range(n):
            if r != c and M[r][c] != 0:
                f = M[r][c] / M[c][c]
                M[r] = [M[r][k] - f * M[c][k] for k in range(w)]
    return [[M[r][k] / M[r][r] for k in range(n, w)] for r in range(n)]


def pseudo_inverse(k, samples):
    """(B^T B)^-1 B^T for the degree-k Bernstein matrix B at `samples` parameters: (k+1) x #samples."""
    ts = [s / (samples - 1) for s in range(samples)]
    B = [bernstein(k, t) for t in ts]
    BtB = [[sum(B[s][a] * B[s][b] for s in range(samples)) for b in range(k + 1)] for a in range(k + 1)]
    Bt = [[B[s][a] for s in range(samples)] for a in range(k + 1)]
    return solve(BtB, Bt), ts


def fit_net(surface, m, n):
    """The least-squares Bezier net of degree (m, n): net[i][j] = [x, y, z]."""
    Pu, us = pseudo_inverse(m, 4 * m + 1)
    Pv, vs = pseudo_inverse(n, 4 * n + 1)
    S = [[surface(u, v) for v in vs] for u in us]
    net = [[[0.0, 0.0, 0.0] for _ in range(n + 1)] for _ in range(m + 1)]
    for c in range(3):
        T = [[sum(Pu[i][s] * S[s][t][c] for s in range(len(us))) for t in range(len(vs))] for i in range(m + 1)]
        for i in range(m + 1):
            for j in range(n + 1):
                net[i][j][c] = sum(T[i][t] * Pv[j][t] for t in range(len(vs)))
    return net


def max_fit_error(surface, net, samples=41):
    m, n = len(net) - 1, len(net[0]) - 1
    worst = 0.0
    for a in range(samples):
        for b in range(samples):
            u, v = a / (samples - 1), b / (samples - 1)
            bu, bv = bernstein(m, u), bernstein(n, v)
            p = [sum(bu[i] * bv[j] * net[i][j][c] for i in range(m + 1) for j in range(n + 1)) for c in range(3)]
            q = surface(u, v)
            worst = max(worst, math.dist(p, q))
    return worst


# ---- the surfaces -------------------------------------------------------------------------------

def sphere_cap(u, v):
    """the unit sphere over [-0.6, 0.6]^2: (x, y, sqrt(1 - x^2 - y^2))."""
    x, y = 1.2 * u - 0.6, 1.2 * v - 0.6
    return [x, y, math.sqrt(1 - x * x - y * y)]


def torus_patch(u, v):
    """the torus of radii R = 2, r = 0.7 around z: theta = (pi/2) u around the axis, phi = -pi/2 + pi v
    around the tube (the outer half of a quarter)."""
    theta, phi = 0.5 * math.pi * u, -0.5 * math.pi + math.pi * v
    rho = 2 + 0.7 * math.cos(phi)
    return [rho * math.cos(theta), rho * math.sin(theta), 0.7 * math.sin(phi)]


def saddle_bump(u, v):
    """z = (x^2 - y^2)/2 + 0.6 exp(-((x - 0.2)^2 + (y + 0.1)^2)/0.6) over [-1, 1]^2."""
    x, y = 2 * u - 1, 2 * v - 1
    return [x, y, 0.5 * (x * x - y * y) + 0.6 * math.exp(-((x - 0.2) ** 2 + (y + 0.1) ** 2) / 0.6)]


def gentle_hill(u, v):
    """z = 0.3 sin(pi x) cos(pi y / 2) + 0.2 x y over [0, 1] x [-1, 1]."""
    x, y = u, 2 * v - 1
    return [x, y, 0.3 * math.sin(math.pi * x) * math.cos(0.5 * math.pi * y) + 0.2 * x * y]


# ---- the files ----------------------------------------------------------------------------------

def ribbon_file(name, description, surface, m, n):
    net = fit_net(surface, m, n)
    err = max_fit_error(surface, net)
    doc = {
        "name": name,
        "description": description,
        "source": (f"constructed for coons by scripts/make_mask_data.py: least-squares Bezier fit of degree "
                   f"({m}, {n}) on a ({4 * m + 1} x {4 * n + 1}) uniform parameter grid, max deviation "
                   f"{err:.2g} on a 41 x 41 grid; sides = its outer ring, ribbons = its second ring"),
        "degree": [m, n],
        "bottom": [net[i][0] for i in range(m + 1)],
        "top": [net[i][n] for i in range(m + 1)],
        "left": [net[0][j] for j in range(n + 1)],
        "right": [net[m][j] for j in range(n + 1)],
        "ribbons": {
            "bottom": [net[i][1] for i in range(m + 1)],
            "top": [net[i][n - 1] for i in range(m + 1)],
            "left": [net[1][j] for j in range(n + 1)],
            "right": [net[m - 1][j] for j in range(n + 1)],
        },
    }
    return doc


def free_set_file(name, description, surface, m, n, rings, is_free):
    net = fit_net(surface, m, n)
    free = [[1 if is_free(i, j) else 0 for j in range(n + 1)] for i in range(m + 1)]
    for i in range(m + 1):
        for j in range(n + 1):
            assert not (free[i][j] and min(i, j, m - i, n - j) < rings), (name, i, j)
    count = sum(map(sum, free))
    return {
        "name": name,
        "description": f"{description} ({count} free points)",
        "source": (f"constructed for coons by scripts/make_mask_data.py: the net is the least-squares Bezier fit of "
                   f"degree ({m}, {n}) of {surface.__doc__.strip().rstrip('.')}; the values at free "
                   f"points are only start values"),
        "degree": [m, n],
        "rings": rings,
        "net": net,
        "free": free,
    }


def files():
    out = {}
    out["data/boundaries/sphere_cap_ribbons.json"] = ribbon_file(
        "sphere_cap_ribbons", "the unit sphere over [-0.6, 0.6]^2 (z = sqrt(1 - x^2 - y^2)) with two data rings",
        sphere_cap, 6, 6)
    out["data/boundaries/torus_patch_ribbons.json"] = ribbon_file(
        "torus_patch_ribbons", "the outer half of a quarter torus (R = 2, r = 0.7) with two data rings",
        torus_patch, 7, 5)
    out["data/boundaries/saddle_bump_ribbons.json"] = ribbon_file(
        "saddle_bump_ribbons",
        "the saddle z = (x^2 - y^2)/2 with a Gaussian bump near (0.2, -0.1), over [-1, 1]^2, with two data rings",
        saddle_bump, 8, 8)
    m = n = 10

    def l_hole(i, j):  # an L: a 6 x 2 bar along i and a 2 x 4 foot along j, all at depth >= 2
        return (2 <= i <= 7 and 2 <= j <= 3) or (6 <= i <= 7 and 4 <= j <= 7)

    def island(i, j):  # the inside of the two rings except a fixed 3 x 3 island in the middle
        return 2 <= i <= 8 and 2 <= j <= 8 and not (4 <= i <= 6 and 4 <= j <= 6)

    def curve(i, j):  # the inside except a fixed polyline: the diagonal i = j, then the row i = 5
        on_curve = (i == j and 2 <= i <= 5) or (i == 5 and 5 <= j <= 8)
        return 2 <= i <= 8 and 2 <= j <= 8 and not on_curve

    out["data/free_sets/l_hole.json"] = free_set_file(
        "l_hole", "an L-shaped hole in the net of a saddle with a bump: every point outside the L is data",
        saddle_bump, m, n, 2, l_hole)
    out["data/free_sets/island.json"] = free_set_file(
        "island", "a hole around a fixed 3 x 3 island in the middle of a sphere cap's net, two data rings",
        sphere_cap, m, n, 2, island)
    out["data/free_sets/curve.json"] = free_set_file(
        "curve", "a gentle hill's net with two data rings and a fixed interior curve (a diagonal, then a row)",
        gentle_hill, m, n, 2, curve)
    return out


def main():
    check = "--check" in sys.argv[1:]
    differ = 0
    for rel, doc in files().items():
        text = json.dumps(doc, indent=1) + "\n"
        path = ROOT / rel
        if check:
            if not path.exists() or path.read_text() != text:
                print(f"differs: {rel}")
                differ += 1
        else:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
            print(f"wrote {rel}")
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
