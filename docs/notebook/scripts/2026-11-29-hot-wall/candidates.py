#!/usr/bin/python3
"""Candidates for the hot wall's missing resistance, on the C++ wall layer's balance (layer.py).

General solver: the pair channel, the wall's pair conduction and friction as in the C++; the
particles' channel as one or more carrier channels, each a symmetric exchange kernel with a
given shape (a normalised density K(s) given by its tail G(x) = int_x^inf K), its bulk
conductivity fixed exactly on the grid, the part reaching beyond the plane going to the wall at
T_w (diffuse re-emission resets the carrier).
"""
import os
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
import math
import numpy as np
from scipy.special import erfc
import layer as L

ZETA_W = 2 * L.half_space(0.0, 2.0, "t2")  # int w_D (e.t)^2 d^2r = pi/12


def zeta_mf(p):
    """mean-field friction rate per velocity component (002:(17)), m = 1."""
    return p["n"] * p["gamma"] * ZETA_W


# ------------------------------------------------------------------ kernel tails G(x), x >= 0
def tail_laplace(ell):
    return lambda x: 0.5 * np.exp(-np.asarray(x) / ell)


_U = np.concatenate([np.geomspace(1e-7, 1e-2, 600), np.linspace(1e-2, 60, 6000)[1:]])
_WU = np.gradient(_U) * np.exp(-_U)  # int e^-u du weights (u = t / tau_u)
_WU /= _WU.sum()


def tail_ou(tau_u, tau_v, Dv):
    """deposit kernel of an OU walker (velocity relaxation tau_v, long-time diffusion Dv, started
    from the stationary Maxwellian) whose label relaxes at rate 1/tau_u:
    K(s) = int dt e^{-t/tau_u}/tau_u N(s; 0, sigma^2(t)), sigma^2 = 2 Dv (t - tau_v (1 - e^{-t/tau_v}))."""
    t = _U * tau_u
    if tau_v > 0:
        s2 = 2 * Dv * (t - tau_v * (-np.expm1(-t / tau_v)))
    else:
        s2 = 2 * Dv * t
    sig = np.sqrt(np.maximum(s2, 1e-300))

    def G(x):
        x = np.atleast_1d(np.asarray(x, float))
        return (0.5 * erfc(x[:, None] / (sig[None, :] * math.sqrt(2))) * _WU[None, :]).sum(1)
    var = float((s2 * _WU).sum())
    return G, var


# ------------------------------------------------------------------ general solver
def shift(a, d):
    """a[k + d], the last value continued past the end."""
    N = len(a)
    d = min(d, N)
    return np.concatenate([a[d:], np.full(d, a[-1])])


def solve(p, carriers, lam_scale=1.0, return_profile=False, dh=None, H=None, local=None):
    """carriers: list of (kappa_c, G, length) with G the kernel tail, length its scale (for reach).
    lam_scale scales the pair conductance in the pair channel and the wall's pair conduction.
    local: optional dict of per-cell factors (n, gamma) for candidate (b)."""
    ellmax = max(c[2] for c in carriers) if carriers else 0.1
    ellmin = min(c[2] for c in carriers) if carriers else 0.1
    if dh is None:
        dh = max(min(0.02, ellmin / 10), 0.005)
    if H is None:
        H = max(8.0, 14 * ellmax)
    N = int(math.ceil(H / dh))
    S = L.System(N, dh)
    h = S.h
    n = p["n"]
    nk = np.full(N, n) if local is None else local["n"]
    kern = L.plane_kernel(dh)
    lam = p["lam"] * lam_scale
    for d in range(1, len(kern)):
        nn = nk * shift(nk, d)
        S.exchange_band(d, nn * lam * dh * dh * kern[d])
    wall = np.zeros(N)
    for kc, G, ell in carriers:
        reach = int(math.ceil(14 * ell / dh)) + 1
        x = (np.arange(reach + 2) - 0.5) * dh
        x[0] = 0
        Gx = G(x)
        e = dh * (Gx[1:-1] - Gx[2:])  # e[d-1]: point at a cell centre to cell d away
        dd = np.arange(1, reach + 1)
        kd = dh * (dd ** 2 * e).sum()  # discrete bulk conductivity of unit amplitude
        C = kc / kd
        if local is not None and "carrier_scale" in local:
            cs = local["carrier_scale"]
        else:
            cs = np.ones(N)
        for d in dd:
            cc = C * e[d - 1] * np.sqrt(cs * shift(cs, int(d)))
            S.exchange_band(int(d), cc)
        wall += C * cs * dh * G(h) / 1.0  # reach beyond the plane
    Wh = np.array([L.half_space(x) for x in h])
    gam = p["gamma"] if local is None else local["gamma"]
    wall += nk * dh * p["f"] * lam * p["rho_w"] * Wh
    wall += nk * dh * 0.25 * gam * p["rho_w"] * Wh  # no-slip: full friction moment
    S.A[np.arange(N), np.arange(N)] -= wall
    theta = S.solve()
    b = L.extrapolation_length(theta, h, H, ellmax)
    if return_profile:
        return b, h, theta
    return b


# ------------------------------------------------------------------ candidates
def base(p, lam_scale=1.0, kpair_scale=1.0):
    ell = L.energy_length(p)
    kp = p["kappa"] - kpair_scale * p["kappa_pair"]
    return solve(p, [(kp, tail_laplace(ell), ell)], lam_scale=lam_scale)


def cand_a_CE(p):
    """(a) translational kinetic energy as its own carriers: Chapman-Enskog of the OU (Fokker-
    Planck) velocity process with bath temperature T(x): the heat-flux moment v (v^2 - (d+2) T)
    is a 3rd-order Hermite eigenfunction, relaxing at 3 zeta, so kappa_tr = (d+2)/2 n T / (3 zeta)
    and its carriers' length sqrt(T) / (3 zeta) (ell^2 = kappa_tr/(n c_tr) * tau). Internal
    carriers keep ell = sqrt(D tau_u) and the rest of kappa - kappa_pair."""
    z = zeta_mf(p)
    d = 2
    ktr = (d + 2) / 2 * p["n"] * p["T"] / (3 * z)
    ltr = math.sqrt(p["T"]) / (3 * z)
    ell = L.energy_length(p)
    kp = p["kappa"] - p["kappa_pair"]
    return solve(p, [(kp - ktr, tail_laplace(ell), ell), (ktr, tail_laplace(ltr), ltr)])


def cand_a_cap(p):
    """(a') capacity split: every particle carries c_v (internal) + (d+2)/2 (translational, with
    the pressure work) per unit T with the same D; kappa - kappa_pair split 10 : 2. Internal
    carriers ell_u = sqrt(D tau_u); translational ones relax with the friction's energy rate
    2 zeta (000:(2.37), kinetic energy toward the pair's temperature): ell_tr = sqrt(D / (2 zeta))."""
    z = zeta_mf(p)
    ctr = 2.0
    kp = p["kappa"] - p["kappa_pair"]
    ktr = kp * ctr / (p["cv"] + ctr)
    ell = L.energy_length(p)
    ltr = math.sqrt(p["D"] / (2 * z))
    return solve(p, [(kp - ktr, tail_laplace(ell), ell), (ktr, tail_laplace(ltr), ltr)])


def cand_c_ou(p, which="measuredD"):
    """(c) the carriers' persistence: a carrier is a particle with an OU velocity, its label
    relaxing at 1/tau_u; the exchange kernel is its deposit kernel (a mixture of Gaussians over
    the exponential lifetime; Laplace in the diffusive limit, the free-flight E1-like kernel of a
    Maxwellian gas in the ballistic one, where 'kernel beyond the plane goes to the wall' is exact
    for a diffuse wall that resets the carrier). Amplitude from kappa - kappa_pair as in the C++.
      measuredD: tau_v = D / T (a walker whose long-time D is the measured D)
      meanfield: tau_v = 1/zeta_mf, Dv = T/zeta_mf (002:(17))
      samevar:   tau_v = D/T, but variance rescaled to the C++'s 2 D tau_u (shape effect only)"""
    tu = L.tau_u(p)
    if which == "measuredD":
        tv, Dv = p["D"] / p["T"], p["D"]
    elif which == "meanfield":
        z = zeta_mf(p)
        tv, Dv = 1 / z, p["T"] / z
    elif which == "samevar":
        tv = p["D"] / p["T"]
        Dv = p["D"] * (tu + tv) / tu
    G, var = tail_ou(tu, tv, Dv)
    ell_eq = math.sqrt(var / 2)
    kp = p["kappa"] - p["kappa_pair"]
    return solve(p, [(kp, G, max(ell_eq, math.sqrt(p["T"]) * tu))])


if __name__ == "__main__":
    # Milne constants of the kernel shapes (particles alone, no pair, no wall terms): b / sqrt(var/2)
    p0 = L.default_inputs(4.0, 1.0, 20.0, 0.0)
    p0.update(kappa_pair=0.0, lam=0.0, gamma=0.0)
    print("Milne problem of the carriers alone: b / sqrt(var/2)")
    for r in (0.0, 0.3, 1.0, 3.0, 30.0):
        tu, T = 1.0, 1.0
        tv = r * tu
        Dv = T * tv if tv > 0 else 1.0
        G, var = tail_ou(tu, tv, Dv)
        le = math.sqrt(var / 2)
        b = solve(p0, [(20.0, G, max(le, math.sqrt(T) * tu))], dh=le / 40, H=16 * max(le, tu))
        print(f"  tau_v/tau_u {r:5.1f}: ell_eq {le:.4f}, b {b:.4f}, b/ell_eq {b/le:.4f}")
    for name, st in (("hot", L.HOT), ("cold", L.COLD)):
        p = L.default_inputs(*st, 1)
        z = zeta_mf(p)
        print(f"{name}: zeta_mf {z:.3f}, tau_v(mf) {1/z:.3f}, tau_v(D/T) {p['D']/p['T']:.3f}, tau_u {L.tau_u(p):.3f}, "
              f"kappa_tr(CE) {2*p['n']*p['T']/(3*z):.3f}, l_tr {math.sqrt(p['T'])/(3*z):.3f}")
    L.table("baseline through the general solver (Laplace, cell-averaged kernel)", base)
    L.table("(c0) measured pair part: P = 1.25 x theory's (theory.md), same lambda elsewhere",
            lambda p: base(p, kpair_scale=1.25))
    L.table("(c0') lambda_eff = 1.25 lambda everywhere (pair channel, wall pair conduction, tau_u)",
            lambda p: solve(p, [(p['kappa'] - 1.25 * p['kappa_pair'],
                                 tail_laplace(L.energy_length(p) / math.sqrt(1.25)),
                                 L.energy_length(p) / math.sqrt(1.25))], lam_scale=1.25))
    L.table("(a) translational carriers, Chapman-Enskog split", cand_a_CE)
    L.table("(a') translational carriers, capacity split", cand_a_cap)
    L.table("(c1) OU carriers, tau_v = D/T", lambda p: cand_c_ou(p, "measuredD"))
    L.table("(c2) OU carriers, mean-field walker", lambda p: cand_c_ou(p, "meanfield"))
    L.table("(c3) OU carriers, C++ variance, OU shape", lambda p: cand_c_ou(p, "samevar"))
