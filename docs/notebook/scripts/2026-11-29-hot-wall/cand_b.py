#!/usr/bin/python3
"""(b) the layer's own profile: n and T vary across the layer on an isobar (n T = n_w T_w), D, tau_u,
ell, kappa's particle part, the pair channel's n^2, the wall terms' n and the friction's gamma(T)
with them, at the slab's gradient |dT/dh| ~ 0.8 / 20 = 0.04 (walls 1.4 / 0.6, 20 rc apart).
Laplace carriers as the C++ (ell_kl, amplitude: means of the two cells'). Nonlinear: fixed-point
passes on T(h). b as the measurement takes it: a parabola through the bulk beyond one cutoff,
its value at the plane over its slope at the slab's centre (10 rc from the wall)."""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
import math
import numpy as np
import layer as L
from candidates import shift

# kappa's particle part along the walls' states: K (T/T0)^a through the two walls' kappa - kappa_pair
KP_HOT = 21.0 - 0.262 * 2.8 ** 2
KP_COLD = 20.4 - 0.262 * 6.3 ** 2
A_K = math.log(KP_HOT / KP_COLD) / math.log(1.4 / 0.6)


def solve_b(p, g, sign, H=10.0, passes=6):
    n_w, T_w = p["n"], p["T"]
    P = n_w * T_w
    kp_w = p["kappa"] - p["kappa_pair"]
    ell_w = L.energy_length(p)
    dh = max(min(0.02, ell_w / 10), 0.005)
    N = int(math.ceil(H / dh))
    h = (np.arange(N) + 0.5) * dh
    T = np.full(N, T_w)
    kern = L.plane_kernel(dh)
    Wh = np.array([L.half_space(x) for x in h])
    for _ in range(passes):
        n = P / T
        D = p["D"] * (T / T_w) ** 1.36 * n_w / n
        tu = p["cv"] / (n * p["lam"] * 2 * L.half_space(0.0))
        ell = np.sqrt(D * tu)
        kp = kp_w * (T / T_w) ** A_K
        gam = 9 / (2 * T)
        S = L.System(N, dh)
        for d in range(1, len(kern)):
            S.exchange_band(d, n * shift(n, d) * p["lam"] * dh * dh * kern[d])
        for d in range(1, int(math.ceil(14 * ell.max() / dh)) + 1):
            el = 0.5 * (ell + shift(ell, d))
            kk = 0.5 * (kp + shift(kp, d))
            S.exchange_band(d, kk / (2 * el ** 3) * dh * dh * np.exp(-d * dh / el))
        wall = kp / (2 * ell ** 2) * np.exp(-h / ell) * dh
        wall += n * dh * p["f"] * p["lam"] * p["rho_w"] * Wh
        wall += n * dh * 0.25 * gam * p["rho_w"] * Wh
        S.A[np.arange(N), np.arange(N)] -= wall
        theta = S.solve()  # slope 1 far away
        T = T_w + sign * g * theta
    m = (h >= 1.0) & (h <= H - 0.5)
    c2, c1, c0 = np.polyfit(h[m], theta[m], 2)
    return c0 / (c1 + 2 * c2 * H)


if __name__ == "__main__":
    for g in (0.0, 0.04):
        L.table(f"(b) layer on the isobar, |dT/dh| = {g}",
                lambda p: solve_b(p, g, -1 if p["T"] > 1 else +1))
