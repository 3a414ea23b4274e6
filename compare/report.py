#!/usr/bin/env python3
"""Figures (PNG) and a report (report.md, report.html) for a twinflow result directory.

    python3 compare/report.py DIR

DIR is one of
  a run        (DIR/compare/metrics.json)           -> DIR/report/
  a sweep      (DIR/sweep.csv + DIR/sweep.json)     -> DIR/report/
  a stability  (DIR/stability.csv + .json)          -> DIR/report/

Every number shown is read from the C++ stages' files; this script only reads, arranges and
plots them (the one derived number is the report's "fraction explained", 1 - gap_cal / gap_nom).
Needs only Debian's python3, python3-numpy and python3-matplotlib. Exit codes: 0 written,
2 DIR is none of the above (one line on stderr).
"""

import csv
import html
import json
import math
import os
import re
import shutil
import sys
import tempfile

EXIT_BAD_INPUT = 2
DPI = 150
UNITS_NOTE = "particle units: lengths in rc, times in tau, temperatures in T0 (energies in k T0)"
AXES = "xyz"
TWINS = ("nominal", "calibrated")
TWIN_LABEL = {"nominal": "nominal twin", "calibrated": "calibrated twin"}
# One colour per data source, the same in every figure.
COLOUR = {"particle": "#1f4e9c", "nominal": "#d9541e", "calibrated": "#2a9d4b",
          "noise": "0.35", "benchmark": "black"}
LINESTYLE = {"nominal": "-", "calibrated": "--"}
# de Vahl Davis (1983), Int. J. Numer. Meth. Fluids 3, 249: Boussinesq cavity, no-slip walls,
# Pr = 0.71, mean Nusselt number.
DE_VAHL_DAVIS_NUSSELT = ((1e3, 1.118), (1e4, 2.243), (1e5, 4.519), (1e6, 8.800))
# A difference counts as "within noise" when it exceeds the noise by at most this many standard
# errors (stated in every report that uses it).
WITHIN_NOISE_STDERRS = 2.0


def calibration_text(metrics):
    """How the calibrated twin's walls were set (compare/metrics.json), for captions."""
    twin = ((metrics or {}).get("twins") or {}).get("calibrated") or {}
    return twin.get("calibration") or "walls at the fluid's wall temperatures"


def fail(message):
    print(f"report: {message}", file=sys.stderr)
    sys.exit(EXIT_BAD_INPUT)


# ---------------------------------------------------------------------------------------------
# Reading

def read_json(path):
    """The parsed file, or None when it is absent (the stage did not run)."""
    try:
        with open(path, encoding="utf-8") as f:
            return json.load(f)
    except FileNotFoundError:
        return None


def lookup(data, *path):
    """data[path[0]][path[1]]..., or None when any step is missing."""
    for key in path:
        if isinstance(data, dict) and key in data:
            data = data[key]
        elif isinstance(data, list) and isinstance(key, int) and -len(data) <= key < len(data):
            data = data[key]
        else:
            return None
    return data


def number(data, *path):
    """A finite float at path, else NaN (C++ writes non-finite numbers as null)."""
    value = lookup(data, *path)
    if isinstance(value, bool) or value is None:
        return math.nan
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def to_float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return math.nan


def finite(value):
    return value is not None and isinstance(value, (int, float)) and math.isfinite(value)


class Table:
    """A CSV file with optional leading '#' comment lines, then a header, then rows."""

    def __init__(self, path):
        self.path = path
        self.comments = []
        with open(path, newline="", encoding="utf-8") as f:
            lines = f.read().splitlines()
        while lines and lines[0].startswith("#"):
            self.comments.append(lines.pop(0).lstrip("# ").rstrip())
        reader = csv.reader(lines)
        self.header = next(reader, [])
        self.rows = [dict(zip(self.header, cells)) for cells in reader if cells]

    def has(self, column):
        return column in self.header

    def numbers(self, column, rows=None):
        import numpy as np
        rows = self.rows if rows is None else rows
        return np.array([to_float(r.get(column, "")) for r in rows], dtype=float)


def read_table(path):
    return Table(path) if os.path.isfile(path) else None


# ---------------------------------------------------------------------------------------------
# Number formatting

def fmt(value, digits=4):
    """value to `digits` significant digits, without exponent between 1e-3 and 1e5."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if value == 0:
        return "0"
    if 1e-3 <= abs(value) < 1e5:
        decimals = max(0, digits - 1 - math.floor(math.log10(abs(value))))
        text = f"{value:.{decimals}f}"
        return text.rstrip("0").rstrip(".") if "." in text else text
    mantissa, exponent = f"{value:.{max(0, digits - 1)}e}".split("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{int(exponent)}"


def fmt_pm(value, error):
    """value ± error with the error to two significant digits."""
    if not finite(value):
        return "–"
    if not finite(error) or error <= 0:
        return fmt(value)
    scale = max(abs(value), error)
    power = 0 if 1e-4 <= scale < 1e5 else math.floor(math.log10(scale))
    value, error = value / 10 ** power, error / 10 ** power
    decimals = max(0, 1 - math.floor(math.log10(error)))
    text = f"{value:.{decimals}f} ± {error:.{decimals}f}"
    return text if power == 0 else f"({text})e{power}"


def fmt_percent(fraction):
    return "–" if not finite(fraction) else f"{100 * fraction:.1f} %"


# ---------------------------------------------------------------------------------------------
# The report document: one list of blocks rendered both as Markdown and as HTML.

class Document:
    def __init__(self, title):
        self.title = title
        self.blocks = []

    def heading(self, text, level=2):
        self.blocks.append(("heading", level, text))

    def paragraph(self, text):
        self.blocks.append(("paragraph", text))

    def bullets(self, items):
        if items:
            self.blocks.append(("bullets", list(items)))

    def table(self, header, rows):
        self.blocks.append(("table", list(header), [list(r) for r in rows]))

    def figure(self, file_name, caption):
        self.blocks.append(("figure", file_name, caption))

    def markdown(self):
        def cell(text):
            return str(text).replace("|", "\\|").replace("\n", " ")

        out = [f"# {self.title}", ""]
        for block in self.blocks:
            kind = block[0]
            if kind == "heading":
                out += ["#" * block[1] + " " + block[2], ""]
            elif kind == "paragraph":
                out += [block[1], ""]
            elif kind == "bullets":
                out += [f"- {item}" for item in block[1]] + [""]
            elif kind == "table":
                out.append("| " + " | ".join(cell(h) for h in block[1]) + " |")
                out.append("|" + "---|" * len(block[1]))
                out += ["| " + " | ".join(cell(c) for c in row) + " |" for row in block[2]]
                out.append("")
            elif kind == "figure":
                out += [f"![{block[1]}]({block[1]})", "", f"*{block[2]}*", ""]
        return "\n".join(out)

    def html(self):
        e = html.escape
        out = ["<!DOCTYPE html>", "<html lang=\"en\"><head><meta charset=\"utf-8\">",
               f"<title>{e(self.title)}</title>",
               "<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;"
               "padding:0 1em;line-height:1.45}table{border-collapse:collapse;margin:0.5em 0 1em}"
               "th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left}"
               "th{background:#eee}img{max-width:100%}figure{margin:1em 0 2em}"
               "figcaption{font-size:0.92em;color:#333}</style></head><body>",
               f"<h1>{e(self.title)}</h1>"]
        for block in self.blocks:
            kind = block[0]
            if kind == "heading":
                out.append(f"<h{block[1]}>{e(block[2])}</h{block[1]}>")
            elif kind == "paragraph":
                out.append(f"<p>{e(block[1])}</p>")
            elif kind == "bullets":
                out.append("<ul>" + "".join(f"<li>{e(str(i))}</li>" for i in block[1]) + "</ul>")
            elif kind == "table":
                out.append("<table><thead><tr>" + "".join(f"<th>{e(str(h))}</th>" for h in block[1])
                           + "</tr></thead><tbody>")
                for row in block[2]:
                    out.append("<tr>" + "".join(f"<td>{e(str(c))}</td>" for c in row) + "</tr>")
                out.append("</tbody></table>")
            elif kind == "figure":
                out.append(f"<figure><img src=\"{e(block[1])}\" alt=\"{e(block[1])}\">"
                           f"<figcaption>{e(block[2])}</figcaption></figure>")
        out.append("</body></html>")
        return "\n".join(out)


def write_text(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text if text.endswith("\n") else text + "\n")


def save_figure(fig, out_dir, file_name):
    fig.savefig(os.path.join(out_dir, file_name), dpi=DPI)
    import matplotlib.pyplot as plt
    plt.close(fig)
    return file_name


# ---------------------------------------------------------------------------------------------
# Run directory

class RunGeometry:
    """What the figures need of the scene: box, walled directions, heated and vertical axes."""

    def __init__(self, metrics, particle_summary, nominal_summary, bins):
        parameters = lookup(particle_summary, "parameters") or \
            lookup(nominal_summary, "case_parameters") or {}
        counts = lookup(metrics, "bins") or []
        self.dim = len(counts) or int(to_float(parameters.get("Scene/Dimension", "2")) or 2)
        box = [to_float(v) for v in str(parameters.get("Scene/Box size", "")).split(",")]
        if len(box) != self.dim or not all(math.isfinite(v) for v in box):
            box = self._box_from_bins(bins)
        self.box = box
        self.walled = [parameters.get(f"Scene/{AXES[d]} boundaries/Type", "") == "walls"
                       for d in range(self.dim)]
        # Heated direction: the one whose two walls' temperatures differ (metrics.json), else
        # the continuum's, else x.
        self.heated = None
        jumps = lookup(metrics, "particle", "wall_temperature_jumps") or {}
        for d in range(self.dim):
            lower = number(jumps, f"{AXES[d]}_lower", "wall_temperature")
            upper = number(jumps, f"{AXES[d]}_upper", "wall_temperature")
            if finite(lower) and finite(upper) and lower != upper:
                self.heated = d
                break
        if self.heated is None:
            d = number(nominal_summary, "dimensionless", "heated_direction")
            self.heated = int(d) if finite(d) and 0 <= d < self.dim else 0
        gravity = [to_float(v) for v in str(parameters.get("Scene/Gravity", "")).split(",")]
        self.vertical = None
        if len(gravity) == self.dim and any(finite(g) and g != 0 for g in gravity):
            self.vertical = max(range(self.dim), key=lambda d: abs(gravity[d]))
        if self.vertical is None or self.vertical == self.heated:
            self.vertical = next(d for d in range(self.dim) if d != self.heated)

    def _box_from_bins(self, bins):
        box = []
        for d in range(self.dim):
            centres = sorted({to_float(r.get(AXES[d])) for r in (bins.rows if bins else [])})
            if len(centres) >= 2:
                box.append(centres[-1] + 0.5 * (centres[1] - centres[0]))
            elif centres:
                box.append(2 * centres[0])
            else:
                box.append(math.nan)
        return box

    def plane(self):
        """The two axes shown in a field map (horizontal, vertical) and the cut axis (3D)."""
        if self.dim == 2:
            return 0, 1, None
        a, b = self.heated, self.vertical
        cut = next(d for d in range(3) if d not in (a, b))
        return a, b, cut


def bin_plane(bins, geometry):
    """The bins of the plane shown: centres along both axes, row lookup, and the cut's text."""
    import numpy as np
    a, b, cut = geometry.plane()
    rows = bins.rows
    cut_text, layer = "", None
    if cut is not None:
        cut_values = sorted({to_float(r[AXES[cut]]) for r in rows})
        layer = cut_values[len(cut_values) // 2]
        rows = [r for r in rows if to_float(r[AXES[cut]]) == layer]
        where = ("the middle layer" if len(cut_values) % 2 else
                 "the first layer above the mid-plane")
        cut_text = (f"the bin layer at {AXES[cut]} = {fmt(layer)} rc (layer "
                    f"{len(cut_values) // 2 + 1} of {len(cut_values)}, {where})")
    xs = np.array(sorted({to_float(r[AXES[a]]) for r in rows}))
    ys = np.array(sorted({to_float(r[AXES[b]]) for r in rows}))
    index = {(to_float(r[AXES[a]]), to_float(r[AXES[b]])): r for r in rows}

    def grid(column):
        """A (len(ys), len(xs)) array of the column, NaN where absent."""
        out = np.full((len(ys), len(xs)), np.nan)
        if not bins.has(column):
            return out
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                r = index.get((x, y))
                if r is not None:
                    out[j, i] = to_float(r.get(column))
        return out

    return a, b, xs, ys, grid, cut_text, layer


def edges(centres):
    import numpy as np
    if len(centres) == 1:
        return np.array([0.0, 2 * centres[0]])
    h = centres[1] - centres[0]
    return np.concatenate([centres - 0.5 * h, [centres[-1] + 0.5 * h]])


def nice_arrow(value):
    """A round number near value for the arrow key."""
    if not finite(value) or value <= 0:
        return 1.0
    exponent = math.floor(math.log10(value))
    mantissa = value / 10 ** exponent
    for step in (1, 2, 5):
        if mantissa <= step * 1.5:
            return step * 10 ** exponent
    return 10 ** (exponent + 1)


def colour_bar(fig, ax, image, label):
    """A colour bar exactly as tall as its map."""
    fig.colorbar(image, cax=ax.inset_axes([1.04, 0.0, 0.05, 1.0]), label=label)


# The field maps: temperature (fields.png) and, beside a low-Mach twin, number density
# (density.png); bins.csv columns <prefix>_particle and <prefix>_<twin>.
FIELD_MAPS = {
    "temperature": {"prefix": "T", "symbol": "T", "unit": "T0", "cmap": "plasma",
                    "particle": "particle (DPDE), T_kinetic", "twin": ", T",
                    "file": "fields.png"},
    "density": {"prefix": "density", "symbol": "n", "unit": "rc^-d", "cmap": "viridis",
                "particle": "particle (DPDE), n", "twin": ", n(P, T)", "file": "density.png"},
}


def figure_fields(out_dir, bins, geometry, twins, metrics, field="temperature"):
    import numpy as np
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    spec = FIELD_MAPS[field]
    prefix, symbol = spec["prefix"], spec["symbol"]
    a, b, xs, ys, grid, cut_text, layer = bin_plane(bins, geometry)
    cut = geometry.plane()[2]
    ex, ey = edges(xs), edges(ys)
    va, vb = f"v{AXES[a]}", f"v{AXES[b]}"
    sources = [("particle", spec["particle"])] + \
        [(t, TWIN_LABEL[t] + spec["twin"]) for t in twins if bins.has(f"{prefix}_{t}")]
    maps = {name: grid(f"{prefix}_{name}") for name, _ in sources}
    # The difference map against the calibrated twin when there is one, else the nominal.
    reference = next((t for t in ("calibrated", "nominal") if t in maps), None)
    t_low = min(np.nanmin(m) for m in maps.values())
    t_high = max(np.nanmax(m) for m in maps.values())
    interior = grid("interior")
    # One arrow scale for every map: the largest bin speed spans ~0.9 of a bin.
    speeds = [np.hypot(grid(f"{va}_{n}"), grid(f"{vb}_{n}")) for n, _ in sources]
    v_max = max((np.nanmax(s) for s in speeds if np.isfinite(s).any()), default=math.nan)
    spacing = min(ex[1] - ex[0], ey[1] - ey[0])
    arrow_scale = v_max / (0.9 * spacing) if finite(v_max) and v_max > 0 else None

    panels = len(sources) + (1 if reference else 0)
    columns = 2 if panels == 4 else panels
    rows = math.ceil(panels / columns)
    aspect = (ey[-1] - ey[0]) / (ex[-1] - ex[0])
    fig, axes = plt.subplots(rows, columns, figsize=(4.8 * columns, rows * (3.5 * aspect + 0.8)),
                             squeeze=False, layout="constrained")
    # Room for the inset colour bars' labels, which the layout engine does not see.
    fig.get_layout_engine().set(wspace=0.18, hspace=0.06)
    axes = axes.ravel()

    def decorate(ax):
        ax.set_aspect("equal")
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.set_xlabel(f"{AXES[a]} [rc]")
        ax.set_ylabel(f"{AXES[b]} [rc]")
        # The wall layer left out of the distances: hatched.
        for j in range(len(ys)):
            for i in range(len(xs)):
                if interior[j, i] == 0:
                    ax.add_patch(Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j],
                                           fill=False, hatch="///", edgecolor=(0.6, 0.6, 0.6, 0.8),
                                           linewidth=0))

    for ax, (name, title) in zip(axes, sources):
        image = ax.pcolormesh(ex, ey, maps[name], cmap=spec["cmap"], vmin=t_low, vmax=t_high)
        colour_bar(fig, ax, image, f"{symbol} [{spec['unit']}]")
        u, v = grid(f"{va}_{name}"), grid(f"{vb}_{name}")
        if arrow_scale and np.isfinite(u).any():
            X, Y = np.meshgrid(xs, ys)
            arrows = ax.quiver(X, Y, u, v, color="white", scale=arrow_scale, scale_units="xy",
                               angles="xy", width=0.006, headwidth=4)
            if name == "particle":
                key = nice_arrow(0.5 * v_max)
                ax.quiverkey(arrows, 0.78, 1.035, key, f"{fmt(key, 2)} rc/tau", labelpos="E",
                             coordinates="axes", color="black", fontproperties={"size": 8})
        decorate(ax)
        ax.set_title(title, loc="left", fontsize=10)

    for ax in axes[panels:]:
        ax.set_visible(False)
    if reference is None:
        save_figure(fig, out_dir, spec["file"])
        return None, cut_text
    ax = axes[len(sources)]
    difference = maps["particle"] - maps[reference]
    limit = np.nanmax(np.abs(difference))
    limit = limit if finite(limit) and limit > 0 else 1.0
    image = ax.pcolormesh(ex, ey, difference, cmap="RdBu_r", vmin=-limit, vmax=limit)
    colour_bar(fig, ax, image, f"{symbol}_particle − {symbol}_{reference} [{spec['unit']}]")
    decorate(ax)
    # Where the compare stage found the largest interior difference.
    at = lookup(metrics, "twins", reference, field, "max_at") or []
    if len(at) >= geometry.dim and (cut is None or at[cut] == layer):
        ax.plot([at[a]], [at[b]], "x", color="black", ms=10, mew=2)
    ax.set_title(f"particle − {TWIN_LABEL[reference]}", loc="left", fontsize=10)
    save_figure(fig, out_dir, spec["file"])
    return reference, cut_text


def figure_profiles(out_dir, profiles, geometry, metrics, twins, excluded):
    import matplotlib.pyplot as plt

    h, g = geometry.heated, geometry.vertical
    H, G = AXES[h], AXES[g]
    along = {d: [r for r in profiles.rows if r.get("direction") == AXES[d]]
             for d in range(geometry.dim)}
    panels = [(h, "T", "T", f"T along {H} at mid-{G}", "T [T0]")]
    if profiles.has(f"v{G}_particle"):
        panels.append((h, f"v{G}", f"v{G}", f"vertical velocity v{G} along {H} at mid-{G}",
                       f"v{G} [rc/tau]"))
    if profiles.has(f"v{H}_particle"):
        panels.append((g, f"v{H}", f"v{H}", f"horizontal velocity v{H} along {G} at mid-{H}",
                       f"v{H} [rc/tau]"))
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.3), squeeze=False,
                             layout="constrained")
    for ax, (direction, quantity, _, title, ylabel) in zip(axes[0], panels):
        rows = along[direction]
        coordinate = profiles.numbers("coordinate", rows)
        ax.errorbar(coordinate, profiles.numbers(f"{quantity}_particle", rows),
                    yerr=profiles.numbers(f"{quantity}_particle_se", rows), fmt="o", ms=4,
                    capsize=2.5, color=COLOUR["particle"], label="particle ± stderr", zorder=3)
        for twin in twins:
            if profiles.has(f"{quantity}_{twin}"):
                ax.plot(coordinate, profiles.numbers(f"{quantity}_{twin}", rows),
                        LINESTYLE[twin], marker=".", color=COLOUR[twin], label=TWIN_LABEL[twin])
        length = geometry.box[direction]
        if geometry.walled[direction] and finite(excluded) and finite(length):
            ax.axvspan(0, excluded, color="0.88", zorder=0, label="wall layer (excluded)")
            ax.axvspan(length - excluded, length, color="0.88", zorder=0)
        if quantity == "T":
            wall_points(ax, metrics, direction, length)
        if quantity != "T":
            ax.axhline(0, color="0.6", lw=0.7, zorder=1)
        if finite(length):
            ax.set_xlim(0, length)
        ax.set_xlabel(f"{AXES[direction]} [rc]")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
    # One legend: the same entries hold for every panel.
    axes[0][0].legend(fontsize=8, loc="best")
    save_figure(fig, out_dir, "profiles.png")
    return [p[3] for p in panels]


def wall_layer_table(doc, particle_summary, calibrated_summary):
    """Each wall's measured layer and the conditions the calibrated twin took from it."""
    walls = lookup(particle_summary, "results", "walls") or {}
    if not any(isinstance(w, dict) and "effective_position" in w for w in walls.values()):
        return
    twin_walls = {}  # "x_lower" -> the calibrated twin's boundary entry
    for entry in lookup(calibrated_summary, "continuum_parameters", "boundaries") or []:
        for side in ("lower", "upper"):
            if isinstance(entry, dict) and isinstance(entry.get(side), dict):
                twin_walls[f"{entry.get('direction')}_{side}"] = entry[side]
    rows = []
    for name, w in walls.items():
        if not isinstance(w, dict) or "effective_position" not in w:
            continue
        twin = twin_walls.get(name, {})
        rows.append([name, fmt_pm(w.get("effective_position"), w.get("effective_position_stderr")),
                     fmt_pm(w.get("friction_per_area"), w.get("friction_per_area_stderr"))
                     if "friction_per_area" in w else "(free slip)",
                     fmt(twin.get("slip_length")) if "slip_length" in twin else "none",
                     fmt(twin.get("kapitza_conductance")) if "kapitza_conductance" in twin
                     else "none"])
    doc.heading("The walls' layers and what the calibrated twin takes from them", 3)
    doc.table(["wall", "effective position (Gibbs depth, rc)", "friction per area zeta",
               "calibrated twin: Navier slip b (rc)", "calibrated twin: Kapitza h_K"], rows)
    doc.paragraph("From particle/wall_layers.csv (report/wall_layers.png): the Gibbs depth is where "
                  "a step profile with the layer's particle count would start; zeta the no-slip "
                  "wall's tangential friction per area and slip velocity, so b = eta / zeta less "
                  "the depth at which it acts (Compare/Wall slip). Compare/Effective walls moves "
                  "the twin's walls to the Gibbs depths.")


def figure_wall_layers(out_dir, layers, particle_summary):
    """Density, temperature and tangential velocity against the distance from each wall."""
    import matplotlib.pyplot as plt

    walls = list(dict.fromkeys(r["wall"] for r in layers.rows))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained")
    for k, wall in enumerate(walls):
        rows = [r for r in layers.rows if r["wall"] == wall]
        h = layers.numbers("h", rows)
        colour = f"C{k}"
        # The velocity along the wall: the first axis other than the wall's own.
        along = next((a for a in "xyz" if a != wall[0] and layers.has(f"v{a}")), None)
        for ax, column in zip(axes, ["density", "T_kinetic", f"v{along}" if along else None]):
            if column is None or not layers.has(column):
                continue
            ax.errorbar(h, layers.numbers(column, rows), yerr=layers.numbers(column + "_se", rows),
                        fmt=".-", ms=3, lw=0.8, capsize=1.5, color=colour,
                        label=f"{wall} ({column})" if ax is axes[2] else wall)
        depth = number(particle_summary, "results", "walls", wall, "effective_position")
        if finite(depth):
            for ax in axes:
                ax.axvline(depth, color=colour, ls="--", lw=0.8)
    for ax, label in zip(axes, ["number density [rc^-d]", "T_kinetic [T0]",
                                "velocity along the wall [rc/tau]"]):
        ax.set_xlabel("distance from the wall plane h [rc]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    axes[2].axhline(0, color="0.6", lw=0.7)
    save_figure(fig, out_dir, "wall_layers.png")


def wall_points(ax, metrics, direction, length):
    """The walls' own temperatures and the particle fluid's extrapolated temperature there."""
    jumps = lookup(metrics, "particle", "wall_temperature_jumps") or {}
    first = True
    for side, position in (("lower", 0.0), ("upper", length)):
        jump = jumps.get(f"{AXES[direction]}_{side}")
        if not jump or not finite(position):
            continue
        ax.plot([position], [number(jump, "wall_temperature")], "s", ms=7, mfc="none",
                mec="black", mew=1.5, clip_on=False, zorder=4,
                label="wall temperature" if first else None)
        ax.errorbar([position], [number(jump, "fluid_temperature_at_wall")],
                    yerr=[number(jump, "fluid_temperature_at_wall_stderr")], fmt="D", ms=5,
                    color=COLOUR["particle"], mfc="white", clip_on=False, zorder=4,
                    label="particle fluid at the wall (extrapolated)" if first else None)
        first = False


def plain_log_ticks(ax):
    """Plain numbers (20, 30, 50) instead of 2x10^1 on log axes spanning few decades; more
    decades keep matplotlib's powers of ten."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter
    label = FuncFormatter(lambda v, _: f"{v:g}")
    for axis, scale, limits in ((ax.xaxis, ax.get_xscale(), ax.get_xlim()),
                                (ax.yaxis, ax.get_yscale(), ax.get_ylim())):
        if scale != "log" or not (limits[0] > 0):
            continue
        ratio = limits[1] / limits[0]
        if ratio < 30:
            axis.set_major_formatter(label)
            axis.set_minor_formatter(label)
        elif ratio < 1000:
            axis.set_major_formatter(label)
            axis.set_minor_locator(LogLocator(subs=(2.0, 5.0)))
            axis.set_minor_formatter(label)
        else:
            axis.set_minor_formatter(NullFormatter())


def figure_error_vs_time(out_dir, series, metrics, twins):
    import matplotlib.pyplot as plt

    fields = [("temperature", "temperature_noise", "temperature L2 / dT")]
    if any(series.has(f"velocity_l2_{t}") for t in twins):
        fields.append(("velocity", "velocity_noise", "velocity L2 / U"))
    seconds = series.numbers("wall_seconds")
    fig, axes = plt.subplots(1, len(fields), figsize=(5.6 * len(fields), 4.4), squeeze=False,
                             layout="constrained")
    for ax, (field, noise_column, ylabel) in zip(axes[0], fields):
        for twin in twins:
            column = f"{field}_l2_{twin}"
            if not series.has(column):
                continue
            ax.errorbar(seconds, series.numbers(column), yerr=series.numbers(column + "_stderr"),
                        fmt="o" + LINESTYLE[twin], ms=4, capsize=2.5, color=COLOUR[twin],
                        label=f"L2, {TWIN_LABEL[twin]}")
            floor = number(metrics, "twins", twin, field, "excess_over_noise")
            if finite(floor) and floor > 0:
                ax.axhline(floor, color=COLOUR[twin], ls=":", lw=1.3,
                           label=f"floor (final excess over noise), {twin}: {fmt(floor, 3)}")
        if series.has(noise_column):
            noise = series.numbers(noise_column)
            ax.plot(seconds, noise, "-", color=COLOUR["noise"], lw=1.6,
                    label="noise (identical twins would show this)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("particle run wall-clock time [s]")
        ax.set_ylabel(ylabel)
        ax.set_title(f"{field}: distance of the cumulative particle average to the twins",
                     fontsize=10)
        ax.grid(alpha=0.3, which="both")
        plain_log_ticks(ax)
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    save_figure(fig, out_dir, "error_vs_time.png")
    return [f[0] for f in fields]


def within_noise_sentence(name, distance):
    l2, se, noise = (number(distance, k) for k in ("l2", "l2_stderr", "noise"))
    if not (finite(l2) and finite(noise)):
        return f"{name}: no L2 in metrics.json."
    head = f"{name}: L2 = {fmt_pm(l2, se)} against a noise of {fmt(noise, 3)}"
    if finite(se) and se > 0:
        over = (l2 - noise) / se
        verdict = ("within noise" if over <= WITHIN_NOISE_STDERRS else
                   "not within noise: a difference between the twins")
        side = "above" if over >= 0 else "below"
        return f"{head}, {fmt(abs(over), 3)} standard errors {side} it — {verdict}."
    return head + (" — within noise." if l2 <= noise else " — above the noise (no standard error).")


def nusselt_sentence(twin, twin_metrics, particle):
    difference = number(twin_metrics, "nusselt_particle_minus_twin")
    se = number(particle, "nusselt_stderr")
    twin_se = number(twin_metrics, "nusselt_stderr_from_coefficients")
    if not finite(difference):
        return None
    text = (f"Nusselt number, {TWIN_LABEL[twin]}: particle − twin = {fmt(difference)}"
            f" ({fmt_percent(number(twin_metrics, 'nusselt_relative_difference'))} of the twin's)")
    if finite(twin_se) and finite(se):
        # The twin's error: its heat flux's response to the measured coefficients' errors (and
        # the Kapitza twin's to its conductances').
        both = math.hypot(se, twin_se)
        over = abs(difference) / both
        verdict = "within the errors" if over <= WITHIN_NOISE_STDERRS else "not within the errors"
        return text + (f", {fmt(over, 3)} combined standard errors (particle {fmt(se, 2)}, twin "
                       f"{fmt(twin_se, 2)} from its measured inputs) — {verdict}.")
    if finite(se) and se > 0:
        over = abs(difference) / se
        verdict = "within noise" if over <= WITHIN_NOISE_STDERRS else "not within noise"
        return text + f", {fmt(over, 3)} particle standard errors — {verdict}."
    return text + "."


def steady_verdict(imbalance_over_stderr):
    # In a steady state the two walls carry the same heat flow.
    if not finite(imbalance_over_stderr):
        return "no error estimate."
    if abs(imbalance_over_stderr) <= WITHIN_NOISE_STDERRS:
        return "the same flow within errors, as in a steady state."
    return (f"more than {fmt(WITHIN_NOISE_STDERRS, 2)} standard errors apart, so not a steady "
            "state within errors (the fluid still heating or cooling).")


def report_run(run_dir, out_dir):
    compare_dir = os.path.join(run_dir, "compare")
    metrics = read_json(os.path.join(compare_dir, "metrics.json"))
    bins = read_table(os.path.join(compare_dir, "bins.csv"))
    profiles = read_table(os.path.join(compare_dir, "profiles.csv"))
    series = read_table(os.path.join(compare_dir, "error_vs_time.csv"))
    particle_summary = read_json(os.path.join(run_dir, "particle", "summary.json"))
    summaries = {"nominal": read_json(os.path.join(run_dir, "continuum", "summary.json")),
                 "calibrated": read_json(os.path.join(run_dir, "continuum_calibrated",
                                                      "summary.json"))}
    twins = [t for t in TWINS if isinstance(lookup(metrics, "twins", t), dict)]
    particle = lookup(metrics, "particle") or {}
    geometry = RunGeometry(metrics, particle_summary, summaries["nominal"], bins)
    case = lookup(metrics, "case") or lookup(particle_summary, "case") or os.path.basename(
        os.path.abspath(run_dir))
    excluded = number(metrics, "wall_layer_excluded")
    doc = Document(f"Twin comparison: {case}")
    doc.paragraph(f"Run directory: {os.path.abspath(run_dir)}. Twins compared: "
                  + (", ".join(TWIN_LABEL[t] for t in twins) or "none") + ". " + UNITS_NOTE + ".")

    # Dimensionless numbers, each from the stage that states it.
    convection = lookup(particle_summary, "results", "convection") or {}
    rows = []
    if convection:
        rows.append(["particle (estimate, particle/summary.json)",
                     fmt(number(convection, "rayleigh")), fmt(number(convection, "prandtl")),
                     fmt(number(convection, "mach_measured"), 3),
                     fmt(number(convection, "delta_T_over_T"), 3), "–"])
    for twin in TWINS:
        d = lookup(summaries[twin], "dimensionless")
        if d:
            rows.append([f"{TWIN_LABEL[twin]} (continuum{'_calibrated' if twin == 'calibrated' else ''}"
                         "/summary.json)", fmt(number(d, "rayleigh")), fmt(number(d, "prandtl")),
                         "–", "–", fmt(number(d, "epsilon"), 3)])
    if rows:
        doc.heading("Dimensionless numbers")
        doc.table(["source", "Ra", "Pr", "Mach (measured)", "dT/T", "epsilon"], rows)
        note = lookup(convection, "note")
        if note:
            doc.paragraph(f"The particle stage's numbers: {note}.")

    doc.heading("What was compared")
    counts = lookup(metrics, "bins") or []
    doc.bullets([
        f"Bins: {' × '.join(str(int(c)) for c in counts)}; interior bins (counted in the "
        f"distances): {fmt(number(metrics, 'interior_bins'))}.",
        f"Wall layer: requested {fmt(number(metrics, 'wall_layer'))} rc; excluded thickness "
        f"{fmt(excluded)} rc (whole bins) at every wall.",
        f"Temperature scale dT = {fmt(number(metrics, 'temperature_scale'))} T0; velocity scale "
        f"U = {fmt(number(metrics, 'velocity_scale'))} rc/tau (the nominal twin's largest speed). "
        "L2 and max distances below are in these units.",
        f"Fields: {lookup(metrics, 'temperature_field') or 'temperature'}.",
    ] + ([f"Density scale n0 = {fmt(number(metrics, 'density_scale'))} rc^-d (the mean number "
          "density), for the low-Mach twin's n(P, T) against the particles' bin density."]
         if any(lookup(metrics, "twins", t, "density") for t in twins) else []))

    # The metrics, one column per twin.
    table_rows = []
    if twins:
        doc.heading("Distances between the twins")

        def row(label, values):
            table_rows.append([label] + values)

        for field, scale in (("temperature", "dT"), ("velocity", "U"), ("density", "n0")):
            if not any(lookup(metrics, "twins", t, field) for t in twins):
                continue
            d = {t: lookup(metrics, "twins", t, field) or {} for t in twins}
            row(f"{field} L2 / {scale}",
                [fmt_pm(number(d[t], "l2"), number(d[t], "l2_stderr")) for t in twins])
            row(f"{field} noise / {scale}", [fmt(number(d[t], "noise")) for t in twins])
            row(f"{field} excess over noise / {scale}",
                [fmt(number(d[t], "excess_over_noise")) for t in twins])
            row(f"{field} max / {scale} (at the bin centre [rc])",
                [f"{fmt_pm(number(d[t], 'max'), number(d[t], 'max_stderr'))} at "
                 f"({', '.join(fmt(v, 3) for v in (lookup(d[t], 'max_at') or [])[:geometry.dim])})"
                 for t in twins])
        row("Nu particle ± stderr",
            [fmt_pm(number(particle, "nusselt"), number(particle, "nusselt_stderr"))] * len(twins))
        row("Nu twin ± stderr from its measured coefficients and Kapitza conductances (heat "
            "flux / the nominal conduction flux, as the particle's)",
            [fmt_pm(number(metrics, "twins", t, "nusselt"),
                    number(metrics, "twins", t, "nusselt_stderr_from_coefficients"))
             for t in twins])
        row("Nu twin (its own dT)", [fmt(number(metrics, "twins", t, "nusselt_own")) for t in twins])
        row("Nu particle − twin",
            [fmt(number(metrics, "twins", t, "nusselt_particle_minus_twin")) for t in twins])
        row("Nu relative difference",
            [fmt_percent(number(metrics, "twins", t, "nusselt_relative_difference")) for t in twins])
        row("Ra of the twin", [fmt(number(metrics, "twins", t, "rayleigh")) for t in twins])
        doc.table(["quantity"] + [TWIN_LABEL[t] for t in twins], table_rows)
        sentences = []
        for t in twins:
            for field in ("temperature", "velocity", "density"):
                distance = lookup(metrics, "twins", t, field)
                if distance:
                    sentences.append(within_noise_sentence(f"{field}, {TWIN_LABEL[t]}", distance))
            s = nusselt_sentence(t, lookup(metrics, "twins", t), particle)
            if s:
                sentences.append(s)
        stratification = number(convection, "stratification_g_H_over_c2")
        if any(lookup(metrics, "twins", t, "density") for t in twins) and finite(stratification):
            # n ~ exp(-m g z / kT): across the height a linear profile of relative slope
            # g H / c^2, whose rms over the box is that / sqrt(12). The low-Mach twin's
            # thermodynamic pressure is uniform: it has no hydrostatic stratification.
            sentences.append(
                f"density: the particle fluid is stratified by gravity (g H / c^2 = "
                f"{fmt(stratification, 3)}: n ~ exp(−m g z / kT)), which the low-Mach twin "
                "leaves out (its thermodynamic pressure is uniform); that alone makes an rms "
                f"density difference of ~{fmt(stratification / math.sqrt(12), 2)} n0.")
        doc.paragraph(f"Within noise? A difference counts as within noise when the L2 exceeds the "
                      f"noise by at most {fmt(WITHIN_NOISE_STDERRS, 2)} of its standard errors (for "
                      f"Nu: when |Nu particle − Nu twin| is at most {fmt(WITHIN_NOISE_STDERRS, 2)} "
                      "standard errors: the particle's, combined with the twin's where its "
                      "coefficients were measured).")
        doc.bullets(sentences)

    if finite(number(particle, "nusselt")):
        doc.heading("Particle heat flow")
        doc.bullets([
            f"Nu = {fmt_pm(number(particle, 'nusselt'), number(particle, 'nusselt_stderr'))} "
            f"(mean of the two walls; heat flux {fmt_pm(number(particle, 'heat_flux'), number(particle, 'heat_flux_stderr'))} "
            "k T0 / (rc^(d-1) tau)).",
            f"hot wall Nu = {fmt(number(particle, 'nusselt_hot_wall'))}, cold wall Nu = "
            f"{fmt(number(particle, 'nusselt_cold_wall'))}: they differ by "
            f"{fmt(number(particle, 'wall_imbalance_over_stderr'), 3)} standard errors: "
            + steady_verdict(number(particle, "wall_imbalance_over_stderr")),
        ])

    jumps = lookup(particle, "wall_temperature_jumps") or {}
    if jumps:
        doc.heading("Wall temperature jumps (particle)")
        calibrated_parameters = lookup(summaries["calibrated"], "case_parameters") or {}
        rows = []
        for wall, j in jumps.items():
            axis, side = wall.split("_", 1) if "_" in wall else (wall, "")
            calibrated_wall = calibrated_parameters.get(
                f"Scene/{axis} boundaries/{side.capitalize()} wall temperature")
            rows.append([wall, fmt(number(j, "wall_temperature")),
                         fmt_pm(number(j, "fluid_temperature_at_wall"),
                                number(j, "fluid_temperature_at_wall_stderr")),
                         fmt(number(j, "jump")), fmt(number(j, "extrapolated_from_distance")),
                         fmt(to_float(calibrated_wall)) if calibrated_wall else "–"])
        doc.table(["wall", "wall T [T0]", "fluid T at the wall [T0]", "jump = wall − fluid [T0]",
                   "extrapolated from [rc]", "calibrated twin's wall T [T0]"], rows)
        doc.paragraph("The fluid's temperature at a wall is extrapolated linearly from the first "
                      "two bin layers beyond the wall layer (compare stage).")

    if "nominal" in twins and "calibrated" in twins:
        doc.heading("How much of the particle–continuum gap each correction explains")
        gap_rows = []

        def gap(label, nominal_value, calibrated_value):
            if finite(nominal_value) and finite(calibrated_value):
                explained = 1 - calibrated_value / nominal_value if nominal_value != 0 else math.nan
                gap_rows.append([label, fmt(nominal_value), fmt(calibrated_value),
                                 fmt_percent(explained)])

        for field, scale in (("temperature", "dT"), ("velocity", "U"), ("density", "n0")):
            gap(f"{field} L2 / {scale}", number(metrics, "twins", "nominal", field, "l2"),
                number(metrics, "twins", "calibrated", field, "l2"))
            gap(f"{field} excess over noise / {scale}",
                number(metrics, "twins", "nominal", field, "excess_over_noise"),
                number(metrics, "twins", "calibrated", field, "excess_over_noise"))
        gap("|Nu particle − Nu twin|",
            abs(number(metrics, "twins", "nominal", "nusselt_particle_minus_twin")),
            abs(number(metrics, "twins", "calibrated", "nusselt_particle_minus_twin")))
        doc.table(["gap", "nominal twin", f"calibrated twin ({calibration_text(metrics)})",
                   "fraction explained = 1 − calibrated / nominal"], gap_rows)
        differences = parameter_differences(summaries["nominal"], summaries["calibrated"])
        if differences:
            doc.paragraph("The calibrated twin's parameters that differ from the nominal twin's "
                          "(continuum*/summary.json): " + "; ".join(
                              f"{k}: {a} → {b}" for k, a, b in differences) +
                          ". The fraction explained is the part of each gap that this change "
                          "removes; a negative fraction means it made the gap larger.")
    wall_layer_table(doc, particle_summary, summaries.get("calibrated"))

    continuum_accuracy(doc, summaries, twins)

    # Figures.
    doc.heading("Figures")
    if bins and bins.rows and bins.has("T_particle"):
        reference, cut_text = figure_fields(out_dir, bins, geometry, twins, metrics)
        where = f"; 3D: {cut_text}" if cut_text else ""
        difference = (f", and particle − {TWIN_LABEL[reference]} on a diverging scale (×: the "
                      "largest interior difference, metrics.json max_at)" if reference else "")
        doc.figure("fields.png",
                   "Bin-averaged temperature: particle (T_kinetic)"
                   + "".join(", " + TWIN_LABEL[t] for t in twins) + " on one colour scale"
                   + difference + ". Arrows: bin velocities (one scale for all maps, key on the "
                   f"particle map). Hatched: the wall layer ({fmt(excluded)} rc) left out of the "
                   f"distances{where}. {UNITS_NOTE}.")
    if bins and bins.rows and any(bins.has(f"density_{t}") for t in twins):
        reference, _ = figure_fields(out_dir, bins, geometry, twins, metrics, "density")
        doc.figure("density.png",
                   "Bin-averaged number density: particle and the low-Mach twin's n(P, T) "
                   "(thermodynamic pressure P from the closed cavity's mass) on one colour scale"
                   + (f", and particle − {TWIN_LABEL[reference]}" if reference else "")
                   + f". Arrows and hatching as above. {UNITS_NOTE}.")
    if profiles and profiles.rows:
        titles = figure_profiles(out_dir, profiles, geometry, metrics, twins, excluded)
        doc.figure("profiles.png",
                   "Mid-line profiles (" + "; ".join(titles) + "), compare/profiles.csv ("
                   + ("; ".join(profiles.comments) or "mid-line profiles") + "): particle "
                   "bins with their block standard errors, the twins as lines; grey: the "
                   "excluded wall layer; squares: the walls' temperatures; diamonds: the particle "
                   f"fluid's temperature extrapolated to the wall. {UNITS_NOTE}.")
    layers = read_table(os.path.join(run_dir, "particle", "wall_layers.csv"))
    if layers and layers.rows:
        figure_wall_layers(out_dir, layers, particle_summary)
        doc.figure("wall_layers.png",
                   "The particle fluid in the layer at each wall (particle/wall_layers.csv, "
                   "slices parallel to the wall, block standard errors): number density, kinetic "
                   "temperature and the velocity along the wall against the distance h from the "
                   "wall plane; dashed: each wall's effective position (the Gibbs depth of its "
                   "density profile, where Compare/Effective walls puts the calibrated twin's "
                   f"wall). {UNITS_NOTE}.")
    if series and series.rows:
        fields = figure_error_vs_time(out_dir, series, metrics, twins)
        doc.figure("error_vs_time.png",
                   "L2 distance of the cumulative particle average to each twin against the "
                   "particle run's wall-clock time (log-log), with standard errors; solid grey: "
                   "the noise (the L2 two identical twins would show through the particle's "
                   "statistical error); dotted: the floor, the final excess over noise "
                   "(metrics.json).")
        floor_text(doc, series, metrics, twins, fields, particle, summaries)
    write_documents(doc, out_dir)


def continuum_accuracy(doc, summaries, twins):
    """The twins' own errors beside the particle's: discretisation (Nu against mesh level; the
    last change bounds the error of a converging sequence) and the measured coefficients'."""
    rows = []
    for twin in twins:
        for level in lookup(summaries[twin], "results", "mesh_study") or []:
            cells = "×".join(str(int(c)) for c in (lookup(level, "cells") or []))
            change = number(level, "change_in_nusselt")
            rows.append([TWIN_LABEL[twin], fmt(number(level, "level"), 2), cells,
                         fmt(number(level, "nusselt"), 7),
                         fmt(change, 2) if number(level, "level") > 0 else "–",
                         fmt(number(level, "wall_time_s"), 3)])
    if not rows:
        return
    doc.heading("The continuum twins' own errors")
    doc.paragraph("Mesh study (continuum*/summary.json, results.mesh_study): each level halves the "
                  "cells; the change in Nu from the level before bounds the discretisation error "
                  "of the finest level when the changes fall geometrically.")
    doc.table(["twin", "level", "cells", "Nu (own dT)", "change", "wall s"], rows)
    sentences = []
    for twin in twins:
        u = lookup(summaries[twin], "coefficient_uncertainty")
        if not u:
            continue
        names = ["conductivity", "viscosity"] + [f"kapitza_{a}_{s}" for a in "xyz"
                                                 for s in ("lower", "upper")]
        parts = [f"{name.replace('_', ' ')} "
                 f"{fmt_pm(number(u, name, 'value'), number(u, name, 'stderr'))} moves the "
                 f"heat flux by {fmt_percent(number(u, name, 'heat_flux_relative_change'))} per "
                 "standard error" for name in names if lookup(u, name)]
        sentences.append(f"{TWIN_LABEL[twin]}: " + "; ".join(parts) + "; together ± "
                         f"{fmt_percent(number(u, 'heat_flux_relative_stderr'))}.")
    if sentences:
        doc.paragraph("The measured coefficients' errors (transport stage, from the spread of "
                      "repeated runs) and the Kapitza conductances' (from the particle walls' "
                      "heat-flux and fluid-temperature errors), one more solve each:")
        doc.bullets(sentences)


def parameter_differences(nominal_summary, calibrated_summary):
    """(key, nominal value, calibrated value) for every case parameter the twins differ in."""
    a = lookup(nominal_summary, "case_parameters") or {}
    b = lookup(calibrated_summary, "case_parameters") or {}
    return [(k, a.get(k, "–"), b.get(k, "–")) for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]


def floor_text(doc, series, metrics, twins, fields, particle, summaries):
    import numpy as np
    seconds = series.numbers("wall_seconds")
    items = []
    for field in fields:
        noise = series.numbers(f"{field}_noise") if series.has(f"{field}_noise") else None
        if noise is not None and np.isfinite(noise).sum() >= 2:
            items.append(f"{field} noise: {fmt(noise[0], 3)} at {fmt(seconds[0], 3)} s, "
                         f"{fmt(noise[-1], 3)} at {fmt(seconds[-1], 3)} s.")
        for twin in twins:
            floor = number(metrics, "twins", twin, field, "excess_over_noise")
            if finite(floor):
                items.append(f"{field} floor, {TWIN_LABEL[twin]}: {fmt(floor, 3)} (final L2 "
                             f"{fmt(number(metrics, 'twins', twin, field, 'l2'), 3)}).")
    doc.paragraph("The floor. The noise falls as 1/√t with sampling time; what stays as it falls is "
                  "the twins' physical difference, the excess over noise. Measured:")
    doc.bullets(items)
    # What sets the floor, in the numbers of this run.
    causes = []
    jumps = lookup(particle, "wall_temperature_jumps") or {}
    scale = number(metrics, "temperature_scale")
    nominal_range = (number(summaries["nominal"], "results", "temperature_min"),
                     number(summaries["nominal"], "results", "temperature_max"))
    if jumps:
        causes.append("Wall temperature jumps of the particle fluid: " + "; ".join(
            f"{wall}: {fmt(number(j, 'jump'), 3)} T0 ({fmt_percent(number(j, 'jump') / scale)} of dT)"
            for wall, j in jumps.items()) +
            (f". The nominal twin's temperature spans {fmt(nominal_range[0], 3)} … "
             f"{fmt(nominal_range[1], 3)} T0, the walls are at " +
             ", ".join(fmt(number(j, "wall_temperature"), 3) for j in jumps.values()) +
             " T0: the jumps are part of its floor." if all(finite(v) for v in nominal_range)
             else "."))
    if "nominal" in twins and "calibrated" in twins:
        n_floor = number(metrics, "twins", "nominal", "temperature", "excess_over_noise")
        c_floor = number(metrics, "twins", "calibrated", "temperature", "excess_over_noise")
        if finite(n_floor) and finite(c_floor) and n_floor > 0:
            causes.append(f"With {calibration_text(metrics)} (calibrated twin) the "
                          f"temperature floor goes from {fmt(n_floor, 3)} to {fmt(c_floor, 3)} "
                          f"({fmt_percent(c_floor / n_floor)} of the nominal twin's): the rest of "
                          "the calibrated twin's floor is what that wall condition does not explain.")
    for twin in twins:
        rel = number(metrics, "twins", twin, "nusselt_relative_difference")
        if finite(rel):
            causes.append(f"Heat flow: the particle's Nu differs from the {TWIN_LABEL[twin]}'s by "
                          f"{fmt_percent(rel)} of the twin's.")
    if causes:
        doc.paragraph("What sets it, from this run's numbers:")
        doc.bullets(causes)


def write_documents(doc, out_dir):
    write_text(os.path.join(out_dir, "report.md"), doc.markdown())
    write_text(os.path.join(out_dir, "report.html"), doc.html())


# ---------------------------------------------------------------------------------------------
# Sweep and stability directories: shared pieces

def varied_keys(table, stop_columns):
    """The columns between exit_code and the first of the command's own columns."""
    header = table.header
    if "exit_code" not in header:
        return []
    keys = []
    for column in header[header.index("exit_code") + 1:]:
        if column in stop_columns:
            break
        keys.append(column)
    return keys


class Axis:
    """The values of one column as a plot axis: numbers (maybe log) or categories."""

    def __init__(self, name, texts):
        self.name = name
        values = [to_float(t) for t in texts if t != ""]
        self.numeric = bool(values) and all(math.isfinite(v) for v in values)
        shown = dict(sorted({to_float(t): t for t in texts if t != ""}.items()))
        self.values, self.texts = list(shown), list(shown.values())
        if self.numeric:
            self.categories = []
            positive = [v for v in values if v > 0]
            self.log = len(positive) == len(values) and max(values) >= 10 * min(values)
        else:
            self.categories = list(dict.fromkeys(t for t in texts if t != ""))
            self.log = False

    def position(self, text):
        if self.numeric:
            return to_float(text)
        return self.categories.index(text) if text in self.categories else math.nan

    def apply(self, ax, which="x", ticks_at_values=False):
        set_scale = ax.set_xscale if which == "x" else ax.set_yscale
        if self.numeric:
            if self.log:
                set_scale("log")
            if ticks_at_values:
                # A tick at each value of the grid, labelled as the user wrote it.
                from matplotlib.ticker import NullLocator
                axis = ax.xaxis if which == "x" else ax.yaxis
                axis.set_minor_locator(NullLocator())
                axis.set_ticks(self.values, self.texts)
        else:
            positions = range(len(self.categories))
            if which == "x":
                ax.set_xticks(list(positions), self.categories)
                ax.set_xlim(-0.5, len(self.categories) - 0.5)
            else:
                ax.set_yticks(list(positions), self.categories)
                ax.set_ylim(-0.5, len(self.categories) - 0.5)


# Units of the keys a sweep or stability map commonly varies (the rest are shown as is).
KEY_UNITS = {"Particle/Time step": "tau", "Scene/Density": "rc^-d", "Scene/Temperature": "T0",
             "Particle/Internal energy/Heat capacity": "k",
             "Particle/Conservative force/a0": "k T0 / rc"}


def with_unit(key):
    return f"{key} [{KEY_UNITS[key]}]" if key in KEY_UNITS else key


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_") or "value"


def plain(text):
    """A key for a table cell or label: the CSV text as is, else a dash."""
    return text if text not in (None, "") else "–"


# ---------------------------------------------------------------------------------------------
# Sweep directory

SWEEP_OWN_COLUMNS = ("target_rayleigh", "gravity", "wall_seconds")


def study_case_name(grid, directory):
    """The case's name, else its file's name, else the directory's."""
    name = lookup(grid, "base_parameters", "Case name")
    if name:
        return name
    case_file = lookup(grid, "case_file")
    if case_file:
        return re.sub(r"\.prm$", "", os.path.basename(case_file))
    return os.path.basename(os.path.abspath(directory))


def walls_no_slip(grid):
    """True / False from the base parameters' walled directions' Slip, None when not stated."""
    parameters = lookup(grid, "base_parameters") or {}
    answers = []
    for axis in AXES:
        if parameters.get(f"Scene/{axis} boundaries/Type") == "walls":
            slip = parameters.get(f"Scene/{axis} boundaries/Slip")
            if slip is not None:
                answers.append(slip == "no-slip")
    return all(answers) if answers else None


def sweep_groups(rows, series_key, order):
    """(label, rows) per value of the series key, in the grid's order (then first seen); one
    group without a series key."""
    if not series_key:
        return [("", rows)]
    labels = [v for v in order if any(r.get(series_key, "") == v for r in rows)]
    labels += [v for v in dict.fromkeys(r.get(series_key, "") for r in rows) if v not in labels]
    return [(f"{series_key} = {label}", [r for r in rows if r.get(series_key, "") == label])
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
    xs = [x_axis.position(r.get(x_column, "")) for r in rows]
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
        xs = np.array([x_axis.position(r.get(x_column, "")) for r in rows], dtype=float)
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
        finite(to_float(r.get(f"temperature_l2_{t}"))) for r in done)), None)
    if twin is None:
        return None
    rows = [r for r in done if finite(to_float(r.get(f"temperature_l2_{twin}")))
            and finite(to_float(r.get("wall_seconds_particle")))]
    if len(rows) < 2:
        return None
    points = [(to_float(r["wall_seconds_particle"]), to_float(r[f"temperature_l2_{twin}"]))
              for r in rows]
    front = pareto_front(points)
    labels = [", ".join(f"{k.split('/')[-1]} {plain(r.get(k))}" for k in keys) or plain(
        r.get("point")) for r in rows]
    fig, ax = plt.subplots(figsize=(7.6, 4.8), layout="constrained")
    for i, ((c, e), r) in enumerate(zip(points, rows)):
        se = to_float(r.get(f"temperature_l2_{twin}_stderr"))
        ax.errorbar([c], [e], yerr=[se] if finite(se) else None, fmt="o",
                    color=COLOUR["calibrated" if i in front else "noise"], ms=6, capsize=2.5)
        same = sum(1 for p in points[:i] if p == (c, e))  # stack the labels of equal points
        ax.annotate(labels[i], (c, e), textcoords="offset points", xytext=(5, 4 - 9 * same),
                    fontsize=7)
    ax.step([points[i][0] for i in front], [points[i][1] for i in front], where="post",
            color=COLOUR["calibrated"], lw=1.2, label="Pareto front")
    noise = [to_float(r.get("temperature_l2_noise")) for r in rows]
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
                  "time, one point per sweep point (labels: the varied keys); filled: on the Pareto "
                  "front; crosses: each point's noise level, the floor no run length removes.")


def realisations_section(doc, done):
    """Points that differ only in the seed are realisations of one case: each point's Nu gap to
    the calibrated twin against its allowance (both errors + 3%), and the mean gap with its
    standard error from the spread between realisations."""
    rows, relative = [], []
    for r in done:
        p, ps = to_float(r.get("nusselt_particle")), to_float(r.get("nusselt_particle_stderr"))
        c, cs = to_float(r.get("nusselt_calibrated")), to_float(r.get("nusselt_calibrated_stderr"))
        if not all(finite(v) for v in (p, ps, c)) or c == 0:
            continue
        cs = cs if finite(cs) else 0.0
        allowance = ps + cs + 0.03 * abs(c)
        relative.append(p / c - 1)
        rows.append([plain(r.get("Particle/Seed")), fmt_pm(p, ps), fmt_pm(c, cs),
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


def report_sweep(sweep_dir, out_dir):
    import matplotlib.pyplot as plt

    table = Table(os.path.join(sweep_dir, "sweep.csv"))
    description = read_json(os.path.join(sweep_dir, "sweep.json")) or {}
    grid = lookup(description, "grid") or {}
    keys = varied_keys(table, SWEEP_OWN_COLUMNS) or list((lookup(grid, "vary") or {}).keys())
    done = [r for r in table.rows if r.get("status") == "done"]
    not_done = [r for r in table.rows if r.get("status") != "done"]
    by_rayleigh = table.has("target_rayleigh") and any(
        finite(to_float(r.get("target_rayleigh"))) for r in table.rows)
    if by_rayleigh:
        # The continuum's Ra where it ran, else the target.
        x_column = "rayleigh_axis"
        for r in table.rows:
            measured = to_float(r.get("rayleigh"))
            r[x_column] = r.get("rayleigh") if finite(measured) else r.get("target_rayleigh", "")
        x_label, x_name, series_key = "Rayleigh number Ra (nominal twin)", "rayleigh", (
            keys[0] if keys else None)
    elif keys:
        x_column, x_label, x_name = keys[0], with_unit(keys[0]), slug(keys[0])
        series_key = keys[1] if len(keys) > 1 else None
    else:
        x_column, x_label, x_name, series_key = "point", "point", "point", None
    x_axis = Axis(x_column, [r.get(x_column, "") for r in done] or [""])
    if by_rayleigh:
        x_axis.log = True
    groups = sweep_groups(done, series_key,
                          [str(v) for v in (lookup(grid, "vary", series_key) or [])]
                          if series_key else [])

    case_name = study_case_name(grid, sweep_dir)
    doc = Document(f"Sweep: {case_name}")
    doc.paragraph(f"Sweep directory: {os.path.abspath(sweep_dir)}. Case file: "
                  f"{lookup(grid, 'case_file') or '–'}. {UNITS_NOTE}.")
    grid_items = [f"{k}: {', '.join(map(str, v))}" for k, v in (lookup(grid, "vary") or {}).items()]
    if not grid_items:  # sweep.json without the grid: the values in the table
        grid_items = [f"{k}: " + ", ".join(dict.fromkeys(r.get(k, "") for r in table.rows))
                      for k in keys]
    targets = lookup(grid, "rayleigh")
    if targets:
        grid_items.append("target Rayleigh numbers (gravity scaled): " +
                          ", ".join(fmt(to_float(t)) for t in targets))
    doc.heading("Grid")
    doc.bullets(grid_items or ["(sweep.json states no grid)"])
    doc.paragraph(f"{len(table.rows)} points: {len(done)} done, {len(not_done)} not done.")

    figures = []

    def finish(ax, handles, ylabel, title, legend=True):
        handles = handles + mark_not_done(ax, x_axis, x_column, not_done)
        x_axis.apply(ax, "x")
        ax.set_xlabel(x_label)
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which="both")
        plain_log_ticks(ax)
        if handles and legend:
            ax.legend(handles=handles, fontsize=8, loc="upper left", bbox_to_anchor=(1.02, 1))

    nusselt_columns = ("nusselt_particle", "nusselt_nominal", "nusselt_calibrated")
    if done and any(table.has(c) for c in nusselt_columns):
        # Nusselt numbers.
        fig, ax = plt.subplots(figsize=(8.4, 4.8), layout="constrained")
        handles = draw_sources(ax, table, groups, x_axis, x_column, [
            ("particle ± stderr", "nusselt_particle", "nusselt_particle_stderr", COLOUR["particle"]),
            ("nominal twin", "nusselt_nominal", None, COLOUR["nominal"]),
            ("calibrated twin", "nusselt_calibrated", None, COLOUR["calibrated"])])
        no_slip = walls_no_slip(grid)
        benchmark_note = None
        if by_rayleigh and no_slip is not False:
            from matplotlib.lines import Line2D
            ra, nu = zip(*DE_VAHL_DAVIS_NUSSELT)
            label = "de Vahl Davis 1983, no-slip, Pr 0.71" + (
                "" if no_slip else " (walls' slip not stated)")
            ax.plot(ra, nu, "*", ms=10, color=COLOUR["benchmark"], zorder=4)
            handles.append(Line2D([], [], marker="*", ls="", ms=10, color=COLOUR["benchmark"],
                                  label=label))
            benchmark_note = ("Stars: de Vahl Davis (1983), Int. J. Numer. Meth. Fluids 3, 249, "
                              "Boussinesq cavity with no-slip walls at Pr = 0.71"
                              + ("" if no_slip else "; the sweep does not state its walls' slip")
                              + ".")
        elif by_rayleigh:
            benchmark_note = ("de Vahl Davis's no-slip benchmark is not drawn: this case's walls "
                              "are not all no-slip.")
        finish(ax, handles, "Nusselt number Nu", f"Nusselt number against {x_label}")
        name = save_figure(fig, out_dir, f"nusselt_vs_{x_name}.png")
        figures.append((name, f"Nusselt numbers: the particle fluid's (with standard errors) and "
                              f"each continuum twin's, against {x_label}. "
                        + (benchmark_note or "")))

    if done:
        # Distances between the twins.
        fields = [f for f in ("temperature", "velocity") if any(
            table.has(f"{f}_l2_{t}") for t in TWINS)]
        if fields:
            fig, axes = plt.subplots(1, len(fields), figsize=(5.4 * len(fields) + 2.4, 4.6),
                                     squeeze=False, layout="constrained")
            for n, (ax, field) in enumerate(zip(axes[0], fields)):
                handles = draw_sources(ax, table, groups, x_axis, x_column, [
                    ("nominal twin ± stderr", f"{field}_l2_nominal", f"{field}_l2_nominal_stderr",
                     COLOUR["nominal"]),
                    ("calibrated twin ± stderr", f"{field}_l2_calibrated",
                     f"{field}_l2_calibrated_stderr", COLOUR["calibrated"]),
                    ("noise", f"{field}_l2_noise", None, COLOUR["noise"])])
                ax.set_yscale("log")
                finish(ax, handles, f"{field} L2 / {'dT' if field == 'temperature' else 'U'}",
                       f"{field}: L2 distance particle–twin and the noise",
                       legend=n == len(fields) - 1)  # one legend serves both panels
            name = save_figure(fig, out_dir, f"errors_vs_{x_name}.png")
            figures.append((name, "L2 distance of the particle fields to each twin (interior bins, "
                                  "in units of the point's temperature / velocity scale) with "
                                  "standard errors, and the noise: the L2 two identical twins "
                                  "would show through the particle's statistical error."))

        # Cost.
        stages = [("particle stage", "wall_seconds_particle", None, COLOUR["particle"]),
                  ("nominal twin", "wall_seconds_continuum", None, COLOUR["nominal"]),
                  ("calibrated twin", "wall_seconds_continuum_calibrated", None,
                   COLOUR["calibrated"]),
                  ("whole point", "wall_seconds", None, "black")]
        fig, ax = plt.subplots(figsize=(8.4, 4.8), layout="constrained")
        handles = draw_sources(ax, table, groups, x_axis, x_column, stages)
        ax.set_yscale("log")
        finish(ax, handles, "wall-clock time [s]", f"cost per stage against {x_label}")
        figures.append((save_figure(fig, out_dir, "cost.png"),
                        "Wall-clock seconds per stage and per point (the point's child process)."))
        pareto = None if by_rayleigh else figure_pareto(out_dir, done, keys, doc)
        if pareto:
            figures.append(pareto)

    doc.heading("Points")
    columns = [("point", "point"), ("status", "status")] + [(k, k) for k in keys]
    if by_rayleigh:
        columns += [("target Ra", "target_rayleigh"), ("Ra", "rayleigh")]
    rows = []
    for r in table.rows:
        cells = [plain(r.get(c)) if c in ("point", "status") or c in keys else
                 fmt(to_float(r.get(c))) for _, c in columns]
        cells += [fmt_pm(to_float(r.get("nusselt_particle")),
                         to_float(r.get("nusselt_particle_stderr"))),
                  fmt(to_float(r.get("nusselt_nominal"))), fmt(to_float(r.get("nusselt_calibrated"))),
                  fmt_pm(to_float(r.get("temperature_l2_nominal")),
                         to_float(r.get("temperature_l2_nominal_stderr"))),
                  fmt_pm(to_float(r.get("temperature_l2_calibrated")),
                         to_float(r.get("temperature_l2_calibrated_stderr"))),
                  fmt(to_float(r.get("temperature_l2_noise"))),
                  fmt(to_float(r.get("wall_seconds")))]
        rows.append(cells)
    doc.table([c[0] for c in columns] + ["Nu particle", "Nu nominal", "Nu calibrated",
                                          "T L2 nominal", "T L2 calibrated", "T noise",
                                          "wall s"], rows)
    if keys == ["Particle/Seed"]:
        realisations_section(doc, done)
    doc.heading("Points not done")
    if not_done:
        doc.table(["point", "status", "exit code", "reason"],
                  [[plain(r.get("point")), plain(r.get("status")), plain(r.get("exit_code")),
                    plain(r.get("reason"))] for r in not_done])
    else:
        doc.paragraph("None: every point finished.")
    if figures:
        doc.heading("Figures")
        for name, caption in figures:
            doc.figure(name, caption + f" {UNITS_NOTE}.")
    write_documents(doc, out_dir)


# ---------------------------------------------------------------------------------------------
# Stability directory

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
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    table = Table(os.path.join(stability_dir, "stability.csv"))
    description = read_json(os.path.join(stability_dir, "stability.json")) or {}
    grid = lookup(description, "grid") or {}
    keys = varied_keys(table, STABILITY_OWN_COLUMNS) or list((lookup(grid, "vary") or {}).keys())
    rows = table.rows
    case_name = study_case_name(grid, stability_dir)
    doc = Document(f"Stability map: {case_name}")
    doc.paragraph(f"Stability directory: {os.path.abspath(stability_dir)}. Case file: "
                  f"{lookup(grid, 'case_file') or '–'}. {UNITS_NOTE}.")
    doc.heading("Grid")
    doc.bullets([f"{k}: {', '.join(map(str, v))}" for k, v in (lookup(grid, "vary") or {}).items()]
                or [f"{k}" for k in keys])
    counts = {}
    for r in rows:
        counts[r.get("status", "")] = counts.get(r.get("status", ""), 0) + 1
    doc.paragraph(f"{len(rows)} points: " + ", ".join(f"{n} {s}" for s, n in counts.items()) + ".")

    if rows and keys:
        x_key = keys[0]
        y_key = keys[1] if len(keys) > 1 else None
        x_axis = Axis(x_key, [r.get(x_key, "") for r in rows])
        y_axis = Axis(y_key, [r.get(y_key, "") for r in rows]) if y_key else None
        fig, ax = plt.subplots(figsize=(7.6, 5.2 if y_key else 2.9), layout="constrained")
        seen = []
        for r in rows:
            status = r.get("status", "")
            colour, marker = STATUS_STYLE.get(status, ("0.75", "o"))
            x = x_axis.position(r.get(x_key, ""))
            y = y_axis.position(r.get(y_key, "")) if y_axis else 0.0
            predicted = r.get("predicted_stable", "").strip().lower()
            hollow = predicted in ("false", "0", "no")
            ax.plot([x], [y], marker=marker, ms=11, ls="", color=colour,
                    mfc="none" if hollow else colour, mew=2, zorder=3)
            if status not in seen:
                seen.append(status)
        seen.sort(key=lambda s: list(STATUS_STYLE).index(s) if s in STATUS_STYLE else len(STATUS_STYLE))
        handles = [Line2D([], [], marker=STATUS_STYLE.get(s, ("0.75", "o"))[1], ls="", ms=9,
                          color=STATUS_STYLE.get(s, ("0.75", "o"))[0], label=s or "(no status)")
                   for s in seen]
        handles += [Line2D([], [], marker="o", ls="", ms=9, color="0.3", label="predicted stable"),
                    Line2D([], [], marker="o", ls="", ms=9, color="0.3", mfc="none", mew=2,
                           label="predicted unstable (hollow)")]
        # The predicted critical time step (001 eq. (28)) where dt is one of the axes.
        if TIME_STEP_KEY in (x_key, y_key) and table.has("predicted_dt_critical"):
            other = y_axis if x_key == TIME_STEP_KEY else x_axis
            other_key = y_key if x_key == TIME_STEP_KEY else x_key
            by_other = {}
            for r in rows:
                dt_c = to_float(r.get("predicted_dt_critical"))
                if finite(dt_c):
                    key = r.get(other_key, "") if other_key else ""
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
            if values:
                value_text = f" = {fmt(values[0], 3)} tau" if len(values) == 1 else ""
                handles.append(Line2D([], [], label=f"predicted dt_critical{value_text}, "
                                                    "001 eq. (28)", **line))
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
        doc.heading("Map")
        doc.figure("stability_map.png",
                   "One marker per point, colour and shape by the observed status; hollow where "
                   "the prediction (001 eq. (28) and the fluctuation number) says unstable"
                   + ("; dashed: the predicted critical time step dt_critical (001 eq. (28))"
                      if TIME_STEP_KEY in keys else "") + f". {UNITS_NOTE}.")

    doc.heading("Points")
    header = ["point", "status"] + keys + ["dt [tau]", "predicted dt_critical", "fluctuation number",
                                           "predicted stable", "max |dE/E|", "T_kinetic",
                                           "T_internal", "T relative error", "wall s", "reason"]
    table_rows = []
    for r in rows:
        table_rows.append([plain(r.get("point")), plain(r.get("status"))]
                          + [plain(r.get(k)) for k in keys]
                          + [fmt(to_float(r.get(c))) for c in (
                              "dt", "predicted_dt_critical", "fluctuation_number")]
                          + [plain(r.get("predicted_stable"))]
                          + [fmt(to_float(r.get(c)), 3) for c in ("energy_relative_drift_max",)]
                          + [fmt(to_float(r.get(c)), 5) for c in ("T_kinetic", "T_internal")]
                          + [fmt(to_float(r.get(c)), 3) for c in (
                              "temperature_relative_error", "wall_seconds")]
                          + [plain(r.get("reason"))])
    doc.table(header, table_rows)
    agree = [r for r in rows if r.get("status") in STATUS_STYLE and r.get("status") != "failed"
             and r.get("predicted_stable", "").lower() in ("true", "false")]
    if agree:
        matches = sum((r["status"] == "stable") == (r["predicted_stable"].lower() == "true")
                      for r in agree)
        doc.paragraph(f"Prediction against observation: {matches} of {len(agree)} points agree "
                      "(predicted stable and observed stable, or predicted unstable and observed "
                      "any other status; failed points left out).")
    write_documents(doc, out_dir)


# ---------------------------------------------------------------------------------------------

def kind_of(directory):
    if os.path.isfile(os.path.join(directory, "compare", "metrics.json")):
        return "run"
    if all(os.path.isfile(os.path.join(directory, f)) for f in ("sweep.csv", "sweep.json")):
        return "sweep"
    if all(os.path.isfile(os.path.join(directory, f)) for f in ("stability.csv", "stability.json")):
        return "stability"
    return None


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        fail("usage: python3 compare/report.py DIR (a run, sweep or stability directory)")
    directory = argv[1]
    kind = kind_of(directory)
    if kind is None:
        fail(f"{directory}: not a run (compare/metrics.json), sweep (sweep.csv, sweep.json) or "
             "stability (stability.csv, stability.json) directory")
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        fail("matplotlib is missing (Debian: apt-get install python3-matplotlib)")
    # Written to a hidden temporary folder and renamed: an interrupted report never looks complete.
    final = os.path.join(directory, "report")
    work = tempfile.mkdtemp(prefix=".report-", dir=directory)
    try:
        {"run": report_run, "sweep": report_sweep, "stability": report_stability}[kind](
            directory, work)
        os.chmod(work, 0o755)
        old = None
        if os.path.exists(final):
            old = tempfile.mkdtemp(prefix=".report-old-", dir=directory)
            os.rename(final, os.path.join(old, "report"))
        os.rename(work, final)
        if old:
            shutil.rmtree(old)
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    written = sorted(os.listdir(final))
    print(f"report: {kind} report in {final}: {', '.join(written)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
