#!/usr/bin/python3
"""Session 25 (read-only): decompose particle-minus-nominal-twin temperature differences
over compare's interior bins into a uniform offset, a plane and a residual.

Reads only /work/runs/s23/...; writes results.json / results.md beside this script.
compare's definitions (compare/twin_distance.cpp, finish()/field_distance()):
  l2    = sqrt(mean_b (T_p - T_c)^2) / scale
  noise = sqrt(mean_b sigma_b^2) / scale          (sigma_b = T_particle_se)
  over interior bins; scale = |T_wall0 - T_wall1| of the heated direction (metrics.json
  temperature_scale).  Prediction rule (metrics.cpp): pass if l2 <= 1.5 noise or l2 <= 0.01.
"""
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SUITE = "/work/runs/s23/suite"
CASES = [
    ("heated_cavity_2d (default_fresh)", "/work/runs/s23/default_fresh"),
    ("heated_cavity_2d_cv50", f"{SUITE}/heated_cavity_2d_cv50"),
    ("heated_cavity_2d_ra1e2", f"{SUITE}/heated_cavity_2d_ra1e2"),
    ("heated_cavity_2d_ra1e4", f"{SUITE}/heated_cavity_2d_ra1e4"),
    ("heated_cavity_2d_slip", f"{SUITE}/heated_cavity_2d_slip"),
    ("heated_cavity_2d_tall", f"{SUITE}/heated_cavity_2d_tall"),
    ("heated_cavity_2d_walls100x", f"{SUITE}/heated_cavity_2d_walls100x"),
    ("heated_cavity_2d_walls1x", f"{SUITE}/heated_cavity_2d_walls1x"),
    ("conduction_column_repulsive_2d", f"{SUITE}/conduction_column_repulsive_2d"),
    ("heated_cavity_3d", f"{SUITE}/heated_cavity_3d"),
    # supplementary: the newest heated_cavity_2d run (K=4 ensemble, twin-layer study)
    ("heated_cavity_2d (tw/layer3, K=4)", "/work/runs/s23/tw/layer3"),
]
AX = "xyz"


def read_bins(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    header = lines[0].strip().split(",")
    data = np.array([[float(v) for v in l.strip().split(",")] for l in lines[1:] if l.strip()])
    return {h: data[:, i] for i, h in enumerate(header)}


def read_blocks(path, nbins):
    """particle/blocks.csv -> array [block, bin] of T_kinetic (None if absent)."""
    if not os.path.exists(path):
        return None
    rows = np.loadtxt(path, delimiter=",", comments="#", skiprows=2)
    nb = int(rows[:, 0].max()) + 1
    out = np.full((nb, nbins), np.nan)
    out[rows[:, 0].astype(int), rows[:, 1].astype(int)] = rows[:, 2]
    return out


def wls(A, y, w):
    """Weighted least squares: coefficients, covariance (from the weights)."""
    Aw = A * w[:, None]
    M = A.T @ Aw
    cov = np.linalg.inv(M)
    return cov @ (Aw.T @ y), cov


def analyse(name, run):
    b = read_bins(f"{run}/compare/bins.csv")
    m = json.load(open(f"{run}/compare/metrics.json"))
    scale = m["temperature_scale"]
    Tm = m["twins"]["nominal"]["temperature"]
    dims = [a for a in AX if a in b]
    inter = b["interior"] == 1
    d_all = (b["T_particle"] - b["T_nominal"]) / scale
    s_all = b["T_particle_se"] / scale
    d, s = d_all[inter], s_all[inter]
    n = d.size
    l2 = np.sqrt(np.mean(d**2))
    noise = np.sqrt(np.mean(s**2))

    # walls: which directions vary (more than one bin centre) and the heated one
    jumps = m["particle"]["wall_temperature_jumps"]
    heated = jumps and sorted(jumps)[0][0]
    tw = {k: v["wall_temperature"] for k, v in jumps.items()}
    hot = max(tw, key=tw.get)
    cold = min(tw, key=tw.get)
    dT = abs(tw[hot] - tw[cold])
    varying = [a for a in dims if np.unique(b[a]).size > 1]

    # (a) offset: weighted mean (w = 1/se^2), error from the bins' errors as independent
    w = 1 / s**2
    off = np.sum(w * d) / np.sum(w)
    off_se = 1 / np.sqrt(np.sum(w))
    off_unw = d.mean()
    off_unw_se = np.sqrt(np.sum(s**2)) / n
    r0 = d - off
    l2_off = np.sqrt(np.mean(r0**2))
    l2_off_u = np.sqrt(np.mean((d - off_unw) ** 2))  # the L2-minimising offset

    # cross-check of the offset's error from the particle blocks (bins' correlations included)
    blocks = read_blocks(f"{run}/particle/blocks.csv", d_all.size)
    blk = None
    if blocks is not None and not np.isnan(blocks).any():
        bm = blocks.mean(axis=0)
        # block means reproduce T_particle?  (bins.csv order == fields.csv order)
        repro = float(np.max(np.abs(bm - b["T_particle"])))
        se_b = blocks.std(axis=0, ddof=1) / np.sqrt(blocks.shape[0])
        db = (blocks[:, inter] - b["T_nominal"][inter]) / scale
        per_block_off = db.mean(axis=1)
        per_block_woff = (db * w).sum(axis=1) / w.sum()
        nbk = blocks.shape[0]
        blk = {
            "blocks": nbk,
            "max_abs_blockmean_minus_T_particle": repro,
            "max_rel_se_mismatch": float(np.max(np.abs(se_b - b["T_particle_se"]) / b["T_particle_se"])),
            "offset_unweighted_block_se": float(per_block_off.std(ddof=1) / np.sqrt(nbk)),
            "offset_weighted_block_se": float(per_block_woff.std(ddof=1) / np.sqrt(nbk)),
        }
        # merged blocks (pairs, quadruples) like compare's blocking of wall temperatures
        for k in (2, 4):
            nk = nbk // k
            if nk >= 3:
                for lab, pb in (("unweighted", per_block_off), ("weighted", per_block_woff)):
                    mk = pb[: nk * k].reshape(nk, k).mean(axis=1)
                    blk[f"offset_{lab}_block_se_merge{k}"] = float(mk.std(ddof=1) / np.sqrt(nk))

    # (b) plane: weighted fit d = c0 + sum_a c_a (x_a - mean)
    cols = [np.ones(n)] + [b[a][inter] - b[a][inter].mean() for a in varying]
    A = np.column_stack(cols)
    coef, cov = wls(A, d, w)
    r1 = d - A @ coef
    l2_plane = np.sqrt(np.mean(r1**2))
    # unweighted (the L2-minimising) versions, for reference
    coef_u, *_ = np.linalg.lstsq(A, d, rcond=None)
    l2_plane_u = np.sqrt(np.mean((d - A @ coef_u) ** 2))
    # slopes in units of dT across the box length (coefficient * length of the interior span)
    slopes = {}
    for i, a in enumerate(varying):
        span = np.ptp(b[a][inter])
        slopes[a] = {"per_unit_length": float(coef[i + 1]), "se": float(np.sqrt(cov[i + 1, i + 1])),
                     "across_interior_span": float(coef[i + 1] * span),
                     "across_interior_span_se": float(np.sqrt(cov[i + 1, i + 1]) * span),
                     "interior_span": float(span)}

    # (3) near-wall columns: hot and cold wall of the heated direction. Two layers reported:
    #  'wall': the outermost bin layer (touching the wall; excluded from the interior),
    #  'first_interior': the interior bins nearest the wall.
    # Along the wall only bins inside the interior range of the other walled directions.
    hd = hot[0]
    other = [a for a in varying if a != hd]
    lo_other = {a: (b[a][inter].min(), b[a][inter].max()) for a in other}
    along = np.ones(d_all.size, bool)
    for a in other:
        along &= (b[a] >= lo_other[a][0] - 1e-9) & (b[a] <= lo_other[a][1] + 1e-9)
    xs = np.unique(b[hd])
    xi = np.unique(b[hd][inter])
    walls = {}
    for label, wname in (("hot", hot), ("cold", cold)):
        lower = wname.endswith("lower")
        layers = {"wall": xs[0] if lower else xs[-1], "first_interior": xi[0] if lower else xi[-1]}
        walls[label] = {"wall": wname, "T_wall": tw[wname]}
        for lname, xc in layers.items():
            sel = along & np.isclose(b[hd], xc)
            ww = 1 / s_all[sel] ** 2
            mu = np.sum(ww * d_all[sel]) / np.sum(ww)
            mu_se = 1 / np.sqrt(np.sum(ww))
            walls[label][lname] = {
                "coordinate": float(xc), "bins": int(sel.sum()),
                "mean": float(mu), "se": float(mu_se),
                "minus_interior_mean": float(mu - off),
                "minus_interior_mean_se": float(np.hypot(mu_se, off_se)),
            }

    return {
        "case": name, "run": run, "scale": scale, "dT_walls": dT, "hot_wall": hot, "cold_wall": cold,
        "dims": dims, "varying": varying, "interior_bins": int(n),
        "compare": {"l2": Tm["l2"], "noise": Tm["noise"], "l2_over_noise": Tm["l2"] / Tm["noise"],
                    "pass": m["prediction"]["temperature"]["pass"]},
        "repro": {"l2": float(l2), "noise": float(noise),
                  "l2_match_3sig": f"{l2:.3g}" == f"{Tm['l2']:.3g}",
                  "noise_match_3sig": f"{noise:.3g}" == f"{Tm['noise']:.3g}",
                  "l2_rel_diff": float(l2 / Tm["l2"] - 1), "noise_rel_diff": float(noise / Tm["noise"] - 1)},
        "offset": {"weighted": float(off), "weighted_se": float(off_se),
                   "unweighted": float(off_unw), "unweighted_se": float(off_unw_se),
                   "blocks": blk},
        "l2_minus_offset": float(l2_off), "l2_minus_offset_over_noise": float(l2_off / noise),
        "l2_minus_unweighted_offset_over_noise": float(l2_off_u / noise),
        "pass_after_unweighted_offset": bool(l2_off_u <= 1.5 * noise or l2_off_u <= 0.01),
        "pass_after_offset_by": ("noise" if l2_off <= 1.5 * noise else "") + ("+" if l2_off <= 1.5 * noise and l2_off <= 0.01 else "") + ("abs" if l2_off <= 0.01 else ""),
        "l2_minus_offset_abs": float(l2_off), "l2_minus_plane_abs": float(l2_plane),
        "l2_minus_plane": float(l2_plane), "l2_minus_plane_over_noise": float(l2_plane / noise),
        "l2_minus_plane_unweighted_fit_over_noise": float(l2_plane_u / noise),
        # expected L2/noise of pure noise after fitting p parameters: sqrt((n-p)/n)
        "pure_noise_expect_minus_offset": float(np.sqrt((n - 1) / n)),
        "pure_noise_expect_minus_plane": float(np.sqrt((n - A.shape[1]) / n)),
        "plane_slopes": slopes,
        "pass_after_offset": bool(l2_off <= 1.5 * noise or l2_off <= 0.01),
        "pass_after_plane": bool(l2_plane <= 1.5 * noise or l2_plane <= 0.01),
        "walls": walls,
    }


def main():
    res = [analyse(n, r) for n, r in CASES]
    json.dump(res, open(os.path.join(HERE, "results.json"), "w"), indent=1)
    out = []
    out.append("| case | n | compare L2 / noise (L2, noise) | repro L2, noise match | offset %dT (w) +- se [block se] | "
               "L2-off / noise | L2-plane / noise | pass as is | pass after offset | pass after plane | "
               "unweighted offset %dT +- block se | L2-unw.off / noise | pass after unw. offset |")
    out.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in res:
        c, o = r["compare"], r["offset"]
        bse = o["blocks"]
        bse_s = "-" if not bse else "%.2f" % (100 * max(v for k, v in bse.items() if k.startswith("offset_weighted")))
        out.append(
            f"| {r['case']} | {r['interior_bins']} | {c['l2_over_noise']:.2f} ({c['l2']:.4f}, {c['noise']:.4f}) | "
            f"{'yes' if r['repro']['l2_match_3sig'] and r['repro']['noise_match_3sig'] else 'NO'} | "
            f"{100*o['weighted']:+.2f} +- {100*o['weighted_se']:.2f} [{bse_s}] | "
            f"{r['l2_minus_offset_over_noise']:.2f} | {r['l2_minus_plane_over_noise']:.2f} | "
            f"{'yes' if c['pass'] else 'no'} | {'yes' if r['pass_after_offset'] else 'no'} | "
            f"{'yes' if r['pass_after_plane'] else 'no'} | "
            f"{100*o['unweighted']:+.2f} +- {100*max(v for k, v in bse.items() if k.startswith('offset_unweighted')):.2f} | "
            f"{r['l2_minus_unweighted_offset_over_noise']:.2f} | {'yes' if r['pass_after_unweighted_offset'] else 'no'} |")
    out.append("")
    for r in res:
        out.append(f"- {r['case']}: L2 after offset {r['l2_minus_offset_abs']:.4f} ({r['pass_after_offset_by'] or 'fails'}), "
                   f"after plane {r['l2_minus_plane_abs']:.4f}; noise {r['repro']['noise']:.4f}")
    out.append("")
    out.append("| case | plane slopes (%dT across the interior span, +- se) | hot wall layer - interior mean (%dT) | "
               "hot first interior - mean | cold wall layer - mean | cold first interior - mean |")
    out.append("|---|---|---|---|---|---|")
    for r in res:
        sl = "; ".join(f"{a}: {100*v['across_interior_span']:+.2f} +- {100*v['across_interior_span_se']:.2f}"
                       for a, v in r["plane_slopes"].items())
        wv = lambda side, layer: (f"{100*r['walls'][side][layer]['minus_interior_mean']:+.2f} +- "
                                  f"{100*r['walls'][side][layer]['minus_interior_mean_se']:.2f}")
        out.append(f"| {r['case']} | {sl} | {wv('hot','wall')} | {wv('hot','first_interior')} | "
                   f"{wv('cold','wall')} | {wv('cold','first_interior')} |")
    text = "\n".join(out)
    open(os.path.join(HERE, "results.md"), "w").write(text + "\n")
    print(text)
    for r in res:
        print(r["case"], "repro", r["repro"], "unweighted offset %.4f +- %.4f" %
              (r["offset"]["unweighted"], r["offset"]["unweighted_se"]), "blocks", r["offset"]["blocks"],
              "plane unweighted/noise %.2f" % r["l2_minus_plane_unweighted_fit_over_noise"],
              "expect %.3f %.3f" % (r["pure_noise_expect_minus_offset"], r["pure_noise_expect_minus_plane"]),
              "hot", r["hot_wall"], "dT", r["dT_walls"], "scale", r["scale"])


if __name__ == "__main__":
    main()
