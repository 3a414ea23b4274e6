"""The report of a stability directory (DIR/stability.csv + DIR/stability.json, written by
`twinflow stability`): the map of observed status against the prediction, and the points."""

import os

from .data import (UNITS_NOTE, Table, cell, finite, fmt, lookup, plain, read_json, study_case_name,
                   to_float, varied_keys, with_unit)
from .document import Document, write_documents
from .figures import Axis, save_figure

STABILITY_OWN_COLUMNS = ("dt", "predicted_dt_critical", "fluctuation_number", "predicted_stable",
                         "energy_relative_drift_max", "T_kinetic", "T_internal",
                         "temperature_relative_error", "wall_seconds")
STATUS_STYLE = {  # colour, marker
    "stable": ("#2a9d4b", "o"),
    "energy_drift": ("#e9a21a", "s"),
    "temperature_off": ("#8c6bb1", "D"),
    "negative_internal_energy": ("#1f78b4", "v"),
    "non_finite": ("#d62728", "X"),
    "unstable": ("#7f0000", "^"),
    "failed": ("0.45", "P"),
}
TIME_STEP_KEY = "Particle/Time step"


def report_stability(stability_dir, out_dir):
    table = Table(os.path.join(stability_dir, "stability.csv"))
    description = read_json(os.path.join(stability_dir, "stability.json")) or {}
    grid = lookup(description, "grid") or {}
    keys = varied_keys(table, STABILITY_OWN_COLUMNS) or list((lookup(grid, "vary") or {}).keys())
    rows = table.rows
    case_name = study_case_name(grid, stability_dir)
    doc = Document(f"Stability map: {case_name}")
    doc.paragraph(f"Stability directory: {os.path.abspath(stability_dir)}. Case file: "
                  f"{lookup(grid, 'case_file') or '–'}. {UNITS_NOTE}.")
    grid_section(doc, grid, keys, rows)
    if rows and keys:
        figure_stability_map(out_dir, table, keys)
        doc.heading("Map")
        doc.figure("stability_map.png",
                   "One marker per point, colour and shape by the observed status; hollow where "
                   "the prediction (001 eq. (28) and the fluctuation number) says unstable"
                   + ("; dashed: the predicted critical time step dt_critical (001 eq. (28))"
                      if TIME_STEP_KEY in keys else "") + f". {UNITS_NOTE}.")
    points_section(doc, rows, keys)
    prediction_agreement(doc, rows)
    write_documents(doc, out_dir)


def grid_section(doc, grid, keys, rows):
    """The values each key took, and how many points ended in each status."""
    doc.heading("Grid")
    doc.bullets([f"{k}: {', '.join(map(str, v))}" for k, v in (lookup(grid, "vary") or {}).items()]
                or [f"{k}" for k in keys])
    counts = {}
    for r in rows:
        counts[cell(r, "status")] = counts.get(cell(r, "status"), 0) + 1
    doc.paragraph(f"{len(rows)} points: " + ", ".join(f"{n} {s}" for s, n in counts.items()) + ".")


def figure_stability_map(out_dir, table, keys):
    """stability_map.png: each point's observed status against the first (and second) varied
    key, hollow where predicted unstable, and the predicted critical time step."""
    import matplotlib.pyplot as plt

    rows = table.rows
    x_key = keys[0]
    y_key = keys[1] if len(keys) > 1 else None
    x_axis = Axis(x_key, [cell(r, x_key) for r in rows])
    y_axis = Axis(y_key, [cell(r, y_key) for r in rows]) if y_key else None
    fig, ax = plt.subplots(figsize=(7.6, 5.2 if y_key else 2.9), layout="constrained")
    handles = status_markers(ax, rows, x_axis, y_axis)
    critical = draw_critical_time_step(ax, table, x_axis, y_axis)
    if critical:
        handles.append(critical)
    x_axis.apply(ax, "x", ticks_at_values=True)
    ax.set_xlabel(with_unit(x_key))
    if y_axis:
        y_axis.apply(ax, "y", ticks_at_values=True)
        ax.set_ylabel(with_unit(y_key))
    else:
        ax.set_yticks([])
        ax.set_ylim(-1, 1)
    if x_axis.numeric and not x_axis.log:
        ax.margins(x=0.08)
    if y_axis and y_axis.numeric and not y_axis.log:
        ax.margins(y=0.1)
    ax.grid(alpha=0.3, which="both")
    ax.legend(handles=handles, fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.set_title("stability of the particle run per point", fontsize=10)
    save_figure(fig, out_dir, "stability_map.png")


def status_markers(ax, rows, x_axis, y_axis):
    """One marker per point (colour and shape by status, hollow where predicted unstable); the
    legend handles of the statuses seen and of the prediction."""
    from matplotlib.lines import Line2D

    seen = []
    for r in rows:
        status = cell(r, "status")
        colour, marker = STATUS_STYLE.get(status, ("0.75", "o"))
        x = x_axis.position(cell(r, x_axis.name))
        y = y_axis.position(cell(r, y_axis.name)) if y_axis else 0.0
        predicted = cell(r, "predicted_stable").strip().lower()
        hollow = predicted in ("false", "0", "no")
        ax.plot([x], [y], marker=marker, ms=11, ls="", color=colour,
                mfc="none" if hollow else colour, mew=2, zorder=3)
        if status not in seen:
            seen.append(status)
    seen.sort(key=lambda s: list(STATUS_STYLE).index(s) if s in STATUS_STYLE
              else len(STATUS_STYLE))
    handles = [Line2D([], [], marker=STATUS_STYLE.get(s, ("0.75", "o"))[1], ls="", ms=9,
                      color=STATUS_STYLE.get(s, ("0.75", "o"))[0], label=s or "(no status)")
               for s in seen]
    return handles + [Line2D([], [], marker="o", ls="", ms=9, color="0.3",
                             label="predicted stable"),
                      Line2D([], [], marker="o", ls="", ms=9, color="0.3", mfc="none", mew=2,
                             label="predicted unstable (hollow)")]


def draw_critical_time_step(ax, table, x_axis, y_axis):
    """The predicted critical time step (001 eq. (28)) where dt is one of the axes: a line, a
    curve over the other key, or a segment per category of it; its legend handle, else None."""
    from matplotlib.lines import Line2D

    x_key, y_key = x_axis.name, y_axis.name if y_axis else None
    if not (TIME_STEP_KEY in (x_key, y_key) and table.has("predicted_dt_critical",
                                                          optional=False)):
        return None
    other = y_axis if x_key == TIME_STEP_KEY else x_axis
    other_key = y_key if x_key == TIME_STEP_KEY else x_key
    by_other = {}
    for r in table.rows:
        dt_c = to_float(cell(r, "predicted_dt_critical"))
        if finite(dt_c):
            key = cell(r, other_key) if other_key else ""
            by_other.setdefault(key, dt_c)
    values = sorted(set(by_other.values()))
    line = dict(color="black", ls="--", lw=1.4, zorder=2)
    if len(values) == 1:
        (ax.axvline if x_key == TIME_STEP_KEY else ax.axhline)(values[0], **line)
    elif values and other.numeric:
        # dt_critical as a curve over the other key.
        pairs = sorted((other.position(k), v) for k, v in by_other.items())
        o, d = zip(*pairs)
        if x_key == TIME_STEP_KEY:
            ax.plot(d, o, marker="|", ms=14, **line)
        else:
            ax.plot(o, d, marker="_", ms=14, **line)
    elif values:
        # One segment per category of the other key.
        for key, dt_c in by_other.items():
            p = other.position(key)
            if x_key == TIME_STEP_KEY:
                ax.plot([dt_c, dt_c], [p - 0.45, p + 0.45], **line)
            else:
                ax.plot([p - 0.45, p + 0.45], [dt_c, dt_c], **line)
    if not values:
        return None
    value_text = f" = {fmt(values[0], 3)} tau" if len(values) == 1 else ""
    return Line2D([], [], label=f"predicted dt_critical{value_text}, 001 eq. (28)", **line)


def points_section(doc, rows, keys):
    """Every point: its keys, status, the prediction and what the run measured."""
    doc.heading("Points")
    header = ["point", "status"] + keys + ["dt [tau]", "predicted dt_critical",
                                           "fluctuation number", "predicted stable", "max |dE/E|",
                                           "T_kinetic", "T_internal", "T relative error", "wall s",
                                           "reason"]
    table_rows = []
    for r in rows:
        table_rows.append([plain(cell(r, "point")), plain(cell(r, "status"))]
                          + [plain(cell(r, k)) for k in keys]
                          + [fmt(to_float(cell(r, c))) for c in (
                              "dt", "predicted_dt_critical", "fluctuation_number")]
                          + [plain(cell(r, "predicted_stable"))]
                          + [fmt(to_float(cell(r, c)), 3) for c in ("energy_relative_drift_max",)]
                          + [fmt(to_float(cell(r, c)), 5) for c in ("T_kinetic", "T_internal")]
                          + [fmt(to_float(cell(r, c)), 3) for c in (
                              "temperature_relative_error", "wall_seconds")]
                          + [plain(cell(r, "reason"))])
    doc.table(header, table_rows)


def prediction_agreement(doc, rows):
    """How many points' observed status agrees with the prediction (failed points left out)."""
    agree = [r for r in rows if cell(r, "status") in STATUS_STYLE and cell(r, "status") != "failed"
             and cell(r, "predicted_stable").lower() in ("true", "false")]
    if agree:
        matches = sum((cell(r, "status") == "stable") ==
                      (cell(r, "predicted_stable").lower() == "true") for r in agree)
        doc.paragraph(f"Prediction against observation: {matches} of {len(agree)} points agree "
                      "(predicted stable and observed stable, or predicted unstable and observed "
                      "any other status; failed points left out).")
