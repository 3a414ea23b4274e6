#!/usr/bin/python3
"""c3 + the measured pair part (1.25 x theory, docs/theory.md); and the hot layer's local
conductivity q / (kappa dtheta/dh) in h 0.5-1 and 1-2 rc (measured 0.65-0.9, default cavity f 30)."""
import math, numpy as np
import layer as L
from candidates import solve, tail_ou, tail_laplace


def c3(p, kps=1.0, prof=False):
    tu = L.tau_u(p); tv = p["D"] / p["T"]; Dv = p["D"] * (tu + tv) / tu
    G, var = tail_ou(tu, tv, Dv)
    kp = p["kappa"] - kps * p["kappa_pair"]
    return solve(p, [(kp, G, max(math.sqrt(var / 2), math.sqrt(p["T"]) * tu))], return_profile=prof)


def ratio(h, th, a, b):
    m = (h >= a) & (h <= b)
    s = np.polyfit(h[m], th[m], 1)[0]
    far = (h >= 4) & (h <= 7)
    return np.polyfit(h[far], th[far], 1)[0] / s  # bulk slope / local slope = kappa_local / kappa


if __name__ == "__main__":
    L.table("(c3) + measured pair part 1.25x", lambda p: c3(p, 1.25))
    for f in (1, 30):
        p = L.default_inputs(*L.HOT, f)
        ell = L.energy_length(p)
        for name, fn in (("baseline", lambda: solve(p, [(p['kappa'] - p['kappa_pair'], tail_laplace(ell), ell)], return_profile=True)),
                         ("c3", lambda: c3(p, prof=True))):
            b, h, th = fn()
            print(f"hot f {f} {name}: b {b:+.3f}, local kappa/bulk at h 0.5-1: {ratio(h, th, 0.5, 1):.2f}, 1-2: {ratio(h, th, 1, 2):.2f}")
