"""The report of a sweep directory (DIR/sweep.csv + DIR/sweep.json, written by `twinflow sweep`):
the grid, Nusselt numbers, twin distances and cost against the varied key (or Ra), the Pareto
front of error against cost, realisations over seeds, and the points not done."""

import math
import os

from .data import (AXES, TWIN_LABEL, TWINS, UNITS_NOTE, Table, cell, finite, fmt, fmt_percent,
                   fmt_pm, lookup, plain, read_json, slug, study_case_name, to_float, varied_keys,
                   with_unit)
from .document import Document, write_documents
from .figures import COLOUR, Axis, plain_log_ticks, save_figure

SWEEP_OWN_COLUMNS = ("target_rayleigh", "gravity", "wall_seconds")
# de Vahl Davis (1983), Int. J. Numer. Meth. Fluids 3, 249: Boussinesq cavity, no-slip walls,
# Pr = 0.71, mean Nusselt number.
DE_VAHL_DAVIS_NUSSELT = ((1e3, 1.118), (1e4, 2.243), (1e5, 4.519), (1e6, 8.800))


def metric(row, column):
    """A cell of one of the points' metrics ("" when absent). sweep.csv always has its own
    columns (point, status, reason, exit_code, the varied keys, target_rayleigh, gravity,
    wall_seconds: read with cell()); the metrics (compare/metrics.json's table_row) only where
    some point wrote them, none when every point failed: optional."""
    return cell(row, column, optional=True)


def rayleigh_miss(row):
    """How far the point's twin landed from its target Ra: Ra / target - 1 (NaN unless both)."""
    target = to_float(cell(row, "target_rayleigh", optional=True))
    achieved = to_float(metric(row, "rayleigh"))
    if not (finite(target) and finite(achieved)) or target == 0:
        return math.nan
    return achieved / target - 1


def fmt_signed_percent(fraction):
    return "–" if not finite(fraction) else f"{100 * fraction:+.1f} %"


def landing_summary(rows):
    """One sentence on how far the twins landed from their target Ra, None without targets."""
    misses = [(cell(r, "point"), rayleigh_miss(r)) for r in rows]
    misses = [(p, m) for p, m in misses if finite(m)]
    if not misses:
        return None
    point, worst = max(misses, key=lambda pm: abs(pm[1]))
    return (f"The twins' Ra against their targets: {len(misses)} point(s) ran, the farthest "
            f"(point {point}) at {fmt_signed_percent(worst)} from its target; each point's "
            "miss is in the table (Ra / target - 1).")


def in_range(pairs, xs, margin=1.05):
    """The (x, y) pairs whose x lies within the range of xs (a relative margin on each side)."""
    xs = [x for x in xs if finite(x) and x > 0]
    if not xs:
        return []
    low, high = min(xs) / margin, max(xs) * margin
    return [(x, y) for x, y in pairs if low <= x <= high]


def walls_no_slip(grid):
    """True / False from the base parameters' walled directions' Slip, None when not stated."""
    parameters = lookup(grid, "base_parameters") or {}
    answers = []
    for axis in AXES:
        if lookup(parameters, f"Scene/{axis} boundaries/Type") == "walls":
            slip = lookup(parameters, f"Scene/{axis} boundaries/Slip")
            if slip is not None:
                answers.append(slip == "no-slip")
    return all(answers) if answers else None


def sweep_groups(rows, series_key, order):
    """(label, rows) per value of the series key, in the grid's order (then first seen); one
    group without a series key."""
    if not series_key:
        return [("", rows)]
    labels = [v for v in order if any(cell(r, series_key) == v for r in rows)]
    labels += [v for v in dict.fromkeys(cell(r, series_key) for r in rows) if v not in labels]
    return [(f"{series_key} = {label}", [r for r in rows if cell(r, series_key) == label])
            for label in labels]


def source_style(index, label):
    """Marker and line style of the index-th source; the noise is a plain dotted line."""
    if label == "noise":
        return "", ":"
    markers = ["o", "s", "^", "v", "D", "P"]
    styles = ["-", "--", "-.", (0, (5, 1)), (0, (3, 1, 1, 1)), (0, (1, 1))]
    return markers[index % len(markers)], styles[index % len(styles)]


def mark_not_done(ax, x_axis, x_column, rows):
    """A red cross on the x axis at each point that did not finish (listed in the report)."""
    from matplotlib.lines import Line2D
    xs = [x_axis.position(cell(r, x_column)) for r in rows]
    xs = [x for x in xs if finite(x) and (not x_axis.log or x > 0)]
    if not xs:
        return []
    ax.plot(xs, [0.0] * len(xs), "x", color="#c0392b", ms=9, mew=2, clip_on=False, zorder=5,
            transform=ax.get_xaxis_transform())
    return [Line2D([], [], marker="x", ls="", color="#c0392b", ms=9, mew=2,
                   label="point not done (see the report)")]


def draw_sources(ax, table, groups, x_axis, x_column, sources):
    """One line per (group, source): colour per source with one group, else per group (and a
    line style / marker per source). Returns the legend handles."""
    import numpy as np
    from matplotlib.lines import Line2D
    import matplotlib.pyplot as plt

    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    handles = []
    drawn = set()
    for g, (group_label, rows) in enumerate(groups):
        xs = np.array([x_axis.position(cell(r, x_column)) for r in rows], dtype=float)
        order = np.argsort(xs, kind="stable")
        for s, (label, column, error_column, colour) in enumerate(sources):
            marker, style = source_style(s, label)
            if not table.has(column):
                continue
            ys = table.numbers(column, rows)
            errors = table.numbers(error_column, rows) if error_column and table.has(
                error_column) else None
            ok = np.isfinite(xs) & np.isfinite(ys)
            if not ok[order].any():
                continue
            c = colour if len(groups) == 1 else cycle[g % len(cycle)]
            idx = order[ok[order]]
            ax.errorbar(xs[idx], ys[idx], yerr=None if errors is None else errors[idx],
                        marker=marker, ls=style, color=c, ms=5, capsize=2.5,
                        mfc="white" if s > 0 else c)
            drawn.add(s)
            if len(groups) == 1:
                handles.append(Line2D([], [], color=c, marker=marker, ls=style, label=label,
                                      mfc="white" if s > 0 else c))
    if len(groups) > 1:
        for s, (label, *_rest) in enumerate(sources):
            if s in drawn:
                marker, style = source_style(s, label)
                handles.append(Line2D([], [], color="0.2", marker=marker, ls=style, label=label,
                                      mfc="white" if s > 0 else "0.2"))
        for g, (group_label, _) in enumerate(groups):
            handles.append(Line2D([], [], color=cycle[g % len(cycle)], lw=4, label=group_label))
    return handles


def pareto_front(points):
    """Indices of the points no other point beats in both cost and error (ties kept)."""
    front = []
    for i, (c, e) in enumerate(points):
        if not any((c2 <= c and e2 <= e) and (c2 < c or e2 < e) for c2, e2 in points):
            front.append(i)
    return sorted(front, key=lambda i: points[i][0])


def figure_pareto(out_dir, done, keys, doc):
    """Error against cost over the sweep's points (integrator, dt, N, ...): which settings buy the
    least error for their particle wall time. Error: temperature L2 to the calibrated twin (the
    nominal twin's when there is none)."""
    import matplotlib.pyplot as plt
    twin = next((t for t in ("calibrated", "nominal") if any(
        finite(to_float(metric(r, f"temperature_l2_{t}"))) for r in done)), None)
    if twin is None:
        return None
    rows = [r for r in done if finite(to_float(metric(r, f"temperature_l2_{twin}")))
            and finite(to_float(metric(r, "wall_seconds_particle")))]
    if len(rows) < 2:
        return None
    points = [(to_float(metric(r, "wall_seconds_particle")),
               to_float(metric(r, f"temperature_l2_{twin}"))) for r in rows]
    front = pareto_front(points)
    labels = [", ".join(f"{k.split('/')[-1]} {plain(cell(r, k))}" for k in keys) or plain(
        cell(r, "point")) for r in rows]
    fig, ax = plt.subplots(figsize=(7.6, 4.8), layout="constrained")
    for i, ((c, e), r) in enumerate(zip(points, rows)):
        se = to_float(metric(r, f"temperature_l2_{twin}_stderr"))
        ax.errorbar([c], [e], yerr=[se] if finite(se) else None, fmt="o",
                    color=COLOUR["calibrated" if i in front else "noise"], ms=6, capsize=2.5)
        same = sum(1 for p in points[:i] if p == (c, e))  # stack the labels of equal points
        ax.annotate(labels[i], (c, e), textcoords="offset points", xytext=(5, 4 - 9 * same),
                    fontsize=7)
    ax.step([points[i][0] for i in front], [points[i][1] for i in front], where="post",
            color=COLOUR["calibrated"], lw=1.2, label="Pareto front")
    noise = [to_float(metric(r, "temperature_l2_noise")) for r in rows]
    ax.plot([p[0] for p in points], noise, "x", color=COLOUR["noise"], label="noise (each point)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particle stage wall-clock time [s]")
    ax.set_ylabel(f"temperature L2 / dT to the {TWIN_LABEL[twin]}")
    ax.set_title("error against cost", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    name = save_figure(fig, out_dir, "pareto.png")
    doc.paragraph("Pareto front (no other point has both less particle wall time and a smaller "
                  f"temperature L2 to the {TWIN_LABEL[twin]}): "
                  + "; ".join(f"{labels[i]} ({fmt(points[i][0], 3)} s, L2 {fmt(points[i][1], 3)})"
                              for i in front) + ".")
    return (name, f"Temperature L2 to the {TWIN_LABEL[twin]} against the particle stage's wall "
                  "time, one point per sweep point (labels: the varied keys); filled: on the "
                  "Pareto front; crosses: each point's noise level, the floor no run length "
                  "removes.")


def realisations_section(doc, done):
    """Points that differ only in the seed are realisations of one case: each point's Nu gap to
    the calibrated twin against its allowance (both errors + 3%), and the mean gap with its
    standard error from the spread between realisations."""
    rows, relative = [], []
    for r in done:
        p = to_float(metric(r, "nusselt_particle"))
        ps = to_float(metric(r, "nusselt_particle_stderr"))
        c = to_float(metric(r, "nusselt_calibrated"))
        cs = to_float(metric(r, "nusselt_calibrated_stderr"))
        if not all(finite(v) for v in (p, ps, c)) or c == 0:
            continue
        cs = cs if finite(cs) else 0.0
        allowance = ps + cs + 0.03 * abs(c)
        relative.append(p / c - 1)
        rows.append([plain(cell(r, "Particle/Seed")), fmt_pm(p, ps), fmt_pm(c, cs),
                     fmt_percent(p / c - 1), fmt(allowance),
                     "within" if abs(p - c) <= allowance else "out"])
    if not rows:
        return
    doc.heading("Realisations: particle against the calibrated twin")
    doc.table(["seed", "Nu particle", "Nu calibrated twin", "particle / twin - 1",
               "allowance (errors + 3%)", "gap"], rows)
    if len(relative) > 1:
        mean = sum(relative) / len(relative)
        se = math.sqrt(sum((x - mean) ** 2 for x in relative) / (len(relative) - 1) / len(relative))
        doc.paragraph(f"Over {len(relative)} realisations: particle / twin - 1 = "
                      f"{fmt_percent(mean)} ± {fmt_percent(se)} (standard error from the spread "
                      "between the realisations, independent of the runs' own error bars).")


class Sweep:
    """A sweep directory's table and grid, and what its figures put along x: Ra for a sweep over
    target Rayleigh numbers (one series per value of the first varied key), else the first varied
    key (one series per value of the second), else the point."""

    def __init__(self, sweep_dir):
        self.table = table = Table(os.path.join(sweep_dir, "sweep.csv"))
        description = read_json(os.path.join(sweep_dir, "sweep.json")) or {}
        self.grid = lookup(description, "grid") or {}
        self.keys = varied_keys(table, SWEEP_OWN_COLUMNS) or list(
            (lookup(self.grid, "vary") or {}).keys())
        self.done = [r for r in table.rows if cell(r, "status") == "done"]
        self.not_done = [r for r in table.rows if cell(r, "status") != "done"]
        self.by_rayleigh = table.has("target_rayleigh", optional=False) and any(
            finite(to_float(cell(r, "target_rayleigh"))) for r in table.rows)
        self.x_column, self.x_label, self.x_name, series_key = self._choose_x()
        self.x_axis = Axis(self.x_column, [cell(r, self.x_column) for r in self.done] or [""])
        if self.by_rayleigh:
            self.x_axis.log = True
        self.groups = sweep_groups(self.done, series_key,
                                   [str(v) for v in (lookup(self.grid, "vary", series_key) or [])]
                                   if series_key else [])

    def _choose_x(self):
        """(x column, x label, x name in file names, series key); a Ra sweep gets the column
        rayleigh_axis in every row."""
        keys = self.keys
        if self.by_rayleigh:
            # The continuum's Ra where it ran, else the target.
            x_column = "rayleigh_axis"
            for r in self.table.rows:
                measured = to_float(metric(r, "rayleigh"))
                r[x_column] = metric(r, "rayleigh") if finite(measured) else cell(
                    r, "target_rayleigh")
            return x_column, "Rayleigh number Ra (nominal twin)", "rayleigh", (
                keys[0] if keys else None)
        if keys:
            return keys[0], with_unit(keys[0]), slug(keys[0]), (keys[1] if len(keys) > 1 else None)
        return "point", "point", "point", None

    def draw(self, ax, sources):
        """draw_sources over the points done, against x."""
        return draw_sources(ax, self.table, self.groups, self.x_axis, self.x_column, sources)

    def finish(self, ax, handles, ylabel, title, legend=True):
        """The x axis, labels and legend of a figure against x, the points not done marked."""
        handles = handles + mark_not_done(ax, self.x_axis, self.x_column, self.not_done)
        self.x_axis.apply(ax, "x")
        ax.set_xlabel(self.x_label)
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which="both")
        plain_log_ticks(ax)
        if handles and legend:
            ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1))


def report_sweep(sweep_dir, out_dir):
    sweep = Sweep(sweep_dir)
    case_name = study_case_name(sweep.grid, sweep_dir)
    doc = Document(f"Sweep: {case_name}")
    doc.paragraph(f"Sweep directory: {os.path.abspath(sweep_dir)}. Case file: "
                  f"{lookup(sweep.grid, 'case_file') or '–'}. {UNITS_NOTE}.")
    verdict_section(doc, sweep)
    grid_section(doc, sweep)
    figures = sweep_figures(out_dir, sweep, doc)
    points_section(doc, sweep)
    if sweep.keys == ["Particle/Seed"]:
        realisations_section(doc, sweep.done)
    not_done_section(doc, sweep.not_done)
    if figures:
        doc.heading("Figures")
        for name, caption in figures:
            doc.figure(name, caption + f" {UNITS_NOTE}.")
    write_documents(doc, out_dir)


def verdict_section(doc, sweep):
    """The sweep's verdict first: how many points finished, and at how many compare's strict
    verdict and its prediction tolerances hold for the nominal twin (the points' own verdicts,
    columns within_errors_nominal and prediction_pass)."""
    done = sweep.done
    total = len(sweep.table.rows)

    def count(column):
        known = [cell(r, column, optional=True) for r in done]
        known = [v for v in known if v in ("true", "false")]
        return (sum(v == "true" for v in known), len(known)) if known else None

    line = f"verdict: {len(done)} of {total} points done"
    for column, what in (("within_errors_nominal", "the nominal twin matches the particles "
                                                    "within errors (compare's strict verdict)"),
                         ("prediction_pass", "within the prediction tolerances")):
        counted = count(column)
        if counted:
            line += f"; {what} at {counted[0]} of {counted[1]}"
    doc.heading("Verdict")
    items = [line + "."]
    if sweep.not_done:
        items.append("not done: " + ", ".join(
            f"{plain(cell(r, 'point'))} ({plain(cell(r, 'status'))})" for r in sweep.not_done)
            + " (the reasons: Points not done).")
    doc.bullets(items)


def grid_section(doc, sweep):
    """The values each key took (and the target Ra), and how many points finished."""
    grid, table = sweep.grid, sweep.table
    grid_items = [f"{k}: {', '.join(map(str, v))}" for k, v in (lookup(grid, "vary") or {}).items()]
    if not grid_items:  # sweep.json without the grid: the values in the table
        grid_items = [f"{k}: " + ", ".join(dict.fromkeys(cell(r, k) for r in table.rows))
                      for k in sweep.keys]
    targets = lookup(grid, "rayleigh")
    if targets:
        grid_items.append("target Rayleigh numbers (gravity scaled): " +
                          ", ".join(fmt(to_float(t)) for t in targets))
    doc.heading("Grid")
    doc.bullets(grid_items or ["(sweep.json states no grid)"])
    doc.paragraph(f"{len(table.rows)} points: {len(sweep.done)} done, "
                  f"{len(sweep.not_done)} not done.")


def sweep_figures(out_dir, sweep, doc):
    """The figures there is data for: [(file, caption)] (the Pareto front's paragraph goes into
    doc)."""
    figures = []
    nusselt_columns = ("nusselt_particle", "nusselt_nominal", "nusselt_calibrated")
    if sweep.done and any(sweep.table.has(c) for c in nusselt_columns):
        figures.append(figure_nusselt(out_dir, sweep))
    if sweep.done:
        errors = figure_errors(out_dir, sweep)
        if errors:
            figures.append(errors)
        figures.append(figure_cost(out_dir, sweep))
        pareto = None if sweep.by_rayleigh else figure_pareto(out_dir, sweep.done, sweep.keys, doc)
        if pareto:
            figures.append(pareto)
    return figures


def figure_nusselt(out_dir, sweep):
    """The Nusselt numbers against x (and de Vahl Davis's benchmark): (file, caption)."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8.4, 4.8), layout="constrained")
    handles = sweep.draw(ax, [
        ("particle ± stderr", "nusselt_particle", "nusselt_particle_stderr",
         COLOUR["particle"]),
        ("nominal twin", "nusselt_nominal", None, COLOUR["nominal"]),
        ("calibrated twin", "nusselt_calibrated", None, COLOUR["calibrated"])])
    benchmark_note = draw_benchmark(ax, handles, sweep)
    sweep.finish(ax, handles, "Nusselt number Nu", f"Nusselt number against {sweep.x_label}")
    name = save_figure(fig, out_dir, f"nusselt_vs_{sweep.x_name}.png")
    return (name, f"Nusselt numbers: the particle fluid's (with standard errors) and "
                  f"each continuum twin's, against {sweep.x_label}. " + (benchmark_note or ""))


def draw_benchmark(ax, handles, sweep):
    """de Vahl Davis's Nusselt numbers on a Ra sweep with walls not known to slip (its legend
    entry added to handles); the caption's sentence on the benchmark, None unless a Ra sweep."""
    no_slip = walls_no_slip(sweep.grid)
    benchmark_note = None
    # The benchmark only where the sweep has points: its range sets the axis.
    sweep_ra = [sweep.x_axis.position(cell(r, sweep.x_column)) for r in sweep.table.rows]
    benchmark = in_range(DE_VAHL_DAVIS_NUSSELT, sweep_ra)
    if sweep.by_rayleigh and no_slip is not False and benchmark:
        from matplotlib.lines import Line2D
        ra, nu = zip(*benchmark)
        label = "de Vahl Davis 1983, no-slip, Pr 0.71" + (
            "" if no_slip else " (walls' slip not stated)")
        ax.plot(ra, nu, "*", ms=10, color=COLOUR["benchmark"], zorder=4)
        handles.append(Line2D([], [], marker="*", ls="", ms=10, color=COLOUR["benchmark"],
                              label=label))
        benchmark_note = ("Stars: de Vahl Davis (1983), Int. J. Numer. Meth. Fluids 3, 249, "
                          "Boussinesq cavity with no-slip walls at Pr = 0.71, its values "
                          "within the sweep's Ra range"
                          + ("" if no_slip else "; the sweep does not state its walls' slip")
                          + ".")
    elif sweep.by_rayleigh and no_slip is not False:
        benchmark_note = ("de Vahl Davis's no-slip benchmark (Ra 1e3-1e6) has no value "
                          "within the sweep's Ra range.")
    elif sweep.by_rayleigh:
        benchmark_note = ("de Vahl Davis's no-slip benchmark is not drawn: this case's walls "
                          "are not all no-slip.")
    return benchmark_note


def figure_errors(out_dir, sweep):
    """The distances between the twins against x, a panel per field: (file, caption), None
    without distance columns."""
    import matplotlib.pyplot as plt

    fields = [f for f in ("temperature", "velocity") if any(
        sweep.table.has(f"{f}_l2_{t}") for t in TWINS)]
    if not fields:
        return None
    fig, axes = plt.subplots(1, len(fields), figsize=(5.4 * len(fields) + 2.4, 4.6),
                             squeeze=False, layout="constrained")
    for n, (ax, field) in enumerate(zip(axes[0], fields)):
        handles = sweep.draw(ax, [
            ("nominal twin ± stderr", f"{field}_l2_nominal", f"{field}_l2_nominal_stderr",
             COLOUR["nominal"]),
            ("calibrated twin ± stderr", f"{field}_l2_calibrated",
             f"{field}_l2_calibrated_stderr", COLOUR["calibrated"]),
            ("noise", f"{field}_l2_noise", None, COLOUR["noise"])])
        ax.set_yscale("log")
        sweep.finish(ax, handles, f"{field} L2 / {'dT' if field == 'temperature' else 'U'}",
                     f"{field}: L2 distance particle–twin and the noise",
                     legend=n == len(fields) - 1)  # one legend serves both panels
    name = save_figure(fig, out_dir, f"errors_vs_{sweep.x_name}.png")
    return (name, "L2 distance of the particle fields to each twin (interior bins, "
                  "in units of the point's temperature / velocity scale) with "
                  "standard errors, and the noise: the L2 two identical twins "
                  "would show through the particle's statistical error.")


def figure_cost(out_dir, sweep):
    """Each stage's wall-clock time against x: (file, caption)."""
    import matplotlib.pyplot as plt

    stages = [("particle stage", "wall_seconds_particle", None, COLOUR["particle"]),
              ("nominal twin", "wall_seconds_continuum", None, COLOUR["nominal"]),
              ("calibrated twin", "wall_seconds_continuum_calibrated", None,
               COLOUR["calibrated"]),
              ("whole point", "wall_seconds", None, "black")]
    fig, ax = plt.subplots(figsize=(8.4, 4.8), layout="constrained")
    handles = sweep.draw(ax, stages)
    ax.set_yscale("log")
    sweep.finish(ax, handles, "wall-clock time [s]", f"cost per stage against {sweep.x_label}")
    return (save_figure(fig, out_dir, "cost.png"),
            "Wall-clock seconds per stage and per point (the point's child process).")


def points_section(doc, sweep):
    """Every point's keys, status and metrics (and, for a Ra sweep, how far its twin landed from
    its target Ra)."""
    keys, by_rayleigh, table = sweep.keys, sweep.by_rayleigh, sweep.table
    doc.heading("Points")
    columns = [("point", "point"), ("status", "status")] + [(k, k) for k in keys]
    if by_rayleigh:
        columns += [("target Ra", "target_rayleigh"), ("Ra", "rayleigh")]
    rows = []
    for r in table.rows:
        # (rayleigh, the nominal twin's, is a metric; target_rayleigh the sweep's own)
        cells = [plain(cell(r, c)) if c in ("point", "status") or c in keys else
                 fmt(to_float(cell(r, c, optional=c == "rayleigh"))) for _, c in columns]
        if by_rayleigh:
            cells.append(fmt_signed_percent(rayleigh_miss(r)))
        cells += [fmt_pm(to_float(metric(r, "nusselt_particle")),
                         to_float(metric(r, "nusselt_particle_stderr"))),
                  fmt(to_float(metric(r, "nusselt_nominal"))),
                  fmt(to_float(metric(r, "nusselt_calibrated"))),
                  fmt_pm(to_float(metric(r, "temperature_l2_nominal")),
                         to_float(metric(r, "temperature_l2_nominal_stderr"))),
                  fmt_pm(to_float(metric(r, "temperature_l2_calibrated")),
                         to_float(metric(r, "temperature_l2_calibrated_stderr"))),
                  fmt(to_float(metric(r, "temperature_l2_noise"))),
                  fmt(to_float(cell(r, "wall_seconds")))]
        rows.append(cells)
    if by_rayleigh:
        columns.append(("Ra / target - 1", None))
        summary = landing_summary(table.rows)
        if summary:
            doc.paragraph(summary)
    doc.table([c[0] for c in columns] + ["Nu particle", "Nu nominal", "Nu calibrated",
                                          "T L2 nominal", "T L2 calibrated", "T noise",
                                          "wall s"], rows)


def not_done_section(doc, not_done):
    """The points that did not finish, and why."""
    doc.heading("Points not done")
    if not_done:
        doc.table(["point", "status", "exit code", "reason"],
                  [[plain(cell(r, "point")), plain(cell(r, "status")), plain(cell(r, "exit_code")),
                    plain(cell(r, "reason"))] for r in not_done])
    else:
        doc.paragraph("None: every point finished.")


# ---------------------------------------------------------------------------------------------
