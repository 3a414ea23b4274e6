#!/usr/bin/env python3
"""Slip per wall from particle/summary.json's poiseuille block, against the twin's kinetic slip
eta / beta(n, T), beta = 2 n [sqrt(m k T / 2 pi) + rho_w I_d gamma(T, T_w)] (continuum/parameters.hpp),
gamma = sigma^2/4 (1/T + 1/T_w), I_d = 0.02222 (w_D = (1 - r)^2, 2D), rho_w = 4, at the run's mean
T_kinetic and n; eta the half's own."""
import json, sys, math
for d in sys.argv[1:]:
    j = json.load(open(d + '/particle/summary.json'))
    r = j['results']; p = r['poiseuille']
    T = r['T_kinetic']
    n = float(j['parameters']['Scene/Density'])
    for half in ('lower_half', 'upper_half'):
        h = p[half]
        if 'wall_slip' not in h: continue
        eta = h['viscosity']
        gamma = 2.25 * (2 / T)
        beta = 2 * n * (math.sqrt(T / (2 * math.pi)) + 4 * 0.0222222 * gamma)
        print(f"{d:10s} {half:10s} n {n} T {T:.3f}: b {h['wall_slip']:+.3f} +- {h['wall_slip_stderr']:.3f}  eta {eta:.3f} +- {h['viscosity_stderr']:.3f}  kinetic-slip theory {eta / beta:.3f}")
