#!/usr/bin/python3
"""All variants over the five c_v slabs; b as the slab reads it; chi^2 over the 10 readings."""
import sys, time; import os; sys.path.insert(0, os.path.dirname(os.path.abspath(__file__))); sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-11-29-cv-slabs"))
import numpy as np, slab as S, layer as L, predict as P
RUNS = ["cv10_s2", "cv10_s3", "cv20_s1", "cv50_s1", "cv50_s2"]
res = {}
for r in RUNS:
    st = S.state_from_run(f"/work/runs/s24/cvslab/{r}")
    o = st["o"]; hot, cold = o["walls"]["hot"], o["walls"]["cold"]
    meas = [(hot["b"], hot["b_stderr"]), (cold["b"], cold["b_stderr"])]
    kh, kc, nh, nc, pf = hot["kappa_bulk_at_wall"], cold["kappa_bulk_at_wall"], hot["n_1_2"], cold["n_1_2"], o["pair_factor_median"]
    out = {}
    pr = P.predict(o["cv"], o["f"], kh, kc, pf, ["built"], n=(nh, nc), T=(1.4, 0.6), verbose=False, bin_width=o["bin_width"])
    out["built"] = (pr[("built", "hot", "slab")], pr[("built", "cold", "slab")])
    # centre-state ell for both walls (built half-space layers otherwise)
    Fc = S.fields_on(st, np.array([st["L"] / 2]))
    ellc = float(Fc["ell"][0])
    prof = []
    for side, k, n, T in (("hot", kh, nh, 1.4), ("cold", kc, nc, 0.6)):
        p = P.inputs(side, o["cv"], k, o["f"], n, T)
        prof.append(L.solve_wall_layer(p, ell=ellc, return_profile=True))
    out["centre_ell"] = P.slab_reading(prof[0], prof[1], 20.0, o["bin_width"])
    for name, kw in (("path", dict(kernel="path")), ("path_isobar_n", dict(kernel="path", n_mode="isobar")),
                     ("local_slab", dict(kernel="local")), ("arith_path", dict(kernel="arith")), ("path_ell_centre", dict(kernel="path", ell_override=ellc))):
        xg, T, F, ell = S.solve_slab(st, **kw)
        bh, bc, _ = S.read_b(xg, T, st["L"], st["Th"], st["Tc"], o["bin_width"])
        out[name] = (bh, bc)
    res[r] = (meas, out, ellc, o["cv"])
    print(r, "ell centre %.3f" % ellc, {k: "%.3f/%.3f" % v for k, v in out.items()}, flush=True)
models = list(next(iter(res.values()))[1])
print("\n| variant | " + " | ".join(f"{r} hot | {r} cold" for r in RUNS) + " | chi^2 hot | chi^2 cold | chi^2 |")
print("|---" * (2 * len(RUNS) + 4) + "|")
print("| measured | " + " | ".join(f"{m[0][0]:+.2f}+-{m[0][1]:.2f} | {m[1][0]:+.2f}+-{m[1][1]:.2f}" for m, _, _, _ in res.values()) + " | | | |")
for m in models:
    ch = sum(((o[m][0] - ms[0][0]) / ms[0][1]) ** 2 for ms, o, _, _ in res.values())
    cc = sum(((o[m][1] - ms[1][0]) / ms[1][1]) ** 2 for ms, o, _, _ in res.values())
    print(f"| {m} | " + " | ".join(f"{o[m][0]:+.3f} | {o[m][1]:+.3f}" for _, o, _, _ in res.values()) + f" | {ch:.1f} | {cc:.1f} | {ch+cc:.1f} |")
print("\nmeasured - variant, mean over seeds per c_v (hot, cold):")
for m in models:
    row = []
    for cv in (10, 20, 50):
        sel = [(ms, o) for ms, o, _, c in res.values() if c == cv]
        dh = np.mean([ms[0][0] - o[m][0] for ms, o in sel]); dc = np.mean([ms[1][0] - o[m][1] for ms, o in sel])
        row.append(f"c_v {cv}: {dh:+.2f} / {dc:+.2f}")
    print(f"  {m:16s} " + ";  ".join(row))
