#!/usr/bin/env python3
"""One markdown row per run directory: the nominal twin against the particles (Nu, temperature,
velocity and density L2 with their standard errors and noise, from compare/metrics.json) and the
zero of the horizontal velocity on the vertical mid-line (compare/profiles.csv), the particle's
with its standard error.

usage: scripts/twin_table.py RUNDIR [RUNDIR ...]   (each a finished `twinflow run` directory)

The zero: the sign change of u_x along y through the box centre nearest mid-height, linear
between the two bins around it, y0 = y1 + h v1 / (v1 - v2); its error from the bins' block
errors, first order: h / (v1 - v2)^2 sqrt(v2^2 se1^2 + v1^2 se2^2).
"""
import csv
import json
import math
import sys


def midline_rows(run_dir):
    with open(f"{run_dir}/compare/profiles.csv") as f:
        lines = [line for line in f if not line.startswith("#")]
    return [r for r in csv.DictReader(lines) if r["direction"] == "y"]


def zero_crossing(ys, vs, ses=None):
    """The sign change of v(y) nearest the middle of the y range: (y0, se), or (nan, nan)."""
    middle = 0.5 * (ys[0] + ys[-1])
    best = (math.nan, math.nan)
    for k in range(len(ys) - 1):
        v1, v2 = vs[k], vs[k + 1]
        if v1 == 0 or v1 * v2 > 0:
            continue
        h = ys[k + 1] - ys[k]
        y0 = ys[k] + h * v1 / (v1 - v2)
        se = math.nan
        if ses is not None:
            se = h / (v1 - v2) ** 2 * math.hypot(v2 * ses[k], v1 * ses[k + 1])
        if math.isnan(best[0]) or abs(y0 - middle) < abs(best[0] - middle):
            best = (y0, se)
    return best


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("| run | twin model | Nu particle | Nu twin | gap | T L2 (noise) | velocity L2 (noise) | "
          "density L2 (noise) | u_x zero particle | u_x zero twin | bin |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for run_dir in sys.argv[1:]:
        m = json.load(open(f"{run_dir}/compare/metrics.json"))
        summary = json.load(open(f"{run_dir}/continuum/summary.json"))
        model = summary["continuum_parameters"]["model"]
        twin = m["twins"]["nominal"]
        particle = m["particle"]

        def l2(field):
            if field not in twin:
                return "—"
            t = twin[field]
            return f"{t['l2']:.4f} +- {t['l2_stderr']:.4f} ({t['noise']:.4f})"

        rows = midline_rows(run_dir)
        ys = [float(r["coordinate"]) for r in rows]
        zp, zp_se = zero_crossing(ys, [float(r["vx_particle"]) for r in rows],
                                  [float(r["vx_particle_se"]) for r in rows])
        zt, _ = zero_crossing(ys, [float(r["vx_nominal"]) for r in rows])
        bin_width = ys[1] - ys[0]
        nu_p, nu_t = particle["nusselt"], twin["nusselt"]
        se = twin.get("nusselt_stderr_from_coefficients")
        nu_t_se = f" +- {se:.3f}" if isinstance(se, float) and math.isfinite(se) else ""
        print(f"| {run_dir} | {model} | {nu_p:.3f} +- {particle['nusselt_stderr']:.3f} | "
              f"{nu_t:.3f}{nu_t_se} | {nu_p / nu_t - 1:+.1%} | {l2('temperature')} | {l2('velocity')} | "
              f"{l2('density')} | {zp:.2f} +- {zp_se:.2f} | {zt:.2f} | {bin_width:g} |")


if __name__ == "__main__":
    main()
