# The cold column (x = 19) with the twin's bin over the whole scene bin: the twin's value over its
# own domain part, and T_w, v = 0 (bounds: no-slip) over the pinned strip of depth delta.
import csv, glob, json, math, re, sys
import numpy as np
base = sys.argv[1]
dT, dT_fill, dv, dv_fill = {}, {}, {}, {}
for s in sorted([g for g in glob.glob(base + "/seed*") if not g.endswith(".log")]):
    summ = open(s + "/continuum/summary.json").read()
    depth = float(re.findall(r'"pinned_depth": ([0-9.e-]+)', summ)[0])
    rows = list(csv.DictReader(l for l in open(s + "/compare/bins.csv") if not l.startswith("#")))
    w = 2.0; f = depth / w
    for r in rows:
        if r["x"] != "19": continue
        y = int(r["y"]); Tt = float(r["T_nominal"]); vt = float(r["vy_nominal"])
        dT.setdefault(y, []).append(float(r["T_particle"]) - Tt)
        dT_fill.setdefault(y, []).append(float(r["T_particle"]) - ((1 - f) * Tt + f * 0.5))
        dv.setdefault(y, []).append(float(r["vy_particle"]) - vt)
        dv_fill.setdefault(y, []).append(float(r["vy_particle"]) - (1 - f) * vt)
print("depth (last seed)", depth)
for y in sorted(dT, reverse=True):
    e = lambda a: np.std(a, ddof=1) / math.sqrt(len(a))
    print(f"y={y:2d} dT {100*np.mean(dT[y]):+.2f} -> {100*np.mean(dT_fill[y]):+.2f} (+-{100*e(dT[y]):.2f})   dvy {100*np.mean(dv[y]):+.2f} -> {100*np.mean(dv_fill[y]):+.2f} (+-{100*e(dv[y]):.2f})")
