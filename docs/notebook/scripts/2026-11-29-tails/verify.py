"""Independent finite-difference checks of the Galerkin (beam-function) code, at a low
hard cutoff Kc (modes with mu, lambda <= Kc^2 only) where a plain 2nd-order FD grid is accurate.
 (1) wall slab 20 x 50: 1D FD per q.  (2) cavity 20 x 20: 2D FD stream function, sparse
 shift-invert eigensolver.  Compares s = lambda_tail/A restricted to those modes ('hard2')."""
import numpy as np, scipy.sparse as sp, scipy.sparse.linalg as spla, time
from modes import slab, cavity_setup, cavity_class
r = 0.384/0.717

def d2(n, h):
    return sp.diags([np.ones(n-1), -2*np.ones(n), np.ones(n-1)], [-1, 0, 1]) / h**2
def d4(n, h):
    m = sp.diags([np.ones(n-2), -4*np.ones(n-1), 6*np.ones(n), -4*np.ones(n-1), np.ones(n-2)],
                 [-2, -1, 0, 1, 2]).tolil()
    m[0, 0] = 7; m[-1, -1] = 7          # clamped: ghost f_{-1} = f_1, f_0 = 0
    return m.tocsr() / h**4

def fd_slab(L, H, Kc, N, jmax=None):
    h = L/N; x = h*np.arange(1, N); n = N-1
    D2, D4, I = d2(n, h), d4(n, h), sp.identity(n)
    s = 0.0
    pmax = int(Kc*L/np.pi)
    for j in range(1, int(Kc*H/(2*np.pi))+1):
        q = 2*np.pi*j/H
        A = (D4 - 2*q*q*D2 + q**4*I).tocsc(); B = (q*q*I - D2).tocsc()
        k = 40
        lam, F = spla.eigsh(A, k=k, M=B, sigma=0, which='LM')
        o = np.argsort(lam); lam, F = lam[o], F[:, o]
        assert lam[-1] > Kc**2
        sel = lam <= Kc**2; lam, F = lam[sel], F[:, sel]
        F = F/np.sqrt(h*np.einsum('ij,ij->j', F, B @ F))
        p = np.arange(1, pmax+1); mu = (p*np.pi/L)**2 + q*q; hs = mu <= Kc**2
        Sx = np.sqrt(2/L)*np.sin(np.outer(p[hs], x)*np.pi/L)
        M = q*h*(Sx @ F)
        s += 2*np.sum(M**2/(r*mu[hs][:, None] + (1-r)*lam[None, :]))
    return 4*np.pi/(L*H)*s

def fd_cavity(L, H, Kc, N, kev=80):
    hx, hy = L/N, H/N   # use square cells for L=H
    nx = ny = N-1
    x = hx*np.arange(1, N); y = hy*np.arange(1, N)
    D2x, D2y, D4x, D4y = d2(nx, hx), d2(ny, hy), d4(nx, hx), d4(ny, hy)
    Ix, Iy = sp.identity(nx), sp.identity(ny)
    A = (sp.kron(D4x, Iy) + 2*sp.kron(D2x, D2y) + sp.kron(Ix, D4y)).tocsc()
    B = (-(sp.kron(D2x, Iy) + sp.kron(Ix, D2y))).tocsc()
    lam, Psi = spla.eigsh(A, k=kev, M=B, sigma=0, which='LM')
    o = np.argsort(lam); lam, Psi = lam[o], Psi[:, o]
    assert lam[-1] > Kc**2, lam[-1]
    sel = lam <= Kc**2; lam, Psi = lam[sel], Psi[:, sel]
    Psi = Psi/np.sqrt(hx*hy*np.einsum('ij,ij->j', Psi, B @ Psi))
    s = 0.0
    for p in range(1, int(Kc*L/np.pi)+1):
        for qq in range(1, int(Kc*H/np.pi)+1):
            mu = (p*np.pi/L)**2 + (qq*np.pi/H)**2
            if mu > Kc**2: continue
            dyth = np.outer(np.sqrt(2/L)*np.sin(p*np.pi*x/L),
                            -np.sqrt(2/H)*(qq*np.pi/H)*np.sin(qq*np.pi*y/H)).ravel()
            M = -hx*hy*(dyth @ Psi)
            s += np.sum(M**2/(r*mu + (1-r)*lam))
    return 4*np.pi/(L*H)*s, lam

if __name__ == '__main__':
    Kc = 1.0
    print('--- slab 20x50, hard2 cutoff Kc=1 ---')
    g = slab(20.0, 50.0, 12.0, 10.0, [r], [Kc])[(r, Kc, 'hard2')]
    print(f'Galerkin beam basis: s = {g:.6f}')
    for N in [200, 400, 800]:
        print(f'FD N={N} (h={20/N}): s = {fd_slab(20.0, 50.0, Kc, N):.6f}')
    print('--- cavity 20x20, hard2 cutoff Kc=1 ---')
    bx, by = cavity_setup(20.0, 20.0, 8.0)
    g = 0.0; laml = []
    for px in (0, 1):
        for py in (0, 1):
            out, info = cavity_class(bx, by, 8.0, 7.0, px, py, [r], [Kc], verbose=False, nlow=400)
            g += 4*np.pi/400*out[(r, Kc, 'hard2')]; laml.append(info['lam_low'])
    laml = np.sort(np.concatenate(laml))
    print(f'Galerkin: s = {g:.6f};  lowest lambda*L^2: {np.round(laml[:6]*400, 3)}')
    for N in [50, 100, 140]:
        t = time.time(); s, lam = fd_cavity(20.0, 20.0, Kc, N)
        print(f'FD N={N} (h={20/N}): s = {s:.6f}; lowest lambda*L^2 {np.round(lam[:6]*400, 3)}; {time.time()-t:.0f}s')
