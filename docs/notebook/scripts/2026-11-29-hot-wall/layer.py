#!/usr/bin/python3
"""Python port of transport/wall_layer.cpp (solve_wall_layer), 2D, the default cavity's fluid.

Inputs as tests/transport/wall_layer_test.cpp's default_wall() and study/twin_wall_theory.cpp:
  kappa_pair = 0.262 n^2  (n^2/4 lambda int r^2 w_H d^2r, g = 1, 000:(3.25); lambda = 10)
  D = 0.263 (T/0.814)^1.36 (4/n)  (measured D at the state point, its T power, 1/n)
  lambda = kappa0 c_v^2 = 10, c_v = 10, w_H = w_D = (1-r)^2, rc = 1, rho_w = 4,
  gamma = sigma^2/(2 T) = 9/(2T), no-slip wall (friction's full Volume moment).
Run single-threaded (numpy dense solve, N ~ 500)."""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import math
from functools import lru_cache
import numpy as np
from scipy.integrate import quad

# ---------------------------------------------------------------- half-space integrals (2D, rc=1)
@lru_cache(maxsize=None)
def half_space(h, e=2.0, moment="vol"):
    """int over {z > h} of (1-r)^e m(e) d^2r about a point at distance h (rc = 1)."""
    h = round(h, 12)
    if h >= 1:
        return 0.0
    def f(r):
        a = math.acos(min(1.0, h / r)) if r > 0 else math.pi / 2
        if moment == "vol":
            ang = 2 * a
        elif moment == "n2":
            ang = a + 0.5 * math.sin(2 * a)
        else:  # t2
            ang = a - 0.5 * math.sin(2 * a)
        return (1 - r) ** e * ang * r
    return quad(f, h, 1.0, epsabs=1e-13, epsrel=1e-11, limit=200)[0]


def plane_kernel(dh, e=2.0, moment="vol"):
    reach = int(math.ceil(1.0 / dh))
    k = np.zeros(reach + 1)
    for d in range(1, reach + 1):
        k[d] = (half_space(max(d * dh - dh / 2, 0.0), e, moment) - half_space(d * dh + dh / 2, e, moment)) / dh
    return k


# ---------------------------------------------------------------- inputs
LAMBDA, CV, RHO_W, SIGMA = 10.0, 10.0, 4.0, 3.0


def default_inputs(n, T, kappa, f):
    return dict(n=n, T=T, kappa=kappa, kappa_pair=0.262 * n * n,
                D=0.263 * (T / 0.814) ** 1.36 * (4 / n), lam=LAMBDA, cv=CV,
                rho_w=RHO_W, f=f, gamma=SIGMA ** 2 / (2 * T), no_slip=True)


HOT = (2.8, 1.4, 21.0)
COLD = (6.3, 0.6, 20.4)
FS = [1, 3, 10, 30, 100]
MEAS_HOT = [(0.79, 0.10), (0.49, 0.06), (0.31, 0.10), (0.29, 0.09), (0.05, 0.06)]
MEAS_COLD = [(0.25, 0.05), (-0.03, 0.05), (-0.34, 0.05), (-0.42, 0.02), (-0.47, 0.05)]
CPP_HOT = [0.56, 0.38, 0.18, 0.05, -0.06]
CPP_COLD = [0.24, 0.02, -0.20, -0.34, -0.46]


def tau_u(p):
    rate = p["n"] * p["lam"] * half_space(0.0) * 2  # n lambda int w_H d^2r
    return p["cv"] / rate


def energy_length(p):
    return math.sqrt(max(p["D"], 1e-12) * min(tau_u(p), 1e6))


def grid_for(ell, rc=1.0):
    ell = max(ell, 1e-3)
    dh = max(min(0.02 * rc, ell / 10), 0.005 * rc)
    H = max(8 * rc, 14 * ell)
    N = int(math.ceil(H / dh))
    return dh, H, N


class System:
    """A theta = rhs, theta = T - T_w per cell, far gradient g = 1 continued past the end."""

    def __init__(self, N, dh):
        self.N, self.dh = N, dh
        self.A = np.zeros((N, N))
        self.rhs = np.zeros(N)
        self.h = (np.arange(N) + 0.5) * dh

    def exchange_band(self, d, c):
        """exchange between every k and k + d at conductance c (scalar or array over k)."""
        N, dh = self.N, self.dh
        c = np.broadcast_to(np.asarray(c, float), (N,)).copy()
        k = np.arange(N)
        inside = k + d < N
        ki, li = k[inside], k[inside] + d
        ci = c[inside]
        self.A[ki, ki] -= ci
        self.A[ki, li] += ci
        self.A[li, li] -= ci
        self.A[li, ki] += ci
        ko = k[~inside]
        co = c[~inside]
        self.A[ko, ko] -= co
        self.A[ko, N - 1] += co
        self.rhs[ko] -= co * ((ko + d) - (N - 1)) * dh

    def solve(self):
        return np.linalg.solve(self.A, self.rhs)


def extrapolation_length(theta, h, H, ell, rc=1.0):
    margin = max(2 * rc, 4 * ell)
    m = (h >= margin) & (h <= H - margin)
    slope, icpt = np.polyfit(h[m], theta[m], 1)
    return icpt / slope


def solve_wall_layer(p, ell=None, return_profile=False):
    """The C++ balance, verbatim."""
    if ell is None:
        ell = energy_length(p)
    dh, H, N = grid_for(ell)
    n = p["n"]
    sys_ = System(N, dh)
    h = sys_.h
    kern = plane_kernel(dh)
    pair_scale = n * n * p["lam"] * dh * dh
    for d in range(1, len(kern)):
        sys_.exchange_band(d, pair_scale * kern[d])
    kp = p["kappa"] - p["kappa_pair"]
    a_kin = kp / (2 * ell ** 3) * dh * dh
    for d in range(1, int(math.ceil(14 * ell / dh)) + 1):
        sys_.exchange_band(d, a_kin * math.exp(-d * dh / ell))
    # to the wall
    c = kp / (2 * ell * ell) * np.exp(-h / ell) * dh
    Wh = np.array([half_space(x) for x in h])
    c += n * dh * p["f"] * p["lam"] * p["rho_w"] * Wh
    Wf = Wh if p["no_slip"] else np.array([half_space(x, 2.0, "n2") for x in h])
    c += n * dh * 0.25 * p["gamma"] * p["rho_w"] * Wf
    sys_.A[np.arange(N), np.arange(N)] -= c
    theta = sys_.solve()
    b = extrapolation_length(theta, h, H, ell)
    if return_profile:
        return b, h, theta
    return b


def chi2(bs, meas):
    return sum(((b - m) / e) ** 2 for b, (m, e) in zip(bs, meas))


def table(label, fn):
    """fn(p) -> b for the 10 entries; prints the table and chi^2."""
    hot = [fn(default_inputs(*HOT, f)) for f in FS]
    cold = [fn(default_inputs(*COLD, f)) for f in FS]
    print(f"\n## {label}")
    print("| f | hot meas | hot b | (b-m)/err | cold meas | cold b | (b-m)/err |")
    print("|---|---|---|---|---|---|---|")
    for f, bh, bc, mh, mc in zip(FS, hot, cold, MEAS_HOT, MEAS_COLD):
        print(f"| {f} | {mh[0]:+.2f} +- {mh[1]:.2f} | {bh:+.3f} | {(bh-mh[0])/mh[1]:+.1f} "
              f"| {mc[0]:+.2f} +- {mc[1]:.2f} | {bc:+.3f} | {(bc-mc[0])/mc[1]:+.1f} |")
    print(f"chi^2 hot {chi2(hot, MEAS_HOT):.1f}, cold {chi2(cold, MEAS_COLD):.1f} (5 points each)")
    return hot, cold


if __name__ == "__main__":
    for name, st in (("hot", HOT), ("cold", COLD)):
        p = default_inputs(*st, 1)
        print(f"{name}: n {p['n']}, T {p['T']}, kappa {p['kappa']}, kappa_pair {p['kappa_pair']:.3f}, "
              f"D {p['D']:.4f}, tau_u {tau_u(p):.4f}, ell {energy_length(p):.4f}, gamma {p['gamma']:.3f}")
    hot, cold = table("C++ port (baseline)", solve_wall_layer)
    print("C++ table hot ", CPP_HOT, "\nC++ table cold", CPP_COLD)
    print("max |port - table|: hot %.3f cold %.3f" % (
        max(abs(a - b) for a, b in zip(hot, CPP_HOT)), max(abs(a - b) for a, b in zip(cold, CPP_COLD))))
