#!/usr/bin/env python3
"""Writes the bundled triangular boundaries data/triangles/*.json (docs/formats.md, triangular
boundary files). Python 3 standard library only; run from anywhere:

    python3 scripts/make_triangles.py

Each side runs as the contract says: sides[0] from b[n][0][0] to b[0][n][0], sides[1] from
b[0][n][0] to b[0][0][n], sides[2] from b[0][0][n] to b[n][0][0]; a corner is computed once and
written on both sides that meet there, so corners agree bit for bit."""
import json
import math
import pathlib
from math import comb

OUT = pathlib.Path(__file__).resolve().parent.parent / "data" / "triangles"


def bernstein(n, i, t):
    return comb(n, i) * t**i * (1 - t) ** (n - i)


def solve(a, b):
    """Gaussian elimination with partial pivoting (small dense systems)."""
    n = len(b)
    m = [row[:] + [b[r]] for r, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(c + 1, n):
            f = m[r][c] / m[c][c]
            for k in range(c, n + 1):
                m[r][k] -= f * m[c][k]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (m[r][n] - sum(m[r][k] * x[k] for k in range(r + 1, n))) / m[r][r]
    return x


def fit_bezier(curve, n, samples=400):
    """Least-squares Bézier fit of degree n to curve(t), t in [0, 1], at uniform t, end points
    interpolated. Returns (points, max deviation at 4·samples parameters)."""
    p0, pn = curve(0.0), curve(1.0)
    ts = [k / (samples - 1) for k in range(samples)]
    inner = list(range(1, n))
    ata = [[sum(bernstein(n, i, t) * bernstein(n, j, t) for t in ts) for j in inner] for i in inner]
    points = [p0]
    coords = []
    for c in range(3):
        rhs = []
        for i in inner:
            rhs.append(sum(bernstein(n, i, t) * (curve(t)[c] - bernstein(n, 0, t) * p0[c] - bernstein(n, n, t) * pn[c])
                           for t in ts))
        coords.append(solve(ata, rhs))
    for k in range(len(inner)):
        points.append([coords[0][k], coords[1][k], coords[2][k]])
    points.append(pn)
    worst = 0.0
    for k in range(4 * samples):
        t = k / (4 * samples - 1)
        q = [sum(bernstein(n, i, t) * points[i][c] for i in range(n + 1)) for c in range(3)]
        worst = max(worst, math.dist(q, curve(t)))
    return points, worst


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


def line_on(f, p, q, n):
    """The side f((1−t)p + tq) for a polynomial f of degree ≤ n in the plane, as exact Bézier
    control points: interpolation at n+1 points solved in the Bernstein basis."""
    ts = [k / n for k in range(n + 1)]
    a = [[bernstein(n, i, t) for i in range(n + 1)] for t in ts]
    values = [f([(1 - t) * p[0] + t * q[0], (1 - t) * p[1] + t * q[1]]) for t in ts]
    cols = [solve(a, [v[c] for v in values]) for c in range(3)]
    pts = [[cols[0][i], cols[1][i], cols[2][i]] for i in range(n + 1)]
    pts[0], pts[-1] = f(p), f(q)
    return pts


def write(name, degree, sides, description, source, extra=None):
    # corners shared bit for bit
    sides[1][0] = sides[0][-1]
    sides[2][0] = sides[1][-1]
    sides[2][-1] = sides[0][0]
    sides = [[[0.0 if abs(c) < 1e-15 else float(c) for c in p] for p in side] for side in sides]
    lines = ["{", f'  "name": {json.dumps(name)},', '  "type": "triangle",', f'  "degree": {degree},',
             '  "sides": [']
    for s, side in enumerate(sides):
        pts = ",\n".join("    " + ("[" if k == 0 else " ") + json.dumps(p) for k, p in enumerate(side))
        lines.append(pts + "]" + ("," if s < 2 else ""))
    lines.append("  ],")
    for key, value in (extra or {}).items():
        lines.append(f"  {json.dumps(key)}: {json.dumps(value)},")
    lines.append(f'  "description": {json.dumps(description, ensure_ascii=False)},')
    lines.append(f'  "source": {json.dumps(source, ensure_ascii=False)}')
    lines.append("}")
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / f"{name}.json").write_text("\n".join(lines) + "\n", encoding="utf-8")


def octant(n=6):
    e = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]

    def arc(a, b):
        return lambda t: [math.cos(t * math.pi / 2) * a[c] + math.sin(t * math.pi / 2) * b[c] for c in range(3)]

    sides, worst = [], 0.0
    for s in range(3):
        pts, dev = fit_bezier(arc(e[s], e[(s + 1) % 3]), n)
        sides.append(pts)
        worst = max(worst, dev)
    write("sphere_octant", n, sides,
          f"the octant x, y, z >= 0 of the unit sphere: its three quarter circles as degree-{n} Bézier "
          f"curves (least squares at 400 uniform angles, end points interpolated; max deviation {worst:.2g})",
          "constructed for coons (issue 13: a spherical triangle)",
          {"target": {"sphere": {"center": [0, 0, 0], "radius": 1}}})


def planar(n=5):
    # a curved-sided triangle in the plane z = 0: corners (1,0), (-1/2, √3/2), (-1/2, -√3/2),
    # each side the parabola (1-t)p + tq + h·4t(1-t)·(outward normal), h = 0.3, 0.1, −0.15 (with equal
    # h the three second differences cancel and every member c reproduces the same quadratic patch)
    corners = [[math.cos(2 * math.pi * k / 3), math.sin(2 * math.pi * k / 3)] for k in range(3)]
    sides = []
    for s, h in enumerate((0.3, 0.1, -0.15)):
        p, q = corners[s], corners[(s + 1) % 3]
        mid = [(p[0] + q[0]) / 2, (p[1] + q[1]) / 2]
        length = math.hypot(*mid)
        normal = [mid[0] / length, mid[1] / length]

        def f(t, p=p, q=q, normal=normal, h=h):
            b = h * 4 * t * (1 - t)
            return [(1 - t) * p[c] + t * q[c] + b * normal[c] for c in range(2)] + [0.0]

        sides.append(elevate(line_on(lambda xy, f=f, p=p, q=q: f(param(p, q, xy)), p, q, 2), n - 2))
    write("planar_bulge", n, sides,
          "a flat curved-sided triangle in the plane z = 0: corners on the unit circle at 0°, 120°, 240°, each "
          "side the parabola (1−t)p + tq + 4h·t(1−t)·(outward normal) with h = 0.3, 0.1, −0.15 on sides 0, 1, 2, "
          "exact quadratics elevated to degree 5",
          "constructed for coons (issue 13: a flat triangle)",
          {"target": {"plane": {"point": [0, 0, 0], "normal": [0, 0, 1]}}})


def param(p, q, xy):
    """t of the point xy = (1−t)p + tq on the segment pq."""
    dx, dy = q[0] - p[0], q[1] - p[1]
    return ((xy[0] - p[0]) * dx + (xy[1] - p[1]) * dy) / (dx * dx + dy * dy)


def monkey_saddle(n=6):
    corners = [[math.cos(2 * math.pi * k / 3), math.sin(2 * math.pi * k / 3)] for k in range(3)]

    def f(xy):
        x, y = xy
        return [x, y, 0.5 * (x**3 - 3 * x * y * y)]

    sides = [elevate(line_on(f, corners[s], corners[(s + 1) % 3], 3), n - 3) for s in range(3)]
    write("monkey_saddle", n, sides,
          "boundary of the monkey saddle z = (x³ − 3xy²)/2 over the triangle with corners on the unit circle "
          "at 0°, 120°, 240°: each side the exact cubic, elevated to degree 6",
          "constructed for coons (issue 13: a saddle-like triangle)")


def dome_half(n=6):
    # the dome of data/boundaries/dome.json cut along its diagonal: its bottom and right sides
    # (the cubic arcs with K = 4(√2 − 1)/3) and the arc of the same sphere (centre (0,0,−1),
    # radius √3) in the plane x = y from (1,1,0) back to (−1,−1,0), as the cubic arc of its angle.
    k = 4 * (math.sqrt(2) - 1) / 3
    bottom = [[-1, -1, 0], [-1 + k, -1, k], [1 - k, -1, k], [1, -1, 0]]
    right = [[1, -1, 0], [1, -1 + k, k], [1, 1 - k, k], [1, 1, 0]]
    r = math.sqrt(3)
    half = math.atan2(math.sqrt(2), 1)  # the end points seen from the centre: ±54.7° from the vertical
    h = 4 / 3 * math.tan(half / 2) * r  # handle length of the cubic arc of angle 2·half
    # in the plane x = y: s = (x + y)/√2 from +√2 to −√2; the tangent at the ends is perpendicular to the radius
    def point(s, z):
        return [s / math.sqrt(2), s / math.sqrt(2), z]
    start, end = (math.sqrt(2), 0.0), (-math.sqrt(2), 0.0)
    t0 = (-1 / r, math.sqrt(2) / r)  # unit tangent at start (radius (√2, 1)/√3 turned towards −s)
    t1 = (-1 / r, -math.sqrt(2) / r)  # unit tangent at end (radius (−√2, 1)/√3)
    diagonal = [point(*start), point(start[0] + h * t0[0], start[1] + h * t0[1]),
                point(end[0] - h * t1[0], end[1] - h * t1[1]), point(*end)]
    sides = [elevate(bottom, n - 3), elevate(right, n - 3), elevate(diagonal, n - 3)]
    sides = [[[float(c) for c in p] for p in side] for side in sides]
    write("dome_half", n, sides,
          "the dome (data/boundaries/dome.json) cut along the diagonal from (−1,−1,0) to (1,1,0): its bottom and "
          "right cubic arcs and the cubic arc (handles 4/3·tan(θ/4)·√3, θ its angle) of the same sphere in the "
          "plane x = y, all elevated to degree 6",
          "constructed for coons from the dome test shape (docs/math.md §7 example 5)",
          {"target": {"sphere": {"center": [0, 0, -1], "radius": math.sqrt(3)}}})


if __name__ == "__main__":
    octant()
    planar()
    monkey_saddle()
    dome_half()
