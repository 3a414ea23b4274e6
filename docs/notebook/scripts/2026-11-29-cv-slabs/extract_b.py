#!/usr/bin/python3
"""Hot and cold wall extrapolation lengths b of a wall slab, as the 2026-11-27 wall slabs took them
(docs/validation.md, "Walls from theory"): b = jump / |slope at the centre| in rc, from the particle
run's own `wall_profile` (particle/diagnostics/walls.cpp wall_profile_fit: a parabola through
T_internal over the bins beyond one cutoff from each wall, carried to the wall, jump = T_wall - that
value; the slope at the centre from a parabola over the central 60%; errors the largest of the
fit's and the blocks' (1, 2, 4 merged)). Sign: b > 0 when the bulk, carried to the plane, has not
reached T_wall (a Kapitza-like resistance): hot b = +jump_lower, cold b = -jump_upper (walls
1.4 lower / 0.6 upper), over |slope|.

Also prints what the predictions need, measured on the same run:
  kappa at the centre = |q| / |slope| (q: wall_pairs heat flux across the pair, as
      transport/wall_kappa.cpp), and at each wall: q over the central-60% parabola's slope carried
      to the plane (the bulk's kappa(T) at T_w, free of the wall layers if they end within 4 rc:
      the input --predict takes), q over the [rc, L - rc] parabola's slope there, and q over a line
      through T_internal in the 3 rc window beyond one cutoff ([1, 4] rc; inside the layer when
      ell is long);
  the density at each wall (bins within the first cutoff, the window [1, 2] rc, and p / T_w with
      p = n T_kinetic over the bulk);
  the pair part over theory's (J_conductive / (-dT/dx) / (0.262 n^2), median over bins in
      [2, L-2] rc, and in the wall windows), the number predict.py takes as --pair-factor.
fields.csv (T_internal and its _se, density, T_kinetic, J_conductive_*) is read when present; the
jumps are refitted from it (fit errors only) as a check on the summary's.

Usage: /usr/bin/python3 extract_b.py RUNDIR [RUNDIR ...] [--predict] [--json OUT.json]
  RUNDIR: a run directory (RUNDIR/particle/summary.json), a particle/ directory, or any summary.json
  holding a wall_profile (a transport stage's Kappa-from-walls summary too: no fields there).
  --predict: the models of predict.py at this run's c_v, f, wall temperatures and measured kappa,
  wall density and pair part, against the measured b."""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def find(o, key):
    """first dict under o (depth first) holding key."""
    if isinstance(o, dict):
        if key in o:
            return o
        for v in o.values():
            r = find(v, key)
            if r is not None:
                return r
    return None


def locate(path):
    for c in (os.path.join(path, "particle", "summary.json"), os.path.join(path, "summary.json"), path):
        if os.path.isfile(c) and c.endswith(".json"):
            return c
    raise SystemExit(f"extract_b: no summary.json at {path}")


def read_fields(directory):
    f = os.path.join(directory, "fields.csv")
    if not os.path.isfile(f):
        return None
    with open(f) as fh:
        rows = [r for r in csv.reader(l for l in fh if not l.startswith("#"))]
    head, data = rows[0], np.array([[float(x) for x in r] for r in rows[1:]])
    return {h: data[:, i] for i, h in enumerate(head)}


def wfit(x, y, se, deg, centre):
    """the weighted polynomial fit of statistics::QuadraticFit / LineFit (weights 1/se^2), about centre;
    returns coefficients (highest first) and their covariance."""
    X = np.vander(x - centre, deg + 1)
    w = 1 / np.maximum(se, 1e-300) ** 2
    A = X.T @ (X * w[:, None])
    cov = np.linalg.inv(A)
    c = cov @ (X.T @ (w * y))
    return c, cov


def val(c, cov, x):
    v = np.vander(np.atleast_1d(x), len(c))[0]
    return float(v @ c), float(math.sqrt(max(v @ cov @ v, 0)))


def dval(c, cov, x):
    """derivative and its error at x (relative to the fit's centre)."""
    n = len(c) - 1
    v = np.array([(n - i) * x ** (n - i - 1) if n - i > 0 else 0.0 for i in range(n + 1)])
    return float(v @ c), float(math.sqrt(max(v @ cov @ v, 0)))


def analyse(path):
    sfile = locate(path)
    d = json.load(open(sfile))
    res = d.get("results", d)
    holder = find(res, "wall_profile")
    if holder is None:
        raise SystemExit(f"extract_b: {sfile} holds no wall_profile (walls at two temperatures, bins across them only)")
    wp = holder["wall_profile"]
    par = d.get("parameters", {})
    axis = "xyz"[int(wp["direction"])]
    box = [float(x) for x in par["Scene/Box size"].split(",")]
    length = box[int(wp["direction"])]
    if "box" in holder:  # a transport wall slab: its own box
        length = float(holder["box"][int(wp["direction"])])
    Tl = float(par[f"Scene/{axis} boundaries/Lower wall temperature"])
    Tu = float(par[f"Scene/{axis} boundaries/Upper wall temperature"])
    slope, se_slope = wp["slope"], wp["slope_stderr"]
    out = {"summary": sfile, "axis": axis, "length": length, "T_lower": Tl, "T_upper": Tu,
           "cv": float(par.get("Particle/Internal energy/Heat capacity", "nan")),
           "kappa0": float(par.get("Particle/Heat conduction/kappa0", "nan")),
           "f": float(str(par.get("Particle/Walls/Heat conduction", "nan")).split(",")[0]),
           "dt": float(par.get("Particle/Time step", "nan")),
           "seed": par.get("Particle/Seed"),
           "heat_coefficient": par.get("Particle/Heat conduction/Coefficient"),
           "conservative": par.get("Particle/Conservative force/Type"),
           "slope": slope, "slope_stderr": se_slope, "T_centre": wp["temperature_at_centre"]}
    # b per wall, hot first
    walls = []
    for side, Tw, jump, se, se_fit in (("lower", Tl, wp["jump_lower"], wp["jump_lower_stderr"], wp["jump_lower_stderr_fit"]),
                                       ("upper", Tu, wp["jump_upper"], wp["jump_upper_stderr"], wp["jump_upper_stderr_fit"])):
        hot = Tw > wp["temperature_at_centre"]
        s = 1.0 if hot else -1.0
        b = s * jump / abs(slope)
        walls.append({"name": "hot" if hot else "cold", "side": side, "T_wall": Tw, "jump": jump,
                      "jump_stderr": se, "b": b, "b_stderr": se / abs(slope),
                      "b_stderr_with_slope": math.hypot(se / abs(slope), b * se_slope / abs(slope)),
                      "b_stderr_fit": se_fit / abs(slope)})
    out["walls"] = {w["name"]: w for w in walls}
    # heat flow across the pair and kappa at the centre
    q = se_q = None
    wpair = res.get("wall_pairs", {}).get(axis)
    if wpair is not None:
        q, se_q = wpair["heat_flux"], wpair["heat_flux_stderr"]
    elif "heat_flux" in holder:
        q, se_q = holder["heat_flux"], holder["heat_flux_stderr"]
    if q is not None:
        out["q"], out["q_stderr"] = q, se_q
        k = abs(q / slope)
        out["kappa_centre"] = k
        out["kappa_centre_stderr"] = k * math.hypot(se_q / q, se_slope / slope)
        wl = res.get("walls", {})
        lo, up = wl.get(f"{axis}_lower", {}), wl.get(f"{axis}_upper", {})
        if "heat_flux_in" in lo and "heat_flux_in" in up:
            out["wall_flows_in"] = (lo["heat_flux_in"], up["heat_flux_in"])
    for k in ("particle_steps_per_second", "wall_seconds", "energy_relative_drift_max", "N", "steps",
              "equilibration_steps"):
        if k in res:
            out[k] = res[k]
    # fields
    fl = read_fields(os.path.dirname(sfile))
    if fl is not None:
        x = fl[axis]
        o = np.argsort(x)
        x = x[o]
        T, Tse = fl["T_internal"][o], fl["T_internal_se"][o]
        n, Tk = fl["density"][o], fl["T_kinetic"][o]
        J = fl.get(f"J_conductive_{axis}")
        J = None if J is None else J[o]
        centre = length / 2
        layer = min(1.0, 0.25 * length)
        mb = (x >= layer) & (x <= length - layer)
        cb, covb = wfit(x[mb], T[mb], Tse[mb], 2, centre)
        mm = (x >= 0.2 * length) & (x <= 0.8 * length)
        cm, covm = wfit(x[mm], T[mm], Tse[mm], 2, centre)
        sl_fit = dval(cm, covm, 0.0)[0]
        v0, v0se = val(cb, covb, -centre)
        vL, vLse = val(cb, covb, centre)
        out["bin_width"] = float(np.median(np.diff(x)))
        out["refit"] = {"slope": sl_fit, "jump_lower": Tl - v0, "jump_upper": Tu - vL,
                        "jump_lower_stderr_fit": v0se, "jump_upper_stderr_fit": vLse}
        # the blocks' errors against the fit's (the summary's ratio): inflate the fields' fit errors
        infl = max(1.0, se_slope / max(wp.get("slope_stderr_fit", se_slope), 1e-300))
        out["block_over_fit_slope_error"] = infl
        # pressure over the bulk (ideal fluid: p = n k T_kinetic)
        pb = n[mb] * Tk[mb]
        p = float(np.median(pb))
        out["pressure_nT"] = p
        for w in walls:
            at_lower = w["side"] == "lower"
            h = x if at_lower else length - x
            near = h <= 1.0
            win12 = (h >= 1.0) & (h <= 2.0)
            win = (h >= 1.0) & (h <= 4.0)
            cl, covl = wfit(x[win], T[win], Tse[win], 1, float(np.mean(x[win])))
            sl, sl_se = cl[0], math.sqrt(covl[0, 0]) * infl
            dp, dp_se = dval(cb, covb, (0.0 if at_lower else length) - centre)
            T_win = float(np.mean(T[win]))
            r = {"n_first_cutoff": float(np.mean(n[near])), "n_1_2": float(np.mean(n[win12])),
                 "n_isobar_Tw": p / w["T_wall"], "T_window_1_4": T_win}
            dm, dm_se = dval(cm, covm, (0.0 if at_lower else length) - centre)
            if q is not None:
                r["kappa_bulk_at_wall"] = abs(q / dm)
                r["kappa_bulk_at_wall_stderr"] = abs(q / dm) * math.hypot(se_q / q, dm_se * infl / dm)
                r["kappa_window_1_4"] = abs(q / sl)
                r["kappa_window_1_4_stderr"] = abs(q / sl) * math.hypot(se_q / q, sl_se / sl)
                r["kappa_at_plane"] = abs(q / dp)
                r["kappa_at_plane_stderr"] = abs(q / dp) * math.hypot(se_q / q, dp_se * infl / dp)
            if J is not None:
                grad = np.array([dval(cb, covb, xx - centre)[0] for xx in x])
                kp_th = 0.262 * n ** 2
                ratio = J / (-grad) / kp_th
                r["pair_factor_window_1_4"] = float(np.median(ratio[win]))
            w.update(r)
        if J is not None:
            grad = np.array([dval(cb, covb, xx - centre)[0] for xx in x])
            ratio = J / (-grad) / (0.262 * n ** 2)
            mi = (x >= 2.0) & (x <= length - 2.0)
            out["pair_factor_median"] = float(np.median(ratio[mi]))
            out["pair_factor_quartiles"] = [float(np.percentile(ratio[mi], 25)), float(np.percentile(ratio[mi], 75))]
    return out


def report(o):
    print(f"# {o['summary']}")
    print(f"c_v {o['cv']:g}, kappa0 {o['kappa0']:g} (lambda = kappa0 c_v^2 = {o['kappa0'] * o['cv'] ** 2:g}), "
          f"wall conduction f {o['f']:g}, dt {o['dt']:g}, seed {o['seed']}; walls {o['T_lower']:g} / {o['T_upper']:g} "
          f"along {o['axis']} ({o['length']:g} rc)")
    if "N" in o:
        print(f"N {o['N']}, steps {o.get('equilibration_steps', '?')} + {o.get('steps', '?')}, wall {o.get('wall_seconds', 0):.0f} s, "
              f"{o.get('particle_steps_per_second', 0):.3g} particle-steps/s, energy drift {o.get('energy_relative_drift_max', float('nan')):.2g}")
    print(f"slope at the centre {o['slope']:.5f} +- {o['slope_stderr']:.5f}, T_centre {o['T_centre']:.4f}")
    if "kappa_centre" in o:
        print(f"q across the pair {o['q']:.4f} +- {o['q_stderr']:.4f}"
              + (f" (walls in: {o['wall_flows_in'][0]:+.4f}, {o['wall_flows_in'][1]:+.4f})" if "wall_flows_in" in o else "")
              + f"; kappa at the centre = |q / slope| = {o['kappa_centre']:.3f} +- {o['kappa_centre_stderr']:.3f}")
    print("| wall | T_w | jump | b (rc) | +- (blocks) | +- (with slope) | +- (fit only) |")
    print("|---|---|---|---|---|---|---|")
    for name in ("hot", "cold"):
        w = o["walls"][name]
        print(f"| {name} | {w['T_wall']:g} | {w['jump']:+.5f} +- {w['jump_stderr']:.5f} | **{w['b']:+.3f}** | {w['b_stderr']:.3f} "
              f"| {w['b_stderr_with_slope']:.3f} | {w['b_stderr_fit']:.3f} |")
    if "refit" in o:
        r = o["refit"]
        print(f"refit from fields.csv (fit errors): slope {r['slope']:.5f}, jumps {r['jump_lower']:+.5f} +- {r['jump_lower_stderr_fit']:.5f}"
              f" / {r['jump_upper']:+.5f} +- {r['jump_upper_stderr_fit']:.5f} (summary: {o['walls']['hot' if o['T_lower'] > o['T_upper'] else 'cold']['jump']:+.5f}"
              f" / {o['walls']['cold' if o['T_lower'] > o['T_upper'] else 'hot']['jump']:+.5f})")
        print(f"bulk pressure n T_kinetic {o['pressure_nT']:.4f}; pair part / theory (0.262 n^2): median {o.get('pair_factor_median', float('nan')):.3f}"
              f" (quartiles {o.get('pair_factor_quartiles', [float('nan')] * 2)[0]:.3f}-{o.get('pair_factor_quartiles', [float('nan')] * 2)[1]:.3f})")
        print("kappa at each wall: 'central' = q over the central-60% parabola's slope carried to the plane (the bulk's"
              " kappa(T) at T_w, the predictions' input); 'bulk' = the [rc, L-rc] parabola's; '1-4 rc' = a line in the"
              " window (inside the wall layer when ell is long)")
        print("| wall | n (first cutoff) | n (1-2 rc) | p / T_w | T (1-4 rc) | kappa central | kappa (1-4 rc line) | kappa bulk | pair / theory (1-4 rc) |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name in ("hot", "cold"):
            w = o["walls"][name]
            kw = f"{w['kappa_window_1_4']:.2f} +- {w['kappa_window_1_4_stderr']:.2f}" if "kappa_window_1_4" in w else "-"
            kp = f"{w['kappa_at_plane']:.2f} +- {w['kappa_at_plane_stderr']:.2f}" if "kappa_at_plane" in w else "-"
            kc = f"{w['kappa_bulk_at_wall']:.2f} +- {w['kappa_bulk_at_wall_stderr']:.2f}" if "kappa_bulk_at_wall" in w else "-"
            print(f"| {name} | {w['n_first_cutoff']:.3f} | {w['n_1_2']:.3f} | {w['n_isobar_Tw']:.3f} | {w['T_window_1_4']:.3f} | {kc} | {kw} | {kp} "
                  f"| {w.get('pair_factor_window_1_4', float('nan')):.3f} |")
    else:
        print("(no fields.csv beside the summary: no wall densities, local kappa or pair part)")


def predict_against(o):
    sys.path.insert(0, HERE)
    import predict as P
    hot, cold = o["walls"]["hot"], o["walls"]["cold"]
    if "kappa_bulk_at_wall" not in hot:
        print("--predict needs fields.csv (local kappa and densities)")
        return
    kh, kc = hot["kappa_bulk_at_wall"], cold["kappa_bulk_at_wall"]
    nh, nc = hot["n_1_2"], cold["n_1_2"]
    pf = o.get("pair_factor_median")
    lam = o["kappa0"] * o["cv"] ** 2
    if abs(lam - 10) > 1e-6 or o.get("heat_coefficient") != "seed-002" or o.get("conservative") != "none":
        print(f"WARNING: the models take the default fluid (seed-002 law, lambda 10, no conservative force); this run: "
              f"{o.get('heat_coefficient')}, lambda {lam:g}, conservative force {o.get('conservative')}")
    models = ["built", "c0", "c3", "c3+c0", "ell1.5"]
    print(f"\n## models at c_v {o['cv']:g}, f {o['f']:g}, walls {hot['T_wall']:g} / {cold['T_wall']:g}, with this run's kappa "
          f"{kh:.2f} / {kc:.2f} (central parabola at the planes), n {nh:.2f} / {nc:.2f} (1-2 rc), pair factor {pf:.3f}")
    r = P.predict(o["cv"], o["f"], kh, kc, pf, models, n=(nh, nc), T=(hot["T_wall"], cold["T_wall"]),
                  slab_length=o["length"], bin_width=o["bin_width"])
    score = {}
    print("| model | hot b (slab reading) | (b - meas) / err | cold b (slab reading) | (b - meas) / err |")
    print("|---|---|---|---|---|")
    print(f"| measured | {hot['b']:+.3f} +- {hot['b_stderr']:.3f} | | {cold['b']:+.3f} +- {cold['b_stderr']:.3f} | |")
    for m in models:
        bh, bc = r.get((m, "hot", "slab"), r[(m, "hot")]), r.get((m, "cold", "slab"), r[(m, "cold")])
        zh, zc = (bh - hot['b']) / hot['b_stderr'], (bc - cold['b']) / cold['b_stderr']
        score[m] = (zh, zc)
        print(f"| {m} | {r[(m, 'hot')]:+.3f} ({bh:+.3f}) | {zh:+.1f} "
              f"| {r[(m, 'cold')]:+.3f} ({bc:+.3f}) | {zc:+.1f} |")
    return score


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--predict", action="store_true")
    ap.add_argument("--json")
    a = ap.parse_args()
    allo, scores = [], []
    for r in a.runs:
        o = analyse(r)
        report(o)
        if a.predict:
            sc = predict_against(o)
            if sc:
                scores.append((o, sc))
                o["scores"] = {m: list(v) for m, v in sc.items()}
        print()
        allo.append(o)
    if len(scores) > 1:
        print("## the pre-registered score: chi^2 of the slab readings over the runs (hot, cold, both)")
        print("| model | hot chi^2 | cold chi^2 | total | points |")
        print("|---|---|---|---|---|")
        for m in scores[0][1]:
            h = sum(sc[m][0] ** 2 for _, sc in scores)
            c = sum(sc[m][1] ** 2 for _, sc in scores)
            print(f"| {m} | {h:.1f} | {c:.1f} | {h + c:.1f} | {2 * len(scores)} |")
    if a.json:
        json.dump(allo, open(a.json, "w"), indent=1, default=float)


if __name__ == "__main__":
    main()
