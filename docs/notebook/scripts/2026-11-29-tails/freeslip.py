"""Reference: same geometries with FREE-SLIP (stress-free) walls instead of no-slip.
Then the velocity modes are analytic and match the heat modes one-to-one:
 cavity: psi ~ sin(p pi x/L) sin(q pi y/H) -> u_x ~ sin(p pi x/L) cos(q pi y/H) = heat mode,
         |M|^2 = (q pi/H)^2/k^2, p,q >= 1.
 slab:   psi ~ sin(p pi x/L) e^{iqy}, |M|^2 = q^2/k^2, p >= 1, q = 2 pi j/H, j != 0.
Hard cut k <= K.  Delta/A relative to periodic 40 (hard cut)."""
import numpy as np
from modes import periodic
def cav_fs(L, H, K):
    p = np.arange(1, int(K*L/np.pi)+1); q = np.arange(1, int(K*H/np.pi)+1)
    kx, ky = np.meshgrid(p*np.pi/L, q*np.pi/H, indexing='ij'); k2 = kx**2+ky**2
    return 4*np.pi/(L*H)*np.sum(np.where(k2 <= K*K, ky**2/k2**2, 0))
def slab_fs(L, H, K):
    p = np.arange(1, int(K*L/np.pi)+1); j = np.arange(1, int(K*H/(2*np.pi))+1)
    kx, ky = np.meshgrid(p*np.pi/L, 2*np.pi*j/H, indexing='ij'); k2 = kx**2+ky**2
    return 2*4*np.pi/(L*H)*np.sum(np.where(k2 <= K*K, ky**2/k2**2, 0))
for K in [2*np.pi, 2*np.pi/0.7]:
    s40 = periodic(40, K, 'hard2')
    print(f'2pi/K={2*np.pi/K:.1f}: free-slip Delta/A: cavity20x20 {cav_fs(20,20,K)-s40:+.3f}, '
          f'cavity20x40 {cav_fs(20,40,K)-s40:+.3f}, cavity40x40 {cav_fs(40,40,K)-s40:+.3f}, slab20x50 {slab_fs(20,50,K)-s40:+.3f}')
