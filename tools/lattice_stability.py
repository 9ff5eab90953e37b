#!/usr/bin/env python3
"""Linear stability of the square (cubic) start lattice under a uniform positive pressure, for the
symmetric pressure force of WCSPH, a_a = -sum_b m (p_a / rho_a^2 + p_b / rho_b^2) grad W_ab.

Displace the lattice by a plane wave u_b = e exp(i k . r_b).  With a uniform pressure the force on a
particle is -C grad sum_b W(x_a - x_b) (C = 2 p m / rho^2 > 0), so the mode grows when
    M(k) = sum_b H(r_b) (1 - cos(k . r_b)),   H = the Hessian of W,
has a negative eigenvalue.  A longitudinal mode also compresses the fluid, and the equation of state
pushes it back (c0^2 >> p / rho); a transverse mode (e perpendicular to k) has no such restoring
force, so the lattice is unstable when the smallest transverse eigenvalue of M over the Brillouin
zone is negative.  Viscosity, walls and the free surface are left out: this explains which
kernels and h / dx keep a still tank on its start lattice, it does not replace running the tank
(docs/convergence.md: e.g. the cubic spline at 1.2 dx is stable here and drifts in the tank).

Usage: tools/lattice_stability.py [--dim 2|3] [--kernels cubic,wendland_c2,wendland_c4]
                                  [--h 1.2,1.3,1.4,1.5,2.0] [--nk 33]
Prints, per kernel and h / dx, the smallest transverse eigenvalue relative to the largest eigenvalue
of M over the zone (negative = unstable; within -0.1 % called marginal) and the wave vector k / pi
where it occurs."""
import argparse
import itertools
import math

import numpy as np

# kernel shapes f(q), q = r / h, support q < 2; the normalisation does not change the sign
SHAPES = {
    "cubic": lambda q: np.where(q < 1, 1 - 1.5 * q**2 + 0.75 * q**3, np.where(q < 2, 0.25 * (2 - q) ** 3, 0.0)),
    "wendland_c2": lambda q: np.where(q < 2, (1 - q / 2) ** 4 * (2 * q + 1), 0.0),
    "wendland_c4": lambda q: np.where(q < 2, (1 - q / 2) ** 6 * (35 / 12 * q**2 + 3 * q + 1), 0.0),
}


def hessian(shape, hf, r, dim, eps=1e-5):
    """Hessian of W(|x| / hf) / hf^dim at x = r, by central differences."""
    def w(x):
        return shape(np.linalg.norm(x) / hf) / hf**dim
    eye = np.eye(dim) * eps
    H = np.empty((dim, dim))
    for i in range(dim):
        for j in range(dim):
            H[i, j] = (w(r + eye[i] + eye[j]) - w(r + eye[i] - eye[j]) - w(r - eye[i] + eye[j]) + w(r - eye[i] - eye[j])) / (4 * eps * eps)
    return H


def smallest_transverse(shape, hf, dim, nk):
    n = math.ceil(2 * hf)
    pts = np.array([p for p in itertools.product(range(-n, n + 1), repeat=dim) if any(p) and math.sqrt(sum(c * c for c in p)) < 2 * hf], float)
    Hs = np.array([hessian(shape, hf, p, dim) for p in pts])
    best, top = (math.inf, None), 0.0
    for k in itertools.product(np.linspace(0, math.pi, nk), repeat=dim):
        k = np.array(k)
        kk = np.linalg.norm(k)
        if kk == 0:
            continue
        M = np.einsum("b,bij->ij", 1 - np.cos(pts @ k), Hs)
        # an orthonormal basis of the plane perpendicular to k: the transverse polarisations
        basis = np.linalg.svd(np.outer(k, k) / kk**2)[0][:, 1:]
        ev = np.linalg.eigvalsh(basis.T @ M @ basis).min()
        top = max(top, np.linalg.eigvalsh(M).max())
        if ev < best[0]:
            best = (ev, k / math.pi)
    return best[0] / top, best[1]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--dim", type=int, default=2, choices=(2, 3))
    ap.add_argument("--kernels", default="cubic,wendland_c2,wendland_c4")
    ap.add_argument("--h", default="1.2,1.3,1.4,1.5,1.7,2.0")
    ap.add_argument("--nk", type=int, default=0, help="k points per direction (default 33 in 2D, 13 in 3D)")
    a = ap.parse_args()
    nk = a.nk or (33 if a.dim == 2 else 13)
    print(f"| kernel | h / dx | smallest transverse eigenvalue / largest ({a.dim}D) | at k / pi | start lattice |")
    print("|---|---|---|---|---|")
    for name in a.kernels.split(","):
        for hf in (float(s) for s in a.h.split(",")):
            ev, k = smallest_transverse(SHAPES[name], hf, a.dim, nk)
            verdict = "stable" if ev >= 0 else "marginal" if ev >= -1e-3 else "unstable"
            print(f"| {name} | {hf:g} | {100 * ev:+.2f} % | ({', '.join(f'{c:.2f}' for c in k)}) | {verdict} |")


if __name__ == "__main__":
    main()
