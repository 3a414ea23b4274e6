"""Run one parity class of a cavity geometry; store partial sums.
usage: run_cavity.py Lx Hy Kb Kuse px py"""
import sys, time, pickle, os
import numpy as np
from modes import cavity_setup, cavity_class
Lx, Hy, Kb, Kuse = map(float, sys.argv[1:5]); px, py = int(sys.argv[5]), int(sys.argv[6])
chi, nu = 0.384, 0.333
RLIST = [chi/(chi+nu), 0.5, 2/3, 1/3]          # chi/nu = 1.153 (default), 1, 2, 0.5
KLIST = [np.pi, np.pi/0.7, 2*np.pi, 2*np.pi/0.7]   # pi, pi/0.7 used via exact scaling for L=40
t = time.time()
bx, by = cavity_setup(Lx, Hy, Kb)
out, info = cavity_class(bx, by, Kb, Kuse, px, py, RLIST, KLIST, nlow=8)
os.makedirs('results', exist_ok=True)
fn = f'results/cav_{Lx:g}x{Hy:g}_Kb{Kb:g}_Ku{Kuse:g}_{px}{py}.pkl'
info_s = {k: v for k, v in info.items() if k in ('n_basis', 'n_vel', 'n_heat', 't_eig', 't_tot', 'lam_low')}
# completeness diagnostic: mean of colsum/expected for heat modes with k<2
exp_ = (info['Q']*np.pi/Hy)**2/info['mu']; sel = info['mu'] < 4
info_s['colsum_ratio_k<2'] = float(np.mean(info['colsum'][sel]/exp_[sel])) if sel.any() else None
pickle.dump(dict(out=out, info=info_s, V=Lx*Hy, args=(Lx, Hy, Kb, Kuse, px, py)), open(fn, 'wb'))
print(fn, info_s, f'{time.time()-t:.1f}s')
