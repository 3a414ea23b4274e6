import csv, glob, sys, math
import numpy as np
base, tw = sys.argv[1], sys.argv[2]
D = {}
for s in sorted(glob.glob(base + "/seed*/compare/bins.csv")):
    for r in csv.DictReader(l for l in open(s) if not l.startswith("#")):
        if r["interior"] != "1": continue
        k = (r["x"], r["y"])
        for f in ("T", "vx", "vy", "density"):
            D.setdefault((f, k), []).append(float(r[f"{f}_particle"]) - float(r[f"{f}_{tw}"]))
for f in ("T", "vx", "vy", "density"):
    ms, es = [], []
    for (g, k), v in D.items():
        if g != f: continue
        v = np.array(v); ms.append(v.mean()); es.append(v.std(ddof=1) / math.sqrt(len(v)))
    ms, es = np.array(ms), np.array(es)
    print(f"{tw:10s} {f:8s} bins {len(ms)}: mean-map rms {np.sqrt((ms**2).mean()):.4f}, its error rms {np.sqrt((es**2).mean()):.4f}, mean (d/e)^2 {np.mean((ms/es)**2):.1f}, worst {ms[np.argmax(abs(ms))]:+.4f}")
