#!/usr/bin/python3
"""Full 20 rc wall slab, both walls, the wall-layer balance with state-dependent carriers.
Channels as transport/wall_layer.cpp (port: layer.py), but solved across the whole slab at the
measured profile's state (n(x), T(x) from the run's fields.csv, kappa(x) = q / |dT/dx| of the
central-60% parabola, kappa_p(x) = kappa(x) - 0.262 n(x)^2, D(x), tau_u(x), ell(x) = sqrt(D tau_u)).
Carrier kernels (exchange C_ij between cells i, j; symmetric, so energy is conserved):
  'path' : a_i a_j exp(-|tau_i - tau_j|), tau(x) = int_0^x ds/ell(s) (optical depth),
           a = sqrt(kappa_p / (2 ell^3)): the WKB Green's function of (D G')' - G/tau_u; local bulk
           conductivity = kappa_p(x) (checked numerically, see conductivity_check)
  'local': cand_b-like: ((kp_i + kp_j)/2) / (2 el^3) exp(-|x_i - x_j| / el), el = (ell_i + ell_j)/2
  'const': one ell and kappa_p per side (hot half/cold half: the wall's values), Laplace
           (reproduces the built theory's two half-space layers superposed)
Wall exchange of the carriers: the wall is a reservoir continuing the plane's state:
  a_i a_w ell_w exp(-tau_i) (tau to that wall). Wall pair conduction and friction with local n(x).
b read as extract_b/predict.slab_reading: 0.5 rc bins, parabola over [1, L-1] carried to the
planes, over |slope| at the centre of the central-60% parabola."""
import os, sys, json, math
os.environ.setdefault("OMP_NUM_THREADS", "1"); os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "2026-11-29-hot-wall"))
sys.path.insert(0, os.path.join(HERE, "..", "2026-11-29-cv-slabs"))
import numpy as np
import layer as L
import extract_b as E

W0 = 2 * L.half_space(0.0)  # int w_H d^2r


def state_from_run(run):
    o = E.analyse(run)
    fl = E.read_fields(os.path.dirname(o["summary"]))
    x = fl["x"]; idx = np.argsort(x)
    x = x[idx]; T = fl["T_internal"][idx]; Tse = fl["T_internal_se"][idx]; n = fl["density"][idx]
    Lx = o["length"]; c = Lx / 2
    mm = (x >= 0.2 * Lx) & (x <= 0.8 * Lx)
    cm, covm = E.wfit(x[mm], T[mm], Tse[mm], 2, c)
    q = abs(o["q"])
    return dict(o=o, x=x, T=T, n=n, L=Lx, cv=o["cv"], f=o["f"], q=q, cm=cm,
                nh=o["walls"]["hot"]["n_1_2"], nc=o["walls"]["cold"]["n_1_2"],
                Th=o["T_lower"], Tc=o["T_upper"])


def fields_on(st, xg, n_mode="measured"):
    x, T, n = st["x"], st["T"], st["n"]
    if "uniform" in st:  # validation: (n, T, kappa) everywhere
        un, uT, uk = st["uniform"]
        ng = np.full(len(xg), un); Tg = np.full(len(xg), uT)
        D = 0.263 * (Tg / 0.814) ** 1.36 * (4 / ng); tu = st["cv"] / (ng * 10.0 * W0)
        return dict(T=Tg, n=ng, kappa=np.full(len(xg), uk), kp=uk - 0.262 * ng ** 2, D=D, tu=tu, ell=np.sqrt(D * tu))
    Tg = np.interp(xg, x, T)
    if n_mode == "measured":
        ng = np.interp(xg, x, n)
        ng = np.where(xg < 1.0, st["nh"], ng)
        ng = np.where(st["L"] - xg < 1.0, st["nc"], ng)
    elif n_mode == "isobar":  # n = p/T through the walls' 1-2 rc densities, linear blend of the two p's
        ph, pc = st["nh"] * np.interp(1.5, x, T), st["nc"] * np.interp(st["L"] - 1.5, x, T)
        p = ph + (pc - ph) * xg / st["L"]
        ng = p / Tg
    c = st["L"] / 2
    dTdx = np.abs(2 * st["cm"][0] * (xg - c) + st["cm"][1])
    kap = st["q"] / dTdx
    kpair = 0.262 * ng ** 2
    kp = kap - kpair
    D = 0.263 * (Tg / 0.814) ** 1.36 * (4 / ng)
    tu = st["cv"] / (ng * 10.0 * W0)
    ell = np.sqrt(D * tu)
    return dict(T=Tg, n=ng, kappa=kap, kp=kp, D=D, tu=tu, ell=ell)


def solve_slab(st, kernel="path", dx=0.01, n_mode="measured", ell_scale=1.0, ell_override=None,
               const_sides=None):
    Lx = st["L"]; N = int(round(Lx / dx)); xg = (np.arange(N) + 0.5) * dx
    F = fields_on(st, xg, n_mode)
    n, kp, ell = F["n"], F["kp"].copy(), F["ell"] * ell_scale
    if ell_override is not None:
        ell = np.full(N, ell_override)
    if const_sides is not None:  # (ell_h, kp_h, ell_c, kp_c): each half at its wall's values
        eh, kh, ec, kc = const_sides
        left = xg < Lx / 2
        ell = np.where(left, eh, ec); kp = np.where(left, kh, kc)
    A = np.zeros((N, N)); rhs = np.zeros(N)
    # pair conduction, n_i n_j lambda k_H
    kern = L.plane_kernel(dx)
    for d in range(1, len(kern)):
        i = np.arange(N - d); j = i + d
        c = n[i] * n[j] * 10.0 * dx * dx * kern[d]
        A[i, i] -= c; A[j, j] -= c; A[i, j] += c; A[j, i] += c
    # carriers
    X = xg[:, None] - xg[None, :]
    if kernel == "path" or const_sides is not None and kernel == "path":
        tau = np.concatenate([[0], np.cumsum(dx / ell)])  # at faces
        tc = 0.5 * (tau[:-1] + tau[1:])
        a = np.sqrt(kp / (2 * ell ** 3))
        C = a[:, None] * a[None, :] * np.exp(-np.abs(tc[:, None] - tc[None, :])) * dx * dx
        # wall exchange: hot wall at x=0, cold at x=L; the wall continues the plane's state
        ah, eh = math.sqrt(kp[0] / (2 * ell[0] ** 3)), ell[0]
        ac, ec = math.sqrt(kp[-1] / (2 * ell[-1] ** 3)), ell[-1]
        wh = a * ah * eh * np.exp(-tc) * dx
        wc = a * ac * ec * np.exp(-(tau[-1] - tc)) * dx
    elif kernel == "arith":  # ell_ij = arithmetic mean of ell along the path (long ell weighted)
        Ic = np.concatenate([[0], np.cumsum(ell * dx)]); ic = 0.5 * (Ic[:-1] + Ic[1:])
        dist = np.abs(X); el = np.where(dist > 0, np.abs(ic[:, None] - ic[None, :]) / np.maximum(dist, 1e-300), ell[:, None])
        kk = np.sqrt(kp[:, None] * kp[None, :])
        C = kk / (2 * el ** 3) * np.exp(-dist / el) * dx * dx
        elh = np.maximum(ic, 1e-12) / xg; elc = (Ic[-1] - ic) / (Lx - xg)
        wh = np.sqrt(kp * kp[0]) / (2 * elh ** 2) * np.exp(-xg / elh) * dx
        wc = np.sqrt(kp * kp[-1]) / (2 * elc ** 2) * np.exp(-(Lx - xg) / elc) * dx
    elif kernel == "local":
        el = 0.5 * (ell[:, None] + ell[None, :]); kk = 0.5 * (kp[:, None] + kp[None, :])
        C = kk / (2 * el ** 3) * np.exp(-np.abs(X) / el) * dx * dx
        wh = kp / (2 * ell ** 2) * np.exp(-xg / ell) * dx
        wc = kp / (2 * ell ** 2) * np.exp(-(Lx - xg) / ell) * dx
    np.fill_diagonal(C, 0.0)
    A += C; A[np.arange(N), np.arange(N)] -= C.sum(1)
    # wall pair conduction and friction, local n; gamma at the wall's T
    h_h, h_c = xg, Lx - xg
    Wh = np.array([L.half_space(h) for h in h_h]); Wc = np.array([L.half_space(h) for h in h_c])
    wh = wh + n * dx * st["f"] * 10.0 * 4.0 * Wh + n * dx * 0.25 * (9 / (2 * st.get("gTh", st["Th"]))) * 4.0 * Wh
    wc = wc + n * dx * st["f"] * 10.0 * 4.0 * Wc + n * dx * 0.25 * (9 / (2 * st.get("gTc", st["Tc"]))) * 4.0 * Wc
    A[np.arange(N), np.arange(N)] -= wh + wc
    rhs -= wh * st["Th"] + wc * st["Tc"]
    Tsol = np.linalg.solve(A, rhs)
    return xg, Tsol, F, ell


def read_b(xg, Tsol, Lx, Th, Tc, bw=0.5):
    nb = int(round(Lx / bw)); xb = (np.arange(nb) + 0.5) * bw
    Tb = np.array([Tsol[(xg >= x - bw / 2) & (xg < x + bw / 2)].mean() for x in xb])
    c = Lx / 2
    m = (xb >= 1.0) & (xb <= Lx - 1.0)
    pb = np.polyfit(xb[m] - c, Tb[m], 2)
    mm = (xb >= 0.2 * Lx) & (xb <= 0.8 * Lx)
    pm = np.polyfit(xb[mm] - c, Tb[mm], 2)
    s = abs(pm[1])
    return (Th - np.polyval(pb, -c)) / s, (np.polyval(pb, c) - Tc) / s, s


def conductivity_check(st, dx=0.01, n_mode="measured"):
    """the path kernel's local conductivity (flux through plane x0 under a unit gradient, kernel only,
    infinite-medium continuation ignored) against kappa_p(x0) at points away from the walls."""
    Lx = st["L"]; N = int(round(Lx / dx)); xg = (np.arange(N) + 0.5) * dx
    F = fields_on(st, xg, n_mode); ell, kp = F["ell"], F["kp"]
    tau = np.concatenate([[0], np.cumsum(dx / ell)]); tc = 0.5 * (tau[:-1] + tau[1:])
    a = np.sqrt(kp / (2 * ell ** 3))
    out = []
    for x0 in (4.0, 7.0, 10.0, 13.0, 16.0):
        k0 = int(x0 / dx)
        i = np.arange(k0); j = np.arange(k0, N)
        C = a[i][:, None] * a[j][None, :] * np.exp(-np.abs(tc[i][:, None] - tc[j][None, :])) * dx * dx
        flux = (C * (xg[j][None, :] - xg[i][:, None])).sum()
        out.append((x0, flux, kp[k0]))
    return out
