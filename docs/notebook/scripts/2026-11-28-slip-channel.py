#!/usr/bin/env python3
"""The slip layer (2026-11-28-slip-layer.py's channels, docs/theory.md "The slip layer") in the
channel's own geometry: both walls, the reverse Poiseuille force, the fit window of
poiseuille_fit; the apparent slips against docs/validation.md's channel table.
    2026-11-28-slip-channel.py [dh [friction|consistent [pair_factor]]]
ell: 'friction' sqrt(D_K tau_v) (the twin's), 'consistent' D_K sqrt(m / T) (tried: hot diffuse 0.86);
pair_factor scales the fluid's pair kernel (tried 0.805, the transport stage's measured / mean-field
pair part: cold slips fall to 0.04-0.10)."""
import math, os, sys, importlib.util
spec = importlib.util.spec_from_file_location('sl', os.path.join(os.path.dirname(os.path.abspath(__file__)), '2026-11-28-slip-layer.py'))
sl = importlib.util.module_from_spec(spec); spec.loader.exec_module(sl)

def channel(n, T, eta, F, walls, L=20.0, dh=0.1, rho_w=None, ell_rule="friction", e_d=2.0, sigma2=9.0, m=1.0, pair_factor=1.0):
    rho_w = n if rho_w is None else rho_w
    gamma = sigma2 / (2 * T)
    N = int(round(L / dh)); hs = [(k + 0.5) * dh for k in range(N)]
    cache = {}
    def W(h):
        key = round(h, 6)
        if key not in cache: cache[key] = sl.half_space(max(h, 0.0), e_d, 't2')
        return cache[key]
    reach = int(math.ceil(1.0 / dh))
    kern = [0.0] + [(W(max(d * dh - dh / 2, 0)) - W(d * dh + dh / 2)) / dh for d in range(1, reach + 1)]
    eta_pair = pair_factor * n * n * gamma * sum(kern[d] * (d * dh) ** 2 for d in range(1, reach + 1)) * dh
    eta_kin = eta - eta_pair
    D = 2 * eta_kin / (n * m)                      # eta_K = n m D / 2 (002:(26))
    zeta = n * gamma * sl.half_space(0.0, e_d, 't2') * 2
    ell = D * math.sqrt(m / T) if ell_rule == 'consistent' else math.sqrt(D * m / zeta)
    A = [[0.0] * N for _ in range(N)]; rhs = [0.0] * N
    pair_scale = pair_factor * n * n * gamma * dh * dh; a_kin = eta_kin / (2 * ell ** 3) * dh * dh
    for k in range(N):
        for l in range(k + 1, N):
            d = l - k
            c = a_kin * math.exp(-d * dh / ell) + (pair_scale * kern[d] if d <= reach else 0.0)
            A[k][k] -= c; A[k][l] += c; A[l][l] -= c; A[l][k] += c
        for side, h in ((0, hs[k]), (1, L - hs[k])):
            if walls[side] == 'diffuse':
                A[k][k] -= eta_kin / (2 * ell * ell) * math.exp(-h / ell) * dh
            else:  # bounce-back: the mirror images of every cell, velocity -u
                for l in range(N):
                    dist = h + (hs[l] if side == 0 else L - hs[l])
                    c = a_kin * math.exp(-dist / ell)
                    A[k][k] -= c; A[k][l] -= c
            A[k][k] -= n * dh * rho_w * gamma * W(h)
        rhs[k] = -n * m * (F if hs[k] < L / 2 else -F) * dh
    u = solve(A, rhs)
    out = []
    for lo, hi, wall_at in ((1.0, L / 2 - 0.05 * L, 0.0), (L / 2 + 0.05 * L, L - 1.0, L)):
        pts = [(h, v) for h, v in zip(hs, u) if lo <= h <= hi]
        c0, c1, c2 = fit2(pts)
        # the parabola's root nearest the wall, beyond it
        disc = math.sqrt(c1 * c1 - 4 * c2 * c0)
        roots = [(-c1 - disc) / (2 * c2), (-c1 + disc) / (2 * c2)]
        root = min(roots, key=lambda r: abs(r - wall_at))
        out.append(abs(wall_at - root) * (1 if (root < 0 if wall_at == 0 else root > L) else -1))
    return out, eta_pair, eta_kin, ell

def solve(A, b):
    N = len(b); M = [row[:] + [v] for row, v in zip(A, b)]
    for i in range(N):
        p = max(range(i, N), key=lambda r: abs(M[r][i])); M[i], M[p] = M[p], M[i]
        Mi = M[i]; piv = Mi[i]
        for r in range(i + 1, N):
            f = M[r][i] / piv
            if f:
                Mr = M[r]
                for c in range(i, N + 1): Mr[c] -= f * Mi[c]
    x = [0.0] * N
    for i in range(N - 1, -1, -1):
        x[i] = (M[i][N] - sum(M[i][c] * x[c] for c in range(i + 1, N))) / M[i][i]
    return x

def fit2(pts):
    S = [[sum(h ** (i + j) for h, _ in pts) for j in range(3)] for i in range(3)]
    r = [sum(v * h ** i for h, v in pts) for i in range(3)]
    return solve(S, r)

if __name__ == '__main__':
    dh = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
    rule = sys.argv[2] if len(sys.argv) > 2 else "friction"
    pf = float(sys.argv[3]) if len(sys.argv) > 3 else 1.0
    for name, n, T, eta, F, walls, meas in (
            ('cold diffuse', 5.6, 0.77, 1.587, 0.0056, ('diffuse', 'diffuse'), '0.21 +- 0.04'),
            ('cold bounce', 5.6, 0.77, 1.559, 0.0056, ('bounce', 'bounce'), '0.15 +- 0.03'),
            ('hot diffuse', 2.4, 1.45, 1.485, 0.0158, ('diffuse', 'diffuse'), '0.68 +- 0.03'),
            ('hot bounce', 2.4, 1.45, 1.512, 0.0158, ('bounce', 'bounce'), '0.15 +- 0.02')):
        b, ep, ek, ell = channel(n, T, eta, F, walls, dh=dh, ell_rule=rule, pair_factor=pf)
        print(f'{name}: b {b[0]:.3f} {b[1]:.3f} (measured {meas}); eta_P {ep:.3f} eta_K {ek:.3f} ell {ell:.3f}')
