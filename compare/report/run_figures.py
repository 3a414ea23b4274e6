"""The run report's figures: field maps (fields.png, density.png), midline profiles
(profiles.png), the wall layers (wall_layers.png and their table) and the error against run time
(error_vs_time.png), with the scene geometry they are drawn in."""

import math

from .data import AXES, TWIN_LABEL, finite, fmt, fmt_pm, lookup, number, present, to_float
from .figures import COLOUR, LINESTYLE, colour_bar, edges, nice_arrow, plain_log_ticks, \
    save_figure


class RunGeometry:
    """What the figures need of the scene: box, walled directions, heated and vertical axes."""

    def __init__(self, metrics, particle_summary, nominal_summary, bins):
        parameters = lookup(particle_summary, "parameters") or \
            lookup(nominal_summary, "case_parameters") or {}

        def parameter(key, default):
            value = lookup(parameters, key)
            return default if value is None else value

        counts = lookup(metrics, "bins") or []
        self.dim = len(counts) or int(to_float(parameter("Scene/Dimension", "2")) or 2)
        box = [to_float(v) for v in str(parameter("Scene/Box size", "")).split(",")]
        if len(box) != self.dim or not all(math.isfinite(v) for v in box):
            box = self._box_from_bins(bins)
        self.box = box
        self.walled = [parameter(f"Scene/{AXES[d]} boundaries/Type", "") == "walls"
                       for d in range(self.dim)]
        # Heated direction: the one whose two walls' temperatures differ (metrics.json), else
        # the continuum's, else x.
        self.heated = None
        jumps = lookup(metrics, "particle", "wall_temperature_jumps") or {}
        for d in range(self.dim):
            # Only thermal walls have a jump.
            lower = number(lookup(jumps, f"{AXES[d]}_lower", optional=True), "wall_temperature")
            upper = number(lookup(jumps, f"{AXES[d]}_upper", optional=True), "wall_temperature")
            if finite(lower) and finite(upper) and lower != upper:
                self.heated = d
                break
        if self.heated is None:
            d = number(nominal_summary, "dimensionless", "heated_direction")
            self.heated = int(d) if finite(d) and 0 <= d < self.dim else 0
        gravity = [to_float(v) for v in str(parameter("Scene/Gravity", "")).split(",")]
        self.vertical = None
        if len(gravity) == self.dim and any(finite(g) and g != 0 for g in gravity):
            self.vertical = max(range(self.dim), key=lambda d: abs(gravity[d]))
        if self.vertical is None or self.vertical == self.heated:
            self.vertical = next(d for d in range(self.dim) if d != self.heated)

    def _box_from_bins(self, bins):
        box = []
        for d in range(self.dim):
            centres = sorted({to_float(lookup(r, AXES[d])) for r in (bins.rows if bins else [])})
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
        cut_values = sorted({to_float(lookup(r, AXES[cut])) for r in rows})
        layer = cut_values[len(cut_values) // 2]
        rows = [r for r in rows if to_float(lookup(r, AXES[cut])) == layer]
        where = ("the middle layer" if len(cut_values) % 2 else
                 "the first layer above the mid-plane")
        cut_text = (f"the bin layer at {AXES[cut]} = {fmt(layer)} rc (layer "
                    f"{len(cut_values) // 2 + 1} of {len(cut_values)}, {where})")
    xs = np.array(sorted({to_float(lookup(r, AXES[a])) for r in rows}))
    ys = np.array(sorted({to_float(lookup(r, AXES[b])) for r in rows}))
    index = {(to_float(lookup(r, AXES[a])), to_float(lookup(r, AXES[b]))): r for r in rows}

    def grid(column, optional=True):
        """A (len(ys), len(xs)) array of the column, NaN where absent."""
        out = np.full((len(ys), len(xs)), np.nan)
        if not bins.has(column, optional=optional):
            return out
        for j, y in enumerate(ys):
            for i, x in enumerate(xs):
                r = index.get((x, y))
                if r is not None:
                    out[j, i] = to_float(lookup(r, column))
        return out

    return a, b, xs, ys, grid, cut_text, layer


# The field maps: temperature (fields.png) and, beside a low-Mach twin, number density
# (density.png); bins.csv columns <prefix>_particle and <prefix>_<twin>.
FIELD_MAPS = {
    "temperature": {"prefix": "T", "symbol": "T", "unit": "T0", "cmap": "plasma",
                    "particle": "particle (DPDE), T_kinetic", "twin": ", T",
                    "file": "fields.png"},
    "density": {"prefix": "density", "symbol": "n", "unit": "rc^-d", "cmap": "viridis",
                "particle": "particle (DPDE), n", "twin": ", n(P, T)", "file": "density.png"},
}


class FieldMaps:
    """One field's maps (FIELD_MAPS) on the plane bin_plane shows: the particle's and each twin's
    on one colour scale with one arrow scale, and the particle's difference to a twin."""

    def __init__(self, bins, geometry, twins, field):
        import numpy as np

        self.spec, self.field, self.geometry = FIELD_MAPS[field], field, geometry
        prefix = self.spec["prefix"]
        self.a, self.b, self.xs, self.ys, self.grid, self.cut_text, self.layer = \
            bin_plane(bins, geometry)
        self.cut = geometry.plane()[2]
        self.ex, self.ey = edges(self.xs), edges(self.ys)
        # Every twin has a temperature column; only a low-Mach twin has a density one.
        self.sources = [("particle", self.spec["particle"])] + \
            [(t, TWIN_LABEL[t] + self.spec["twin"]) for t in twins
             if bins.has(f"{prefix}_{t}", optional=field == "density")]
        self.maps = {name: self.grid(f"{prefix}_{name}", optional=False)
                     for name, _ in self.sources}
        # The difference map against the nominal twin (the prediction), else the calibrated one.
        self.reference = next((t for t in ("nominal", "calibrated") if t in self.maps), None)
        self.low = min(np.nanmin(m) for m in self.maps.values())
        self.high = max(np.nanmax(m) for m in self.maps.values())
        self.interior = self.grid("interior", optional=False)
        # One arrow scale for every map: the largest bin speed spans ~0.9 of a bin.
        speeds = [np.hypot(*self.velocity(n)) for n, _ in self.sources]
        self.v_max = max((np.nanmax(s) for s in speeds if np.isfinite(s).any()),
                         default=math.nan)
        spacing = min(self.ex[1] - self.ex[0], self.ey[1] - self.ey[0])
        self.arrow_scale = (self.v_max / (0.9 * spacing)
                            if finite(self.v_max) and self.v_max > 0 else None)

    def velocity(self, name):
        """The bins' in-plane velocity (u, v) of a source, NaN where its columns are absent."""
        return self.grid(f"v{AXES[self.a]}_{name}"), self.grid(f"v{AXES[self.b]}_{name}")

    def figure(self, panels):
        """The figure and its axes (flat): one row of panels, 2 × 2 for four, each as tall as the
        plane's aspect makes it."""
        import matplotlib.pyplot as plt

        columns = 2 if panels == 4 else panels
        rows = math.ceil(panels / columns)
        aspect = (self.ey[-1] - self.ey[0]) / (self.ex[-1] - self.ex[0])
        fig, axes = plt.subplots(rows, columns,
                                 figsize=(4.8 * columns, rows * (3.5 * aspect + 0.8)),
                                 squeeze=False, layout="constrained")
        # Room for the inset colour bars' labels, which the layout engine does not see.
        fig.get_layout_engine().set(wspace=0.18, hspace=0.06)
        return fig, axes.ravel()

    def frame(self, ax):
        """The plane's extent and axis labels, and the wall layer left out of the distances
        hatched."""
        from matplotlib.patches import Rectangle

        ex, ey = self.ex, self.ey
        ax.set_aspect("equal")
        ax.set_xlim(ex[0], ex[-1])
        ax.set_ylim(ey[0], ey[-1])
        ax.set_xlabel(f"{AXES[self.a]} [rc]")
        ax.set_ylabel(f"{AXES[self.b]} [rc]")
        for j in range(len(self.ys)):
            for i in range(len(self.xs)):
                if self.interior[j, i] == 0:
                    ax.add_patch(Rectangle((ex[i], ey[j]), ex[i + 1] - ex[i], ey[j + 1] - ey[j],
                                           fill=False, hatch="///", edgecolor=(0.6, 0.6, 0.6, 0.8),
                                           linewidth=0))

    def draw_source(self, fig, ax, name, title):
        """A source's map on the common colour scale, with its bin velocities (the arrow key on
        the particle's)."""
        import numpy as np

        image = ax.pcolormesh(self.ex, self.ey, self.maps[name], cmap=self.spec["cmap"],
                              vmin=self.low, vmax=self.high)
        colour_bar(fig, ax, image, f"{self.spec['symbol']} [{self.spec['unit']}]")
        u, v = self.velocity(name)
        if self.arrow_scale and np.isfinite(u).any():
            X, Y = np.meshgrid(self.xs, self.ys)
            arrows = ax.quiver(X, Y, u, v, color="white", scale=self.arrow_scale,
                               scale_units="xy", angles="xy", width=0.006, headwidth=4)
            if name == "particle":
                key = nice_arrow(0.5 * self.v_max)
                ax.quiverkey(arrows, 0.78, 1.035, key, f"{fmt(key, 2)} rc/tau", labelpos="E",
                             coordinates="axes", color="black", fontproperties={"size": 8})
        self.frame(ax)
        ax.set_title(title, loc="left", fontsize=10)

    def draw_difference(self, fig, ax, metrics):
        """particle − the reference twin on a diverging scale, × where the compare stage found
        the largest interior difference."""
        import numpy as np

        symbol, reference = self.spec["symbol"], self.reference
        difference = self.maps["particle"] - self.maps[reference]
        limit = np.nanmax(np.abs(difference))
        limit = limit if finite(limit) and limit > 0 else 1.0
        image = ax.pcolormesh(self.ex, self.ey, difference, cmap="RdBu_r", vmin=-limit,
                              vmax=limit)
        colour_bar(fig, ax, image,
                   f"{symbol}_particle − {symbol}_{reference} [{self.spec['unit']}]")
        self.frame(ax)
        at = lookup(metrics, "twins", reference, self.field, "max_at") or []
        if len(at) >= self.geometry.dim and (self.cut is None or at[self.cut] == self.layer):
            ax.plot([at[self.a]], [at[self.b]], "x", color="black", ms=10, mew=2)
        ax.set_title(f"particle − {TWIN_LABEL[reference]}", loc="left", fontsize=10)


def figure_fields(out_dir, bins, geometry, twins, metrics, field="temperature"):
    """fields.png (density.png for field="density"); returns the twin the difference map is
    against (None without a twin's map) and the 3D cut's text."""
    field_maps = FieldMaps(bins, geometry, twins, field)
    panels = len(field_maps.sources) + (1 if field_maps.reference else 0)
    fig, axes = field_maps.figure(panels)
    for ax, (name, title) in zip(axes, field_maps.sources):
        field_maps.draw_source(fig, ax, name, title)
    for ax in axes[panels:]:
        ax.set_visible(False)
    if field_maps.reference is not None:
        field_maps.draw_difference(fig, axes[len(field_maps.sources)], metrics)
    save_figure(fig, out_dir, field_maps.spec["file"])
    return field_maps.reference, field_maps.cut_text


def figure_profiles(out_dir, profiles, geometry, metrics, twins, excluded):
    import matplotlib.pyplot as plt

    h, g = geometry.heated, geometry.vertical
    H, G = AXES[h], AXES[g]
    along = {d: [r for r in profiles.rows if lookup(r, "direction") == AXES[d]]
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
            if profiles.has(f"{quantity}_{twin}", optional=quantity != "T"):
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
    # A scene without walls has none; a wall has a layer when the particle stage measured one
    # (effective_position); friction only a no-slip wall; a twin's wall a slip length or a
    # Kapitza conductance only when the calibration gave it one.
    walls = lookup(lookup(particle_summary, "results"), "walls", optional=True) or {}
    if not any(present(w, "effective_position") for w in walls.values()):
        return
    twin_walls = {}  # "x_lower" -> the calibrated twin's boundary entry
    for entry in lookup(calibrated_summary, "continuum_parameters", "boundaries") or []:
        for side in ("lower", "upper"):  # a periodic direction has neither
            if isinstance(lookup(entry, side, optional=True), dict):
                twin_walls[f"{lookup(entry, 'direction')}_{side}"] = lookup(entry, side)
    rows = []
    for name, w in walls.items():
        if not present(w, "effective_position"):
            continue
        twin = twin_walls.get(name, {})
        rows.append([name, fmt_pm(lookup(w, "effective_position"),
                                  lookup(w, "effective_position_stderr")),
                     fmt_pm(lookup(w, "friction_per_area"), lookup(w, "friction_per_area_stderr"))
                     if present(w, "friction_per_area") else "(free slip)",
                     fmt(lookup(twin, "slip_length")) if present(twin, "slip_length") else "none",
                     fmt(lookup(twin, "kapitza_conductance"))
                     if present(twin, "kapitza_conductance") else "none"])
    doc.heading("The walls' layers and what the calibrated twin takes from them", 3)
    doc.table(["wall", "effective position (Gibbs depth, rc)", "friction per area zeta",
               "calibrated twin: Navier slip b (rc)", "calibrated twin: Kapitza h_K"], rows)
    doc.paragraph("From particle/wall_layers.csv (report/wall_layers.png): the Gibbs depth is "
                  "where a step profile with the layer's particle count would start; zeta the "
                  "no-slip wall's tangential friction per area and slip velocity, so b = eta / "
                  "zeta less the depth at which it acts (Compare/Wall slip). Compare/Effective "
                  "walls moves the twin's walls to the Gibbs depths.")


def figure_wall_layers(out_dir, layers, particle_summary):
    """Density, temperature and tangential velocity against the distance from each wall."""
    import matplotlib.pyplot as plt

    walls = list(dict.fromkeys(lookup(r, "wall") for r in layers.rows))
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained")
    for k, wall in enumerate(walls):
        rows = [r for r in layers.rows if lookup(r, "wall") == wall]
        h = layers.numbers("h", rows)
        colour = f"C{k}"
        # The velocity along the wall: the first axis other than the wall's own.
        along = next((a for a in "xyz" if a != wall[0] and layers.has(f"v{a}")), None)
        for ax, column in zip(axes, ["density", "T_kinetic", f"v{along}" if along else None]):
            if column is None or not layers.has(column, optional=column == f"v{along}"):
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
        jump = lookup(jumps, f"{AXES[direction]}_{side}", optional=True)  # thermal walls only
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
            if not series.has(column, optional=field != "temperature"):
                continue
            ax.errorbar(seconds, series.numbers(column), yerr=series.numbers(column + "_stderr"),
                        fmt="o" + LINESTYLE[twin], ms=4, capsize=2.5, color=COLOUR[twin],
                        label=f"L2, {TWIN_LABEL[twin]}")
            floor = number(metrics, "twins", twin, field, "excess_over_noise")
            if finite(floor) and floor > 0:
                ax.axhline(floor, color=COLOUR[twin], ls=":", lw=1.3,
                           label=f"floor (final excess over noise), {twin}: {fmt(floor, 3)}")
        if series.has(noise_column, optional=False):
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
