#!/usr/bin/env python3
"""Writes the bundled B-spline boundary data/boundaries/bspline_wave.json (docs/formats.md,
"B-spline boundaries"). Python 3 standard library only; run from anywhere:

    python3 scripts/make_bspline_boundary.py

Four clamped B-spline curves over the square [0, 2] x [0, 1] with a wave in z: bottom and top are
cubic (degree_spline p = 3) with 8 points on the non-uniform knots_u; left and right are quadratic
(q = 2) with 5 points, each on its own non-uniform knot vector ("knots_v" per side), so the reader
makes them compatible by knot insertion (a note in the report). The net is 8 x 7 points after
that: m != n. Control points are the Greville points of z = 0.25 sin(pi x) cos(pi y / 2) along
each side (x, y at the side's Greville abscissae), so the curves are smooth and non-planar; each
corner is computed once and written on both sides that meet there."""
import json
import math
import pathlib

OUT = pathlib.Path(__file__).resolve().parent.parent / "data" / "boundaries" / "bspline_wave.json"

P, Q = 3, 2
KNOTS_U = [0, 0, 0, 0, 0.1, 0.25, 0.6, 0.8, 1, 1, 1, 1]  # 8 points, non-uniform
KNOTS_LEFT = [0, 0, 0, 0.2, 0.7, 1, 1, 1]  # 5 points
KNOTS_RIGHT = [0, 0, 0, 0.45, 0.55, 1, 1, 1]  # 5 points, other interior knots


def greville(knots, degree):
    count = len(knots) - degree - 1
    return [sum(knots[i + 1:i + degree + 1]) / degree for i in range(count)]


def height(x, y):
    return 0.25 * math.sin(math.pi * x) * math.cos(math.pi * y / 2) + 0.1 * x * y


def point(x, y):
    return [x, y, height(x, y)]


def main():
    xs = [2 * g for g in greville(KNOTS_U, P)]
    corners = {(x, y): point(x, y) for x in (0.0, 2.0) for y in (0.0, 1.0)}

    def side_u(y):
        pts = [point(x, y) for x in xs]
        pts[0], pts[-1] = corners[(0.0, y)], corners[(2.0, y)]
        return pts

    def side_v(x, knots):
        ys = greville(knots, Q)
        pts = [point(x, y) for y in ys]
        pts[0], pts[-1] = corners[(x, 0.0)], corners[(x, 1.0)]
        return pts

    doc = {
        "name": "bspline_wave",
        "description": "Clamped B-spline sides over [0,2]x[0,1] with z = 0.25 sin(pi x) cos(pi y/2) + 0.1 x y at "
                       "the Greville points: cubic bottom/top on non-uniform knots, quadratic left/right on two "
                       "different non-uniform knot vectors (made compatible by knot insertion).",
        "source": "scripts/make_bspline_boundary.py (constructed for coons)",
        "degree_spline": [P, Q],
        "knots_u": KNOTS_U,
        "knots_v": {"left": KNOTS_LEFT, "right": KNOTS_RIGHT},
        "bottom": side_u(0.0),
        "top": side_u(1.0),
        "left": side_v(0.0, KNOTS_LEFT),
        "right": side_v(2.0, KNOTS_RIGHT),
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")


if __name__ == "__main__":
    main()
