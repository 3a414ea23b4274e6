#!/usr/bin/env python3
"""The runs of one case over seeds, each with its own transport stage and twins (a sweep over
Particle/Seed), against their stated errors: one row per run, then chi^2/dof of each stated
error over the runs and how many strict verdicts read "within errors".

    scripts/seed_table.py SWEEPDIR            (its points/*)
    scripts/seed_table.py RUNDIR RUNDIR ...

Everything is read from the runs' own files: particle/summary.json (the seed, the heat flow
across the heated pair of walls), compare/metrics.json (Nu, the wall jumps, the distances,
the strict verdict's `within_errors` and `beyond_errors`, the prediction tolerances) and
continuum/summary.json (the twin's kappa and heat flux error from its coefficients), compare/bins.csv (the
twin's fields, whose scatter over the runs is checked against compare's `noise_twin`)."""

import csv
import glob
import json
import math
import os
import sys


def read(path):
    with open(path) as f:
        return json.load(f)


def run_row(run_dir):
    """The numbers of one run directory."""
    summary = read(os.path.join(run_dir, "particle", "summary.json"))
    metrics = read(os.path.join(run_dir, "compare", "metrics.json"))
    twin = read(os.path.join(run_dir, "continuum", "summary.json"))
    particle, nominal = metrics["particle"], metrics["twins"]["nominal"]
    axis = "xyz"[twin["dimensionless"]["heated_direction"]]
    pair = summary["results"]["wall_pairs"][axis]
    jumps = particle["wall_temperature_jumps"]
    q0 = twin["dimensionless"]["conduction_flux"]
    q_twin = nominal["nusselt_own"] * q0
    return {
        "seed": summary["parameters"]["Particle/Seed"],
        "nu": (particle["nusselt"], particle["nusselt_stderr"]),
        # read alone, Nu also carries its conduction flux's kappa error (compare's field)
        "nu_alone": (particle["nusselt"],
                     particle.get("nusselt_stderr_with_conductivity", math.nan)),
        "kappa": tuple(twin["coefficient_uncertainty"].get("conductivity", {}).get(k, math.nan)
                       for k in ("value", "stderr")),
        "nu_twin": (nominal["nusselt"], nominal["nusselt_stderr_from_coefficients"]),
        "gap": nominal["nusselt_relative_difference"],
        "heat_flow": (pair["heat_flux"],
                      max([pair["heat_flux_stderr"]] + pair.get("heat_flux_stderr_blocking", []))),
        "twin_heat_flow": (q_twin,
                           twin["coefficient_uncertainty"]["heat_flux_relative_stderr"] * q_twin),
        "jumps": {w: (j["jump"], j["fluid_temperature_at_wall_stderr"]) for w, j in jumps.items()},
        "t_over_noise": nominal["temperature"]["l2"] / nominal["temperature"]["noise"],
        "v_over_noise": nominal["velocity"]["l2"] / nominal["velocity"]["noise"],
        "beyond": nominal.get("beyond_errors", []),
        "within": nominal["within_errors"],
        "prediction": metrics["prediction"]["pass"],
        "twin_fields": twin_fields(run_dir, metrics),
    }


def twin_fields(run_dir, metrics):
    """The nominal twin's interior bins (T, and the velocity vector) and their stated errors
    from its inputs (compare's noise_twin, in the fields' own units; None without)."""
    with open(os.path.join(run_dir, "compare", "bins.csv")) as f:
        bins = [b for b in csv.DictReader(line for line in f if not line.startswith("#"))
                if b["interior"] == "1"]
    nominal = metrics["twins"]["nominal"]
    velocity = [c for c in bins[0] if c.startswith("v") and c.endswith("_nominal")]

    def stated(name, scale):
        error = nominal.get(name, {}).get("noise_twin")
        return None if error is None else error * metrics[scale]

    return {"temperature": ([[float(b["T_nominal"])] for b in bins],
                            stated("temperature", "temperature_scale")),
            "velocity": ([[float(b[c]) for c in velocity] for b in bins],
                         stated("velocity", "velocity_scale"))}


def field_scatter(fields):
    """The runs' sample variance per bin (a vector's summed over its components), rms over the
    bins: what compare's noise_twin states for one run."""
    runs, total = len(fields), 0.0
    for b in range(len(fields[0])):
        for c in range(len(fields[0][b])):
            values = [f[b][c] for f in fields]
            mean = sum(values) / runs
            total += sum((v - mean) ** 2 for v in values) / (runs - 1)
    return math.sqrt(total / len(fields[0]))


def chi2_per_dof(pairs):
    """chi^2/dof of values with errors about their weighted mean, the sd and the rms error."""
    values, errors = [v for v, _ in pairs], [e for _, e in pairs]
    weights = [1 / e**2 for e in errors]
    mean = sum(w * v for w, v in zip(weights, values)) / sum(weights)
    dof = len(values) - 1
    chi2 = sum(((v - mean) / e) ** 2 for v, e in zip(values, errors)) / dof
    plain = sum(values) / len(values)
    sd = math.sqrt(sum((v - plain) ** 2 for v in values) / dof)
    rms = math.sqrt(sum(e * e for e in errors) / len(errors))
    return chi2, sd, rms


def chi2_range(dof):
    """The central 95% of chi^2/dof (Wilson & Hilferty 1931's cube-root normal approximation)."""
    k = 2 / (9 * dof)
    return tuple((1 - k + z * math.sqrt(k)) ** 3 for z in (-1.959964, 1.959964))


def pm(pair, digits=4):
    return f"{pair[0]:.{digits}f} +- {pair[1]:.{digits}f}"


def print_table(rows):
    walls = sorted(rows[0]["jumps"])
    print("| seed | Nu particle | Nu twin | gap | heat flow across | "
          + " | ".join(f"{w} jump % dT" for w in walls)
          + " | T L2 / noise | v L2 / noise | strict verdict (nominal) | prediction |")
    print("|---" * (9 + len(walls)) + "|")
    for r in rows:
        jumps = " | ".join(f"{100 * r['jumps'][w][0]:+.2f} +- {100 * r['jumps'][w][1]:.2f}"
                           for w in walls)
        verdict = "within errors" if r["within"] else ", ".join(r["beyond"]) + " beyond"
        print(f"| {r['seed']} | {pm(r['nu'])} | {pm(r['nu_twin'])} | {100 * r['gap']:+.1f}% | "
              f"{pm(r['heat_flow'])} | {jumps} | {r['t_over_noise']:.2f} | "
              f"{r['v_over_noise']:.2f} | {verdict} | {'met' if r['prediction'] else 'not met'} |")


def print_checks(rows):
    dof = len(rows) - 1
    low, high = chi2_range(dof)
    print(f"\nchi^2/dof over {len(rows)} runs (95% range {low:.3f}-{high:.3f}):")
    checks = [("heat flow across the heated walls", [r["heat_flow"] for r in rows]),
              ("the twin's heat flux (its coefficients' errors)",
               [r["twin_heat_flow"] for r in rows]),
              ("the twin's kappa (each run's transport stage)", [r["kappa"] for r in rows]),
              ("particle Nu (the heat flow's and its conduction flux's kappa errors)",
               [r["nu_alone"] for r in rows]),
              ("gap particle / twin - 1 (combined errors)",
               [(r["gap"], (1 + r["gap"]) * math.hypot(r["nu"][1] / r["nu"][0],
                                                      r["nu_twin"][1] / r["nu_twin"][0]))
                for r in rows])]
    checks += [(f"{w} jump", [r["jumps"][w] for r in rows]) for w in sorted(rows[0]["jumps"])]
    for name, pairs in checks:
        if not all(math.isfinite(e) for _, e in pairs):
            continue  # a run without the stated error (a twin on theory's coefficients)
        chi2, sd, rms = chi2_per_dof(pairs)
        inside = "inside" if low <= chi2 <= high else "OUTSIDE"
        print(f"- {name}: {chi2:.3f} ({inside}; sd {sd:.4g}, rms stated {rms:.4g})")
    for name in ("temperature", "velocity"):
        stated = [r["twin_fields"][name][1] for r in rows]
        if any(e is None for e in stated):
            continue
        scatter = field_scatter([r["twin_fields"][name][0] for r in rows])
        rms = math.sqrt(sum(e * e for e in stated) / len(stated))
        print(f"- the twin's {name} field over the runs' transport stages: scatter {scatter:.4g} "
              f"against its stated error {rms:.4g} (ratio {scatter / rms:.2f}; 1 when right)")
    for name in ("Nu", "temperature", "velocity"):
        within = sum(1 for r in rows if name not in r["beyond"])
        print(f"- strict verdict, {name} within errors: {within} of {len(rows)}")
    print(f"- prediction tolerances met: {sum(1 for r in rows if r['prediction'])} of {len(rows)}")


def main(arguments):
    if not arguments:
        sys.exit(__doc__)
    dirs = []
    for a in arguments:
        points = sorted(glob.glob(os.path.join(a, "points", "*")))
        dirs += points if points else [a]
    rows = [run_row(d) for d in dirs
            if os.path.exists(os.path.join(d, "compare", "metrics.json"))]
    if len(rows) < 2:
        sys.exit("seed_table.py: fewer than two finished runs in " + " ".join(arguments))
    print_table(rows)
    print_checks(rows)


if __name__ == "__main__":
    main(sys.argv[1:])
