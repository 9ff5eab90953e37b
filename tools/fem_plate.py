#!/usr/bin/env python3
"""FEM reference for a 2D plane-strain elastic plate (cantilever) clamped at x = 0.

Domain 0 <= x <= L, -H/2 <= y <= H/2; isotropic linear elasticity, plane strain,
lambda = K - 2G/3, mu = G (K, G are the 3D moduli); density rho.
Clamp: u = v = 0 at every node of the edge x = 0 (no Poisson contraction there);
all other edges traction-free.

Discretisation: uniform structured mesh of 9-node Lagrange quadrilaterals (Q9,
biquadratic), nthick elements through the thickness and nthick*round(L/H) along
x (aspect ratio ~1), 3x3 Gauss quadrature for stiffness, consistent mass and
consistent body-force vector.  Linear algebra uses numpy only: with x-major dof
numbering the reduced stiffness is banded, so it is stored block-tridiagonally
(block size = bandwidth) and factored by block Cholesky.

Computed for each mesh:
  1. T1 = 2 pi / omega_1, the lowest eigenpair of K u = omega^2 M u
     (subspace inverse iteration + Rayleigh-Ritz), which is the first bending mode;
  2. static deflection under a uniform body force rho*g in -y (line load
     q = rho g H): v at (L, 0) and the mean v over the edge x = L.
Compared with Euler-Bernoulli (E' = E/(1-nu^2), I = H^3/12, kL = 1.875104069,
v_EB = q L^4/(8 E' I)), with EB + Timoshenko shear term q L^2/(2 kappa G H), and a
Timoshenko-beam period (1D FE, 400 linear elements, reduced-integrated shear,
rotary inertia, kappa = 5/6).  The last three meshes (successive halving) give a
Richardson extrapolation with observed order p; err = |extrapolated - finest|.
"""
import os
for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")
import argparse
import time
import numpy as np

GP = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
GW = np.array([5.0, 8.0, 5.0]) / 9.0


def shape1d(s):
    return (np.array([s * (s - 1) / 2, 1 - s * s, s * (s + 1) / 2]),
            np.array([s - 0.5, -2 * s, s + 0.5]))


def element_matrices(dx, dy, lam, mu, rho):
    """Q9 stiffness, consistent mass and unit body-force (per rho*g, -y) vectors.
    Local node a = 3*ia + ja (ia along x, ja along y); dofs (u, v) per node."""
    D = np.array([[lam + 2 * mu, lam, 0], [lam, lam + 2 * mu, 0], [0, 0, mu]])
    Ke, Me, fe = np.zeros((18, 18)), np.zeros((18, 18)), np.zeros(18)
    detJ = dx * dy / 4
    for xi, wx in zip(GP, GW):
        Nx1, dNx1 = shape1d(xi)
        for eta, wy in zip(GP, GW):
            Ny1, dNy1 = shape1d(eta)
            N = np.outer(Nx1, Ny1).ravel()
            Nx = np.outer(dNx1, Ny1).ravel() * 2 / dx
            Ny = np.outer(Nx1, dNy1).ravel() * 2 / dy
            B = np.zeros((3, 18))
            B[0, 0::2], B[1, 1::2] = Nx, Ny
            B[2, 0::2], B[2, 1::2] = Ny, Nx
            w = wx * wy * detJ
            Ke += w * B.T @ D @ B
            NN = w * rho * np.outer(N, N)
            Me[0::2, 0::2] += NN
            Me[1::2, 1::2] += NN
            fe[1::2] -= w * rho * N
    return Ke, Me, fe


class BlockTri:
    """Symmetric banded matrix stored as block-tridiagonal (diag D[k], sub S[k])."""

    def __init__(self, r, c, v, n, nb, pad_diag):
        self.n, self.nb = n, nb
        self.nblk = -(-n // nb)
        br, bc = r // nb, c // nb
        nbb = nb * nb
        size = self.nblk * nbb
        m = br == bc
        self.D = np.bincount(br[m] * nbb + (r[m] % nb) * nb + c[m] % nb, v[m],
                             size).reshape(self.nblk, nb, nb)
        m = br == bc + 1
        self.S = np.bincount(br[m] * nbb + (r[m] % nb) * nb + c[m] % nb, v[m],
                             size).reshape(self.nblk, nb, nb)
        for i in range(n, self.nblk * nb):      # padding dofs
            self.D[-1, i % nb, i % nb] = pad_diag

    def matvec(self, X):                         # X: (nblk, nb, m)
        Y = self.D @ X
        Y[1:] += self.S[1:] @ X[:-1]
        Y[:-1] += np.swapaxes(self.S[1:], 1, 2) @ X[1:]
        return Y

    def factor(self):
        self.Li, self.Ls = np.zeros_like(self.D), np.zeros_like(self.S)
        eye = np.eye(self.nb)
        for k in range(self.nblk):
            A = self.D[k].copy()
            if k > 0:
                self.Ls[k] = self.S[k] @ self.Li[k - 1].T
                A -= self.Ls[k] @ self.Ls[k].T
            self.Li[k] = np.linalg.solve(np.linalg.cholesky(A), eye)

    def solve(self, B):
        Y = np.empty_like(B)
        Y[0] = self.Li[0] @ B[0]
        for k in range(1, self.nblk):
            Y[k] = self.Li[k] @ (B[k] - self.Ls[k] @ Y[k - 1])
        X = np.empty_like(B)
        X[-1] = self.Li[-1].T @ Y[-1]
        for k in range(self.nblk - 2, -1, -1):
            X[k] = self.Li[k].T @ (Y[k] - self.Ls[k + 1].T @ X[k + 1])
        return X


def ritz(K, M, Y):
    """Rayleigh-Ritz on block vectors Y (nblk, nb, p): eigenvalues, new basis."""
    Yf = Y.reshape(-1, Y.shape[2])
    Kr = Yf.T @ K.matvec(Y).reshape(Yf.shape)
    Mr = Yf.T @ M.matvec(Y).reshape(Yf.shape)
    Lm = np.linalg.cholesky(Mr)
    Lmi = np.linalg.solve(Lm, np.eye(len(Lm)))
    lam, Q = np.linalg.eigh(Lmi @ Kr @ Lmi.T)
    return lam, (Yf @ (Lmi.T @ Q)).reshape(Y.shape)


def solve_plate(L, H, rho, lam, mu, g, nthick):
    ny, nx = nthick, max(1, int(round(L / H))) * nthick   # nested meshes
    nyn, nxn = 2 * ny + 1, 2 * nx + 1
    Ke, Me, fe = element_matrices(L / nx, H / ny, lam, mu, rho)
    ex, ey = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    ia, ja = np.meshgrid(np.arange(3), np.arange(3), indexing="ij")
    nodes = ((2 * ex.ravel()[:, None] + ia.ravel()) * nyn
             + 2 * ey.ravel()[:, None] + ja.ravel())          # (nel, 9)
    edof = np.stack([2 * nodes, 2 * nodes + 1], axis=2).reshape(-1, 18)
    edof = edof - 2 * nyn                  # clamped column i = 0 -> negative
    n = 2 * nyn * nxn - 2 * nyn
    r = np.repeat(edof, 18, axis=1).ravel()
    c = np.tile(edof, (1, 18)).ravel()
    keep = (r >= 0) & (c >= 0)
    r, c = r[keep], c[keep]
    nb = int(np.max(np.abs(r - c))) + 1
    kv = np.tile(Ke.ravel(), len(edof))[keep]
    mv = np.tile(Me.ravel(), len(edof))[keep]
    K = BlockTri(r, c, kv, n, nb, 1.0)
    M = BlockTri(r, c, mv, n, nb, 0.0)
    f = np.zeros(K.nblk * nb)
    ed = edof.ravel()
    okf = ed >= 0
    np.add.at(f, ed[okf], (g * np.tile(fe, len(edof)))[okf])
    K.factor()
    # static deflection
    u = K.solve(f.reshape(K.nblk, nb, 1)).ravel()
    tip = (2 * nx * nyn + ny) * 2 + 1 - 2 * nyn
    wy = np.zeros(nyn)                      # Simpson weights along x = L
    for e in range(ny):
        wy[2 * e:2 * e + 3] += np.array([1, 4, 1]) * (H / ny) / 6
    vedge = u[(2 * nx * nyn + np.arange(nyn)) * 2 + 1 - 2 * nyn]
    # lowest eigenpair: subspace inverse iteration
    rng = np.random.default_rng(0)
    Y = rng.standard_normal((K.nblk, nb, 4))
    Y.reshape(-1, 4)[n:] = 0
    Y[..., 0] = M.matvec(f.reshape(K.nblk, nb, 1))[..., 0]  # static shape ~ mode 1
    lam_old = np.inf
    for it in range(100):
        Y = K.solve(M.matvec(Y))
        lam_r, Y = ritz(K, M, Y)
        if abs(lam_r[0] - lam_old) < 1e-13 * lam_r[0]:
            break
        lam_old = lam_r[0]
    return dict(nthick=ny, nx=nx, ndof=n, T1=2 * np.pi / np.sqrt(lam_r[0]),
                vtip=u[tip], vmean=wy @ vedge / H, iters=it + 1)


def timoshenko_period(L, H, rho, Ep, G, kappa=5 / 6, ne=400):
    """First period of a clamped-free Timoshenko beam (per unit width), 1D FE."""
    A, I, h = H, H ** 3 / 12, L / ne
    n = 2 * (ne + 1)
    Kg, Mg = np.zeros((n, n)), np.zeros((n, n))
    # dofs per node (w, theta); gamma = w' - theta, reduced 1-point for shear
    Bs = np.array([-1 / h, -0.5, 1 / h, -0.5])
    Bb = np.array([0, -1 / h, 0, 1 / h])
    ke = Ep * I * h * np.outer(Bb, Bb) + kappa * G * A * h * np.outer(Bs, Bs)
    m1 = np.array([[2, 1], [1, 2]]) * h / 6
    me = np.zeros((4, 4))
    me[np.ix_([0, 2], [0, 2])] = rho * A * m1
    me[np.ix_([1, 3], [1, 3])] = rho * I * m1
    for e in range(ne):
        d = np.arange(2 * e, 2 * e + 4)
        Kg[np.ix_(d, d)] += ke
        Mg[np.ix_(d, d)] += me
    Kg, Mg = Kg[2:, 2:], Mg[2:, 2:]
    Lm = np.linalg.cholesky(Mg)
    Li = np.linalg.solve(Lm, np.eye(len(Lm)))
    w2 = np.linalg.eigvalsh(Li @ Kg @ Li.T)[0]
    return 2 * np.pi / np.sqrt(w2)


def richardson(vals):
    f1, f2, f3 = vals[-3:]
    with np.errstate(all="ignore"):
        p = np.log2((f1 - f2) / (f2 - f3))
    if not np.isfinite(p) or p < 0.5:
        return f3, abs(f3 - f2), p
    fx = f3 + (f3 - f2) / (2 ** p - 1)
    return fx, abs(fx - f3), p


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--L", type=float, default=0.2)
    ap.add_argument("--H", type=float, default=0.02)
    ap.add_argument("--rho", type=float, default=1000.0)
    ap.add_argument("--K", type=float, default=3.25e6)
    ap.add_argument("--G", type=float, default=7.15e5)
    ap.add_argument("--g", type=float, default=1.0)
    ap.add_argument("--nthick", type=int, nargs="+", default=[2, 4, 8, 16])
    a = ap.parse_args()
    L, H, rho, K, G, g = a.L, a.H, a.rho, a.K, a.G, a.g
    lam, mu = K - 2 * G / 3, G
    E = 9 * K * G / (3 * K + G)
    nu = (3 * K - 2 * G) / (2 * (3 * K + G))
    Ep, I, q, kap = E / (1 - nu ** 2), H ** 3 / 12, rho * g * H, 5 / 6
    T_eb = 2 * np.pi / np.sqrt(Ep * H ** 2 * (1.875104069 / L) ** 4 / (12 * rho))
    v_eb = q * L ** 4 / (8 * Ep * I)
    v_ts = v_eb + q * L ** 2 / (2 * kap * G * H)
    T_ts = timoshenko_period(L, H, rho, Ep, G, kap)
    print(f"L={L} H={H} L/H={L / H:.4g} rho={rho} K={K:.4g} G={G:.4g} g={g}")
    print(f"E={E:.6g} nu={nu:.6f} E'={Ep:.6g} lambda={lam:.6g} q=rho*g*H={q:.6g} N/m")
    print(f"T_EB={T_eb:.6g} s  T_Timoshenko={T_ts:.6g} s (T_Ti/T_EB={T_ts / T_eb:.5f})")
    print(f"v_EB={-v_eb:.6g} m  v_EB+shear={-v_ts:.6g} m (ratio {v_ts / v_eb:.5f})")
    hdr = (f"{'nthick':>6} {'nx':>5} {'ndof':>7} {'T1 [s]':>12} {'T1/T_EB':>9} "
           f"{'T1/T_Ti':>9} {'v_tip [m]':>13} {'v/v_EB':>8} {'v/v_EBs':>8} "
           f"{'vmean/v_EB':>10} {'t[s]':>6}")
    print(hdr)
    res = []
    for nt in a.nthick:
        t0 = time.time()
        r = solve_plate(L, H, rho, lam, mu, g, nt)
        res.append(r)
        print(f"{r['nthick']:6d} {r['nx']:5d} {r['ndof']:7d} {r['T1']:12.7g} "
              f"{r['T1'] / T_eb:9.6f} {r['T1'] / T_ts:9.6f} {r['vtip']:13.7g} "
              f"{-r['vtip'] / v_eb:8.5f} {-r['vtip'] / v_ts:8.5f} "
              f"{-r['vmean'] / v_eb:10.5f} {time.time() - t0:6.1f}")
    if len(res) >= 3:
        for key, ref, name in (("T1", T_eb, "T1"), ("vtip", -v_eb, "v_tip"),
                               ("vmean", -v_eb, "v_mean")):
            fx, err, p = richardson([r[key] for r in res])
            print(f"extrap {name:6s} = {fx:.7g} +- {err:.2g} (rel {abs(err / fx):.1e},"
                  f" order p={p:.2f}); /EB = {fx / ref:.5f}"
                  + (f"; /T_Ti = {fx / T_ts:.5f}" if key == "T1" else
                     f"; /(EB+shear) = {fx / ref * v_eb / v_ts:.5f}"))


if __name__ == "__main__":
    main()
