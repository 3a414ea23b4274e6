#!/usr/bin/env python3
"""Tables from bench/vs_lammps.sh's raw measurements (medians over repeats)."""
import math
import statistics as st
import sys
from collections import defaultdict

from host import host_block

perf, scenes, thermo = defaultdict(list), defaultdict(list), []
for line in open(sys.argv[1]):
    w = line.split()
    if not w:
        continue
    if w[0] == "perf" and len(w) >= 4:
        who, integ, par, n = w[1].split(":")
        perf[(who, integ, int(par), int(n))].append((float(w[2]), float(w[3])))
    elif w[0] == "scene" and len(w) >= 4:
        scene, integ, par = w[1].split(":")
        scenes[(scene, integ, int(par))].append(float(w[2]))
    elif w[0] == "thermo":
        f = [x.strip() for x in line.split("|")]
        thermo.append([f[0].split()[1]] + f[1:])

print("Host:\n\n" + host_block(sys.argv[1]))

med = lambda v: st.median(x[0] for x in v)
fmt = lambda x: "%.3g" % x if x else "-"
if perf:
    sizes = sorted({k[3] for k in perf})
    variants = [v for v in ["shardlow", "shardlow+uniform", "ec-verlet", "ec-verlet+uniform"]
                if any(k[0] == "ours" and k[1] == v for k in perf)]
    cfg = [("ours", v, t) for v in variants for t in (1, 2)]
    ranked = [v for v in ("shardlow", "ec-verlet") if any(k[:2] == ("ours-2ranks", v) for k in perf)]
    cfg += [("ours-2ranks", v, 1) for v in ranked]
    cfg += [("lammps", "shardlow", 1), ("lammps", "shardlow", 2)]
    names = ["%s %dT" % (v, t) for v in variants for t in (1, 2)]
    names += ["%s 2 ranks x 1T" % v for v in ranked]
    names += ["LAMMPS 1 rank", "LAMMPS 2 ranks"]
    reps = max(len(v) for v in perf.values())
    print("particle-steps/s, a0 = 15 + heat (median of %d; ratios against LAMMPS's best "
          "configuration at that N; +uniform: Particle/Noise = uniform)\n" % reps)
    print("| N | " + " | ".join(names) + " | " + " | ".join("%s / LAMMPS" % v for v in variants) +
          " | 2-thread efficiency " + ", ".join(variants) + " |")
    print("|---" * (len(names) + len(variants) + 2) + "|")
    for n in sizes:
        v = [med(perf[c + (n,)]) if perf.get(c + (n,)) else 0 for c in cfg]
        best = max(v[-2], v[-1])
        ratio = lambda x: "%.2fx" % (x / best) if best else "-"
        eff = lambda one, two: "%.0f%%" % (100 * two / (2 * one)) if one else "-"
        ours = [(v[2 * k], v[2 * k + 1]) for k in range(len(variants))]
        print("| %d | %s | %s | %s |" % (
            n, " | ".join(fmt(x) for x in v),
            " | ".join("%s (%s)" % (ratio(two), ratio(one)) for one, two in ours),
            ", ".join(eff(one, two) for one, two in ours)))
    print("\n(ratios: 2 threads, in brackets 1 thread)\n")
    if ranked:
        print("2 MPI ranks x 1 thread against 1 rank x 2 threads (same binary, same run):\n")
        for v in ranked:
            k = 2 * variants.index(v) + 1
            print("- %s: " % v + ", ".join(
                "N = %d: %.2f" % (n, med(perf[("ours-2ranks", v, 1, n)]) / med(perf[cfg[k] + (n,)]))
                for n in sizes if perf.get(("ours-2ranks", v, 1, n)) and perf.get(cfg[k] + (n,))))
        print()
    print("cost exponent b in time per step ~ N^b (least squares over N = %s):\n" %
          ", ".join(map(str, sizes)))
    def slope(pts):
        mx = st.mean(p[0] for p in pts)
        my = st.mean(p[1] for p in pts)
        return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)

    for c, name in zip(cfg, names):
        have = [n for n in sizes if perf.get(c + (n,))]
        if len(have) >= 2:
            b = slope([(math.log(n), math.log(n / med(perf[c + (n,)]))) for n in have])
            # Each repeat ran its sizes back to back: its own fit shows how much the machine's
            # load moved the exponent between repeats.
            runs = min(len(perf[c + (n,)]) for n in have)
            each = sorted(slope([(math.log(n), math.log(n / perf[c + (n,)][k][0])) for n in have])
                          for k in range(runs))
            spread = " (per repeat: median %.3f, %.3f-%.3f)" % (
                st.median(each), each[0], each[-1]) if runs > 1 else ""
            print("- %s: b = %.3f%s" % (name, b, spread))
    print("\nmemory: peak-RSS difference between the largest and smallest N, per particle "
          "(median RSS):\n")
    for c, name in zip(cfg, names):
        have = [n for n in sizes if perf.get(c + (n,))]
        if len(have) >= 2:
            lo, hi = have[0], have[-1]
            r = lambda n: st.median(x[1] for x in perf[c + (n,)])
            print("- %s: %.0f bytes/particle (%.0f MB at N = %d)" % (
                name, (r(hi) - r(lo)) * 1024 / (hi - lo), r(hi) / 1024, hi))
if scenes:
    print("\nscenes, ours, N = 48000 (particle-steps/s, median; 1 / 2 threads):\n")
    print("| scene | shardlow | ec-verlet |\n|---|---|---|")
    for scene in ["ideal", "ideal+heat", "a0=15", "a0=15+heat"]:
        cell = lambda i: " / ".join(fmt(st.median(scenes[(scene, i, t)])) if scenes.get(
            (scene, i, t)) else "-" for t in (1, 2))
        print("| %s | %s | %s |" % (scene, cell("shardlow"), cell("ec-verlet")))
if thermo:
    print("\nthermodynamics, N = 6000, a0 = 15 + heat, 10 tau sampled after 10 tau "
          "(energy drift: max |E(t) - E(0)|/E(0) over all 20 tau):\n")
    print("| code | max dE/E0 | T_kinetic | T_internal | pressure |\n|---|---|---|---|---|")
    for row in thermo:
        print("| " + " | ".join(row) + " |")
