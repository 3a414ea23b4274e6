#!/usr/bin/env python3
"""Momentum analogue of transport/wall_layer: a 1D mean-field balance of tangential momentum beside
a half-space DPD wall, steady, fixed shear stress far away. Channels: the fluid's pair friction
(nonlocal over w_D (e_t)^2, partners beyond the plane missing), the particles' own momentum transport
(exp kernel, length ell = sqrt(D tau_v)) with the wall a reservoir at u = 0 (diffuse) or a mirror
(bounce-back: image velocity -u), the wall's own friction rho_w gamma int w_D (e_t)^2 over its half
space. Returns the extrapolation length b (rc) of the bulk line."""
import math, sys

def half_space(h, e, moment, nr=400, nphi=200):
    # 2D: int over {z > h} of w(r) m(r) d^2r, w = (1-r)^e (rc = 1); m: 1, (z/r)^2, (x/r)^2
    if h >= 1: return 0.0
    s = 0.0
    dr = (1 - h) / nr
    for i in range(nr):
        r = h + (i + 0.5) * dr
        # angle range where z = r cos(phi) > h: |phi| < acos(h/r)
        a = math.acos(min(1.0, h / r))
        w = (1 - r) ** e
        if moment == 'vol': ang = 2 * a
        elif moment == 'n2': ang = a + 0.5 * math.sin(2 * a)  # int cos^2 over [-a,a]
        else: ang = a - 0.5 * math.sin(2 * a)                 # int sin^2 over [-a,a]
        s += w * ang * r * dr
    return s

def solve(n, gamma, eta_total, rho_w, wall, e_d=2.0, dh=0.05, H=8.0, ell=None, D=None, m=1.0):
    N = int(round(H / dh))
    hs = [(k + 0.5) * dh for k in range(N)]
    Wt = {}
    def W(h):
        key = round(h, 6)
        if key not in Wt: Wt[key] = half_space(max(h, 0.0), e_d, 't2')
        return Wt[key]
    # bulk pair viscosity from the plane kernel: n^2 gamma int_0^1 s^2 k(s) ds / ... computed directly
    kern = [0.0]
    reach = int(math.ceil(1.0 / dh))
    for d in range(1, reach + 1):
        s = d * dh
        kern.append((W(max(s - dh / 2, 0)) - W(s + dh / 2)) / dh)
    eta_pair = n * n * gamma * sum(kern[d] * (d * dh) ** 2 for d in range(1, reach + 1)) * dh / 1.0
    # the exchange between planes k, l (both orders): force density on k = sum c (u_l - u_k);
    # stress across a plane = sum over pairs straddling; for a linear profile: eta = n^2 gamma sum k(s) s^2 ds
    # (each separation s straddles s planes -> s*dh multiplicity; one side only -> factor 1)
    eta_kin = max(eta_total - eta_pair, 1e-9)
    zeta = n * gamma * half_space(0.0, e_d, 't2') * 2  # friction rate on a particle (full space)
    tau = m / zeta
    if ell is None:
        Dv = D if D is not None else 1.0 / zeta * 1.0  # kT/zeta with kT ~ set by caller via D
        ell = math.sqrt(Dv * tau)
    A = [[0.0] * N for _ in range(N)]
    rhs = [0.0] * N
    S = 1.0  # far-field shear rate target: drive by continuing the line beyond H
    def exchange(k, l, c, image=False):
        if image:  # partner is the mirror image of cell l with velocity -u_l
            A[k][k] -= c; A[k][l] -= c; return
        A[k][k] -= c
        if l < N:
            A[k][l] += c; A[l][l] -= c; A[l][k] += c
        else:
            A[k][N - 1] += c; rhs[k] -= c * (l - (N - 1)) * dh * S
    pair_scale = n * n * gamma * dh * dh
    a_kin = eta_kin / (2 * ell ** 3) * dh * dh
    kin_reach = int(math.ceil(14 * ell / dh))
    for k in range(N):
        for d in range(1, reach + 1): exchange(k, k + d, pair_scale * kern[d])
        for d in range(1, kin_reach + 1): exchange(k, k + d, a_kin * math.exp(-d * dh / ell))
        h = hs[k]
        if wall == 'diffuse':
            A[k][k] -= eta_kin / (2 * ell * ell) * math.exp(-h / ell) * dh
        else:  # bounce-back: exchange with the images of the cells l (at -h_l)
            for l in range(N):
                dist = h + hs[l]
                if dist / ell > 14: break
                exchange(k, l, a_kin * math.exp(-dist / ell), image=True)
        A[k][k] -= n * dh * rho_w * gamma * W(h)
    # solve
    M = [row[:] + [v] for row, v in zip(A, rhs)]
    for i in range(N):
        p = max(range(i, min(N, i + 60)), key=lambda r: abs(M[r][i]))
        M[i], M[p] = M[p], M[i]
        piv = M[i][i]
        for r in range(i + 1, min(N, i + 60)):
            f = M[r][i] / piv
            if f != 0:
                Mi = M[i]; Mr = M[r]
                for c in range(i, N + 1): Mr[c] -= f * Mi[c]
    u = [0.0] * N
    for i in range(N - 1, -1, -1):
        s = M[i][N] - sum(M[i][c] * u[c] for c in range(i + 1, N))
        u[i] = s / M[i][i]
    margin = max(2.0, 4 * ell)
    pts = [(h, v) for h, v in zip(hs, u) if margin <= h <= H - margin]
    nn = len(pts); mx = sum(p[0] for p in pts) / nn; my = sum(p[1] for p in pts) / nn
    sl = sum((p[0] - mx) * (p[1] - my) for p in pts) / sum((p[0] - mx) ** 2 for p in pts)
    ic = my - sl * mx
    return ic / sl, eta_pair, eta_kin, ell

if __name__ == '__main__':
    for label, n, T, eta, in_wall in (('cold', 5.6, 0.77, 1.55, 'diffuse'), ('cold bb', 5.6, 0.77, 1.55, 'bounce'),
                                      ('hot', 2.4, 1.45, 1.45, 'diffuse'), ('hot bb', 2.4, 1.45, 1.45, 'bounce')):
        gamma = 9.0 / (2 * T)
        zeta = n * gamma * half_space(0.0, 2.0, 't2') * 2
        D = T / zeta
        b, ep, ek, ell = solve(n, gamma, eta, 4.0, in_wall, D=D)
        print(f"{label}: b {b:+.3f} rc, eta_pair {ep:.3f}, eta_kin {ek:.3f}, ell {ell:.3f}, maxwell+wall b {eta/(2*n*(math.sqrt(T/(2*math.pi)) + 4*0.0222*gamma*1)):.3f}")
