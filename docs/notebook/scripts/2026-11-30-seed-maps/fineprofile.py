# Mid-height band (y in [lo, hi]) profiles across the cavity from compare/bins.csv at fine bins:
# particle and nominal twin, T, vy, n, with the particle's errors (band mean of per-bin block errors / sqrt(rows)).
import csv, sys, math
import numpy as np
path, lo, hi = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
rows = [r for r in csv.DictReader(l for l in open(path) if not l.startswith("#"))]
xs = sorted({float(r["x"]) for r in rows})
print("x   T_p     T_t    dT     | vy_p    vy_t    dvy (se)   | n_p   n_t")
for x in xs:
    sel = [r for r in rows if float(r["x"]) == x and lo <= float(r["y"]) <= hi]
    f = lambda k: np.mean([float(r[k]) for r in sel])
    se = lambda k: math.sqrt(sum(float(r[k])**2 for r in sel)) / len(sel)
    print(f"{x:5.2f} {f('T_particle'):.4f} {f('T_nominal'):.4f} {f('T_particle')-f('T_nominal'):+.4f} | "
          f"{f('vy_particle'):+.4f} {f('vy_nominal'):+.4f} {f('vy_particle')-f('vy_nominal'):+.4f} ({se('vy_particle_se'):.4f}) | "
          f"{f('density_particle'):.3f} {f('density_nominal'):.3f}")
