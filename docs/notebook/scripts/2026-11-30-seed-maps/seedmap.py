import csv, glob, math, sys
import numpy as np
base = sys.argv[1]
maps = {}
for s in sorted(glob.glob(base + "/seed*/compare/bins.csv")):
    rows = list(csv.DictReader(l for l in open(s) if not l.startswith("#")))
    for r in rows:
        k = (float(r["x"]), float(r["y"]))
        d = maps.setdefault(k, {"dT": [], "se": [], "dvx": [], "dvy": [], "dn": [], "interior": r["interior"]})
        d["dT"].append(float(r["T_particle"]) - float(r["T_nominal"]))
        d["se"].append(float(r["T_particle_se"]))
        d["dvx"].append(float(r["vx_particle"]) - float(r["vx_nominal"]))
        d["dvy"].append(float(r["vy_particle"]) - float(r["vy_nominal"]))
        d["dn"].append(float(r["density_particle"]) - float(r["density_nominal"]))
xs = sorted({k[0] for k in maps}); ys = sorted({k[1] for k in maps})
nseed = len(next(iter(maps.values()))["dT"])
print("seeds", nseed)
for name in ["dT", "dvx", "dvy", "dn"]:
    print(f"\nmean {name} over seeds (x right, y up), x100; then /error of mean")
    for y in reversed(ys):
        line = []; line2 = []
        for x in xs:
            v = np.array(maps[(x, y)][name]); m = v.mean(); e = v.std(ddof=1) / math.sqrt(len(v))
            line.append(f"{100*m:+6.2f}"); line2.append(f"{m/e:+5.1f}")
        print(f"y={y:5.1f} " + " ".join(line) + "   | " + " ".join(line2))
# row / column means of dT
A = np.array([[np.mean(maps[(x, y)]["dT"]) for x in xs] for y in ys])
print("\ncolumn means dT x100:", " ".join(f"{100*v:+.2f}" for v in A.mean(axis=0)))
print("row means dT x100 (bottom->top):", " ".join(f"{100*v:+.2f}" for v in A.mean(axis=1)))
