"""Mode-coupling (heat x shear) long-time-tail sums for periodic boxes, no-slip cavities
and wall slabs in 2D.

Conventions (see REPORT.md):
  lambda_tail = (c_p k T / V) * S,   S = sum_{m,n} |M_mn|^2 w_mn / (chi mu_m + nu lambda_n)
  M_mn = int conj(theta_m) (u_n)_x dA,  int |theta_m|^2 = 1, int |u_n|^2 = 1.
  A = c_p k T / (4 pi (chi+nu)).
All functions below return  s = lambda_tail / A = (4 pi / V) * sum M^2 w / (r mu + (1-r) lambda),
with r = chi/(chi+nu).  s depends only on chi/nu (and geometry, cutoff).

Regulators w (applied identically in every geometry):
  'hard2': [mu <= K^2][lambda <= K^2]     (hard cut on both factors of the double sum)
  'hard1': [mu <= K^2]                     (hard cut on heat modes only; velocity sum complete)
  'gauss': exp(-(mu+lambda)/K^2)
Velocity (Stokes) modes of no-slip walls: Rayleigh-Ritz/Galerkin in a tensor basis of
clamped-beam functions (psi = dpsi/dn = 0 built in), eigenproblem
   int (Lap psi)(Lap phi) = lambda int grad psi . grad phi.
"""
import numpy as np
from numpy.polynomial import legendre as Lg
import scipy.linalg as sla

REGS = ('hard2', 'hard1', 'gauss')


def weight(reg, mu, lam, K):
    """mu: (nh,1), lam: (1,nv) -> weight array"""
    if reg == 'hard2':
        return ((mu <= K * K) & (lam <= K * K)).astype(float)
    if reg == 'hard1':
        return np.broadcast_to((mu <= K * K).astype(float), np.broadcast(mu, lam).shape)
    if reg == 'gauss':
        return np.exp(-(mu + lam) / (K * K))
    raise ValueError(reg)


# ----------------------------------------------------------------------------------
# 1D clamped-beam basis on [0, L]
# ----------------------------------------------------------------------------------
def beam1d(L, nb, nleg=None, nquad=None):
    """Lowest nb clamped-beam functions X_i on [0,L] (X=X'=0 at both ends),
    X'''' = beta^4 X, orthonormal in L2(0,L).  Computed by Legendre-Galerkin with the
    Shen basis phi_k = L_k - 2(2k+5)/(2k+7) L_{k+2} + (2k+3)/(2k+7) L_{k+4}.
    Returns dict with beta, S2 = int X_i' X_j', quadrature nodes x, weights w,
    values X (nq x nb), parity (0 even / 1 odd about L/2)."""
    if nleg is None:
        nleg = 2 * nb + 60
    if nquad is None:
        nquad = nleg + 60
    deg = nleg + 3
    C = np.zeros((deg + 1, nleg))
    k = np.arange(nleg)
    C[k, k] = 1.0
    C[k + 2, k] = -2.0 * (2 * k + 5) / (2 * k + 7)
    C[k + 4, k] = (2 * k + 3) / (2 * k + 7)
    C1 = Lg.legder(C, 1, axis=0)
    C2 = Lg.legder(C, 2, axis=0)
    xi, wq = Lg.leggauss(nquad)
    Vd = Lg.legvander(xi, deg)
    P0 = Vd @ C
    P1 = Vd[:, :deg] @ C1 * (2.0 / L)
    P2 = Vd[:, :deg - 1] @ C2 * (2.0 / L) ** 2
    x = L * (xi + 1) / 2
    w = wq * L / 2
    M = P0.T @ (w[:, None] * P0)
    S4 = P2.T @ (w[:, None] * P2)
    # S4 is diagonal for the Shen basis (well conditioned); M is ill conditioned at high
    # degree, so solve the reversed problem M v = (1/beta^4) S4 v, largest eigenvalues.
    d = 1.0 / np.sqrt(np.diag(S4))
    M = M * d[:, None] * d[None, :]
    S4 = S4 * d[:, None] * d[None, :]
    ev, V = sla.eigh(M, S4, subset_by_index=(nleg - nb, nleg - 1))
    ev, V = 1.0 / ev[::-1], V[:, ::-1]
    V = V / np.sqrt(np.einsum('ij,ij->j', V, M @ V))[None, :]
    V = V * d[:, None]
    X = P0 @ V
    X1 = P1 @ V
    beta = ev ** 0.25
    S2 = X1.T @ (w[:, None] * X1)
    S2 = 0.5 * (S2 + S2.T)
    Mchk = X.T @ (w[:, None] * X)
    # parity about L/2: nodes are symmetric (x[::-1] = L - x)
    par = np.array([0 if np.allclose(X[:, i], X[::-1, i], atol=1e-6 * np.abs(X[:, i]).max()) else 1
                    for i in range(nb)])
    return dict(L=L, beta=beta, S2=S2, x=x, w=w, X=X, par=par,
                orth_err=np.abs(Mchk - np.eye(nb)).max())


def beam_roots(n):
    """analytic clamped-beam roots cos B cosh B = 1, first n"""
    from scipy.optimize import brentq
    out = []
    for m in range(1, n + 1):
        g = (m + 0.5) * np.pi
        f = lambda B: np.cos(B) - 1.0 / np.cosh(B)
        out.append(brentq(f, g - 0.4, g + 0.4))
    return np.array(out)


def sine_proj(b, nmax, kind):
    """G[p-1, i] = int_0^L f_p(x) X_i(x) dx for p = 1..nmax.
    kind 'sin' : f_p = sqrt(2/L) sin(p pi x/L)           (Dirichlet heat mode in x)
    kind 'dcos': f_p = d/dy [sqrt(2/L) cos(p pi y/L)]      (y-derivative of Neumann heat mode)"""
    L, x, w, X = b['L'], b['x'], b['w'], b['X']
    p = np.arange(1, nmax + 1)
    if kind == 'sin':
        F = np.sqrt(2.0 / L) * np.sin(np.outer(x, p) * np.pi / L)
    elif kind == 'dcos':
        F = -np.sqrt(2.0 / L) * (p * np.pi / L)[None, :] * np.sin(np.outer(x, p) * np.pi / L)
    else:
        raise ValueError(kind)
    return F.T @ (w[:, None] * X)


# ----------------------------------------------------------------------------------
# periodic P x P box: exact lattice sums
# ----------------------------------------------------------------------------------
def periodic(P, K, reg, kmax_sum=None):
    """s = lambda_tail/A for periodic square box.  M nonzero only for equal wavevectors;
    sum_k (k_y^2/k^2) w(k^2,k^2) / k^2 over all k != 0 (complex modes), times 4 pi / V.
    Independent of chi/nu."""
    return periodic_rect(P, P, K, reg, kmax_sum)


def periodic_rect(Px, Py, K, reg, kmax_sum=None):
    if kmax_sum is None:
        kmax_sum = K if reg != 'gauss' else 6.0 * K
    nx = int(np.ceil(kmax_sum * Px / (2 * np.pi))) + 1
    ny = int(np.ceil(kmax_sum * Py / (2 * np.pi))) + 1
    kx, ky = np.meshgrid(2 * np.pi * np.arange(-nx, nx + 1) / Px,
                         2 * np.pi * np.arange(-ny, ny + 1) / Py, indexing='ij')
    k2 = kx ** 2 + ky ** 2
    k2[nx, ny] = np.inf
    if reg in ('hard1', 'hard2'):
        wgt = (k2 <= K * K).astype(float)
    else:
        wgt = np.exp(-2 * k2 / (K * K))
    return 4 * np.pi / (Px * Py) * np.sum((ky ** 2 / k2) * wgt / k2)


# ----------------------------------------------------------------------------------
# wall slab: x in [0,L] isothermal + no-slip, y periodic with period H
# ----------------------------------------------------------------------------------
def slab(L, H, Kb, Kuse, rlist, Klist, nb=None, return_modes=False):
    """Heat modes sqrt(2/L) sin(p pi x/L) e^{iqy}/sqrt(H), q = 2 pi j/H.
    Velocity: psi = f(x) e^{iqy}/sqrt(H), u = (i q f, -f') e^{iqy}/sqrt(H).
    M = i q int s_p f dx (only equal q couple).  j and -j give identical terms (factor 2);
    q = 0 has u_x = 0 (no coupling).  Modes with mu, lambda <= Kuse^2 kept;
    beam basis up to beta <= Kb."""
    if nb is None:
        nb = int(np.ceil(Kb * L / np.pi)) + 2
    b = beam1d(L, nb)
    keep = b['beta'] <= Kb
    beta = b['beta'][keep]
    S2 = b['S2'][np.ix_(keep, keep)]
    pmax = int(np.floor(Kuse * L / np.pi))
    Gx = sine_proj(b, pmax, 'sin')[:, keep]
    mu_x = (np.arange(1, pmax + 1) * np.pi / L) ** 2
    out = {(r, K, reg): 0.0 for r in rlist for K in Klist for reg in REGS}
    jmax = int(np.floor(Kuse * H / (2 * np.pi)))
    for j in range(1, jmax + 1):
        q = 2 * np.pi * j / H
        A = np.diag(beta ** 4) + 2 * q * q * S2 + q ** 4 * np.eye(len(beta))
        B = S2 + q * q * np.eye(len(beta))
        lam, C = sla.eigh(A, B)
        sel = lam <= Kuse ** 2
        lam, C = lam[sel], C[:, sel]
        mu = mu_x + q * q
        hs = mu <= Kuse ** 2
        M2 = (q * (Gx[hs] @ C)) ** 2
        for r in rlist:
            den = r * mu[hs][:, None] + (1 - r) * lam[None, :]
            base = M2 / den
            for K in Klist:
                for reg in REGS:
                    out[(r, K, reg)] += 2 * np.sum(base * weight(reg, mu[hs][:, None], lam[None, :], K))
    V = L * H
    return {k: 4 * np.pi / V * v for k, v in out.items()}


# ----------------------------------------------------------------------------------
# closed cavity Lx x Hy: x walls Dirichlet heat + no-slip; y walls Neumann heat + no-slip
# ----------------------------------------------------------------------------------
def cavity_setup(Lx, Hy, Kb):
    nbx = int(np.ceil(Kb * Lx / np.pi)) + 2
    nby = int(np.ceil(Kb * Hy / np.pi)) + 2
    bx = beam1d(Lx, nbx)
    by = bx if (Hy == Lx) else beam1d(Hy, nby)
    return bx, by


def cavity_class(bx, by, Kb, Kuse, px, py, rlist, Klist, verbose=True, nlow=0):
    """Contribution of one parity class (px, py) (0 even, 1 odd about centre).
    psi = sum c_ij X_i(x) Y_j(y), basis pairs with beta_i^2 + beta_j^2 <= Kb^2.
    Heat modes theta = sqrt(2/Lx) sin(p pi x/Lx) * c_q(y), c_q Neumann cosine (q>=1 only:
    q = 0 does not couple since int u_x dy = 0).
    M = int theta d_y psi = - int (d_y theta) psi."""
    import time
    t0 = time.time()
    Lx, Hy = bx['L'], by['L']
    ix = np.where((bx['beta'] <= Kb) & (bx['par'] == px))[0]
    iy = np.where((by['beta'] <= Kb) & (by['par'] == py))[0]
    I, J = np.meshgrid(ix, iy, indexing='ij')
    I, J = I.ravel(), J.ravel()
    ok = bx['beta'][I] ** 2 + by['beta'][J] ** 2 <= Kb ** 2
    I, J = I[ok], J[ok]
    n = len(I)
    S2x = bx['S2'][np.ix_(I, I)]
    S2y = by['S2'][np.ix_(J, J)]
    eqI = (I[:, None] == I[None, :])
    eqJ = (J[:, None] == J[None, :])
    A = 2.0 * S2x * S2y
    A[np.diag_indices(n)] += bx['beta'][I] ** 4 + by['beta'][J] ** 4
    B = S2x * eqJ + eqI * S2y
    del S2x, S2y, eqI, eqJ
    lam, C = sla.eigh(A, B, subset_by_value=(0.0, Kuse ** 2), overwrite_a=True, overwrite_b=True,
                      driver='gvx')
    del A, B
    t1 = time.time()
    # heat modes of this parity class: s_p parity even <=> p odd ; sin(q pi y/H) even <=> q odd
    pmax = int(np.floor(Kuse * Lx / np.pi))
    qmax = int(np.floor(Kuse * Hy / np.pi))
    Gx = sine_proj(bx, pmax, 'sin')
    Gy = sine_proj(by, qmax, 'dcos')
    p = np.arange(1, pmax + 1)
    q = np.arange(1, qmax + 1)
    p = p[(p % 2 == 1) == (px == 0)]
    q = q[(q % 2 == 1) == (py == 0)]
    Pm, Qm = np.meshgrid(p, q, indexing='ij')
    Pm, Qm = Pm.ravel(), Qm.ravel()
    mu = (Pm * np.pi / Lx) ** 2 + (Qm * np.pi / Hy) ** 2
    hs = mu <= Kuse ** 2
    Pm, Qm, mu = Pm[hs], Qm[hs], mu[hs]
    G = Gx[np.ix_(Pm - 1, I)] * Gy[np.ix_(Qm - 1, J)]
    M = -(G @ C)
    del G
    M2 = M * M
    out = {}
    for r in rlist:
        base = M2 / (r * mu[:, None] + (1 - r) * lam[None, :])
        for K in Klist:
            for reg in REGS:
                out[(r, K, reg)] = np.sum(base * weight(reg, mu[:, None], lam[None, :], K))
    info = dict(n_basis=n, n_vel=len(lam), n_heat=len(mu), t_eig=t1 - t0, t_tot=time.time() - t0,
                lam_low=lam[:max(nlow, 0)].copy(),
                colsum=M2.sum(axis=1), mu=mu, P=Pm, Q=Qm)
    if verbose:
        print(f'  class ({px},{py}): basis {n}, vel modes {len(lam)}, heat modes {len(mu)}, '
              f'eig {t1 - t0:.1f}s, total {time.time() - t0:.1f}s', flush=True)
    return out, info
