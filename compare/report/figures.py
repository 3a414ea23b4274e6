"""Plotting helpers shared by the run, sweep and stability reports (matplotlib is imported
inside the functions: the package imports without it, and __main__ selects the Agg backend
first)."""

import math
import os

from .data import finite, to_float

DPI = 150
# One colour per data source, the same in every figure.
COLOUR = {"particle": "#1f4e9c", "nominal": "#d9541e", "calibrated": "#2a9d4b",
          "noise": "0.35", "benchmark": "black"}
LINESTYLE = {"nominal": "-", "calibrated": "--"}


def save_figure(fig, out_dir, file_name):
    from .document import write_atomically
    import matplotlib.pyplot as plt
    try:
        write_atomically(os.path.join(out_dir, file_name),
                         lambda tmp: fig.savefig(tmp, dpi=DPI, format="png"))
    finally:
        plt.close(fig)
    return file_name


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
