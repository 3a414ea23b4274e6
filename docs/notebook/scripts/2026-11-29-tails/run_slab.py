"""Wall slab: x in [0,L] isothermal no-slip walls, y periodic with period H.
usage: run_slab.py L H Kb Kuse"""
import sys, pickle, os, time
import numpy as np
from modes import slab
L, H, Kb, Kuse = map(float, sys.argv[1:5])
chi, nu = 0.384, 0.333
RLIST = [chi/(chi+nu), 0.5, 2/3, 1/3]
KLIST = [np.pi, np.pi/0.7, 2*np.pi, 2*np.pi/0.7]   # pi, pi/0.7 used via exact scaling for L=40
t = time.time()
out = slab(L, H, Kb, Kuse, RLIST, KLIST)
os.makedirs('results', exist_ok=True)
fn = f'results/slab_{L:g}x{H:g}_Kb{Kb:g}_Ku{Kuse:g}.pkl'
pickle.dump(dict(out=out, V=L*H, args=(L, H, Kb, Kuse)), open(fn, 'wb'))
print(fn, f'{time.time()-t:.1f}s')
