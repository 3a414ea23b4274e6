import csv, glob, sys
import numpy as np
base = sys.argv[1]; tw = sys.argv[2] if len(sys.argv) > 2 else "nominal"
res = []
for s in sorted(glob.glob(base + "/seed*/compare/bins.csv")):
    rows = list(csv.DictReader(l for l in open(s) if not l.startswith("#")))
    xs = sorted({float(r["x"]) for r in rows}); ys = sorted({float(r["y"]) for r in rows})
    def grid(key):
        g = np.zeros((len(ys), len(xs)))
        for r in rows: g[ys.index(float(r["y"])), xs.index(float(r["x"]))] = float(r[key])
        return g
    npart, vyp = grid("density_particle"), grid("vy_particle")
    ntw, vyt = grid(f"density_{tw}"), grid(f"vy_{tw}")
    dx = xs[1] - xs[0]
    psi_p = np.cumsum(npart * vyp, axis=1) * dx; psi_t = np.cumsum(ntw * vyt, axis=1) * dx
    mid = slice(3, 7)  # rows y = 7..13
    res.append((psi_p[mid].max(axis=1).mean(), psi_t[mid].max(axis=1).mean(),
                (npart*vyp)[mid, -1].mean(), (ntw*vyt)[mid, -1].mean(), (npart*vyp)[mid, 0].mean(), (ntw*vyt)[mid, 0].mean()))
a = np.array(res)
m = a.mean(axis=0); e = a.std(axis=0, ddof=1) / np.sqrt(len(a))
names = ["roll psi max particle", "twin", "n vy cold column particle", "twin", "n vy hot column particle", "twin"]
for nme, mm, ee in zip(names, m, e): print(f"{nme:28s} {mm:+.4f} +- {ee:.4f}")
