#!/usr/bin/env python3
"""Linear systems from outside coons, for `coons bench-matrix`: Matrix Market files written the way
the SuiteSparse Matrix Collection writes them (a comment block; a symmetric matrix as its lower
triangle), built with SciPy (python3-scipy) from standard finite-difference model problems. They
are not mask systems: no grid stencil travels with them, so only the general backends apply.

    python3 scripts/make_outside_matrix.py [--out data/matrices]

writes
  anisotropic_diffusion.mtx   -eps u_xx - u_yy on the unit square, eps = 1e-3, Dirichlet, 32 x 32
                              interior points, 5-point stencil scaled by h^2: SPD, `symmetric`
  convection_diffusion.mtx    -Δu + b·∇u, b = (40, 20), first-order upwind, 24 x 24 interior
                              points, scaled by h^2: nonsymmetric, `general`
  convection_diffusion_b.mtx  two right-hand sides for it (`array`): f = 1 and f = sin(πx) sin(πy)

The bundled copies in data/matrices/ are this script's output; the tests use them (the build
needs no SciPy). Where `python3` is not the system's (a pyenv shim), run /usr/bin/python3.
"""
import argparse
import os

import numpy as np
import scipy.io
import scipy.sparse as sp


def laplacian_1d(n):
    return sp.diags([-np.ones(n - 1), 2 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")


def anisotropic_diffusion(n, eps):
    eye = sp.identity(n, format="csr")
    # unknown k = i + n*j, i along x
    return (eps * sp.kron(eye, laplacian_1d(n)) + sp.kron(laplacian_1d(n), eye)).tocsr()


def convection_diffusion(n, bx, by):
    h = 1.0 / (n + 1)
    eye = sp.identity(n, format="csr")
    # first-order upwind differences for b > 0: (u_i - u_{i-1}) / h, times h^2
    upwind = sp.diags([-np.ones(n - 1), np.ones(n)], [-1, 0], format="csr") * h
    diffusion = sp.kron(eye, laplacian_1d(n)) + sp.kron(laplacian_1d(n), eye)
    convection = bx * sp.kron(eye, upwind) + by * sp.kron(upwind, eye)
    return (diffusion + convection).tocsr(), h


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    default = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "matrices"))
    parser.add_argument("--out", default=default)
    out = parser.parse_args().out
    os.makedirs(out, exist_ok=True)
    tool = "written by coons scripts/make_outside_matrix.py (SciPy " + scipy.__version__ + ")"

    A = anisotropic_diffusion(32, 1e-3)
    scipy.io.mmwrite(os.path.join(out, "anisotropic_diffusion.mtx"), A, symmetry="symmetric",
                     comment="name: anisotropic_diffusion\nkind: 2D/3D problem (SPD)\n"
                             "-eps u_xx - u_yy, eps = 1e-3, unit square, Dirichlet, 32 x 32 interior points, "
                             "5-point stencil times h^2\n" + tool)

    C, h = convection_diffusion(24, 40.0, 20.0)
    scipy.io.mmwrite(os.path.join(out, "convection_diffusion.mtx"), C, symmetry="general",
                     comment="name: convection_diffusion\nkind: computational fluid dynamics problem (nonsymmetric)\n"
                             "-Laplace(u) + b.grad(u), b = (40, 20), first-order upwind, unit square, Dirichlet, "
                             "24 x 24 interior points, times h^2\n" + tool)
    x = np.arange(1, 25) * h
    X, Y = np.meshgrid(x, x, indexing="xy")  # unknown k = i + 24*j: x varies fastest
    B = np.column_stack([np.full(24 * 24, h * h), h * h * (np.sin(np.pi * X) * np.sin(np.pi * Y)).ravel()])
    scipy.io.mmwrite(os.path.join(out, "convection_diffusion_b.mtx"), B,
                     comment="right-hand sides of convection_diffusion.mtx: h^2 f for f = 1 and "
                             "f = sin(pi x) sin(pi y)\n" + tool)
    for name in sorted(os.listdir(out)):
        if name.endswith(".mtx"):
            print(f"{os.path.join(out, name)}: {os.path.getsize(os.path.join(out, name))} bytes")


if __name__ == "__main__":
    main()
