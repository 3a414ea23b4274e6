#!/usr/bin/python3
"""(c4) transport-consistent carriers: the kernel's total rate n c_v / tau_u and its second moment
kappa - kappa_pair fix its variance, 2 D_eff tau_u with D_eff = (kappa - kappa_pair) / (n c_v);
an OU walker (D_v = T tau_v) has D_eff = D_v tau_u / (tau_u + tau_v) (Green-Kubo of the label
with the exponential VACF), so tau_v = D_eff tau_u / (T tau_u - D_eff); the shape its deposit kernel.
(c5) two parts: the mean-field walker (002:(17), tau = 1/zeta_mf, D_mf = T/zeta_mf) carries
n c_v D_mf tau_u / (tau_u + tau_mf) with its OU kernel; the rest of kappa - kappa_pair on the C++'s
Laplace kernel, ell = sqrt(D tau_u)."""
import math
import layer as L
from candidates import solve, tail_ou, tail_laplace, zeta_mf


def c4(p, verbose=False):
    tu = L.tau_u(p)
    kp = p["kappa"] - p["kappa_pair"]
    De = kp / (p["n"] * p["cv"])
    T = p["T"]
    tv = De * tu / (T * tu - De) if T * tu > De else 1e3 * tu
    G, var = tail_ou(tu, tv, T * tv)
    if verbose:
        print(f"  c4: D_eff {De:.3f}, tau_v {tv:.3f}, ell_eq {math.sqrt(var/2):.3f}")
    return solve(p, [(kp, G, max(math.sqrt(var / 2), math.sqrt(T) * tu))])


def c5(p, verbose=False):
    tu = L.tau_u(p)
    kp = p["kappa"] - p["kappa_pair"]
    z = zeta_mf(p)
    tm, Dm = 1 / z, p["T"] / z
    k1 = p["n"] * p["cv"] * Dm * tu / (tu + tm)
    G, var = tail_ou(tu, tm, Dm)
    ell = L.energy_length(p)
    if verbose:
        print(f"  c5: mean-field part {k1:.2f} of {kp:.2f}, ell_eq {math.sqrt(var/2):.3f}, ell {ell:.3f}")
    return solve(p, [(k1, G, max(math.sqrt(var / 2), math.sqrt(p['T']) * tu)),
                     (kp - k1, tail_laplace(ell), ell)])


if __name__ == "__main__":
    for st in (L.HOT, L.COLD):
        c4(L.default_inputs(*st, 1), True); c5(L.default_inputs(*st, 1), True)
    L.table("(c4) transport-consistent OU carriers", c4)
    L.table("(c5) mean-field OU part + Laplace rest", c5)
