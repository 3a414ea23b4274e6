#!/usr/bin/python3
"""The scatter of K realisations' binned fields against their stated errors.

    seed_scatter.py RUNDIR/particle/realisations   (subfolders 00, 01, ... each with fields.csv
                                                     and summary.json)

Per field: sqrt(mean over bins of the realisations' variance / mean over bins of the stated se^2),
with the stated errors as written (after the field's blocking factor) and divided by that factor
(the block errors alone); interior bins (more than 2 rc from every wall) and all bins. ~1 when
the stated errors hold; chi^2/dof = the square, with K - 1 degrees of freedom per bin.
"""
import csv, json, os, sys
import numpy as np

root = sys.argv[1]
dirs = sorted(d for d in os.listdir(root) if os.path.isdir(os.path.join(root, d)))
fields = {'T_kinetic': 'temperature_kinetic', 'density': 'density', 'vx': 'velocity',
          'vy': 'velocity', 'T_internal': 'temperature_internal'}
vals, ses, factors = {k: [] for k in fields}, {k: [] for k in fields}, {k: [] for k in fields}
xy = None
for d in dirs:
    rows = list(csv.reader(l for l in open(os.path.join(root, d, 'fields.csv')) if not l.startswith('#')))
    h = rows[0]
    a = np.array([[float(x) for x in r] for r in rows[1:]])
    ix = {k: i for i, k in enumerate(h)}
    xy = a[:, [ix['x'], ix['y']]]
    f = json.load(open(os.path.join(root, d, 'summary.json')))['results']['field_blocking_factors']
    for k, name in fields.items():
        vals[k].append(a[:, ix[k]])
        ses[k].append(a[:, ix[k + '_se']])
        factors[k].append(f[name])
x, y = xy[:, 0], xy[:, 1]
L = max(x.max(), y.max()) + min(x.min(), y.min())
interior = (x > 2) & (x < L - 2) & (y > 2) & (y < L - 2)
K = len(dirs)
print(f'{K} realisations, {len(x)} bins, {interior.sum()} interior')
for k in fields:
    v = np.array(vals[k]); s = np.array(ses[k]); f = np.array(factors[k])[:, None]
    var = v.var(axis=0, ddof=1)
    for name, m in (('interior', interior), ('all', np.ones_like(interior))):
        stated = np.sqrt(var[m].mean() / (s[:, m] ** 2).mean())
        blocks = np.sqrt(var[m].mean() / ((s / f)[:, m] ** 2).mean())
        print(f'{k:11s} {name:8s} scatter / stated {stated:.3f}  / blocks alone {blocks:.3f}'
              f'  factors {np.min(f):.3f}-{np.max(f):.3f} (mean {np.mean(f):.3f})')
