#!/usr/bin/python3
"""One common ell for both walls = s x (centre-state ell), built half-space layers otherwise; chi^2 over the 10 readings vs s."""
import sys; import os; sys.path.insert(0, os.path.dirname(os.path.abspath(__file__))); sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "2026-11-29-cv-slabs"))
import numpy as np, slab as S, layer as L, predict as P
RUNS = ["cv10_s2", "cv10_s3", "cv20_s1", "cv50_s1", "cv50_s2"]
data = []
for r in RUNS:
    st = S.state_from_run(f"/work/runs/s24/cvslab/{r}"); o = st["o"]; hot, cold = o["walls"]["hot"], o["walls"]["cold"]
    ellc = float(S.fields_on(st, np.array([st["L"] / 2]))["ell"][0])
    data.append((o, hot, cold, ellc))
for s in (0.7, 0.85, 1.0, 1.15, 1.3, 1.5):
    ch = cc = 0; row = []
    for o, hot, cold, ellc in data:
        prof = [L.solve_wall_layer(P.inputs(sd, o["cv"], w["kappa_bulk_at_wall"], o["f"], w["n_1_2"], T), ell=s * ellc, return_profile=True)
                for sd, w, T in (("hot", hot, 1.4), ("cold", cold, 0.6))]
        bh, bc = P.slab_reading(prof[0], prof[1], 20.0, o["bin_width"])
        ch += ((bh - hot["b"]) / hot["b_stderr"]) ** 2; cc += ((bc - cold["b"]) / cold["b_stderr"]) ** 2
        row.append(f"{bh:+.2f}/{bc:+.2f}")
    print(f"s {s:.2f}: chi2 hot {ch:.1f} cold {cc:.1f} total {ch+cc:.1f}  ", " ".join(row), flush=True)
