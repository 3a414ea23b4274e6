"""Reading the C++ stages' files (JSON, CSV), the one lookup helper, and number formatting.

Every read of a key the C++ writes goes through lookup() (number(), Table.numbers() and the
rows of a Table call it). In strict mode (python3 compare/report --strict DIR, or
TWINFLOW_REPORT_STRICT=1) a key that is absent raises MissingKey naming the file and the key,
unless the call site declares it optional (a key the C++ leaves out on purpose, e.g. the
calibrated twin of a periodic scene). Without strict mode an absent key reads as None (a
number as NaN) and the report leaves that cell or section out, as it always did.
"""

import csv
import json
import math
import os
import re

UNITS_NOTE = "particle units: lengths in rc, times in tau, temperatures in T0 (energies in k T0)"
AXES = "xyz"
TWINS = ("nominal", "calibrated")
TWIN_LABEL = {"nominal": "nominal twin", "calibrated": "calibrated twin"}

# Set by the command line (__main__.py); tests switch it with strict_mode().
STRICT = False


class strict_mode:
    """with strict_mode(): ... -- lookups inside are strict (the previous mode is restored)."""

    def __init__(self, on=True):
        self.on = on

    def __enter__(self):
        global STRICT
        self.previous, STRICT = STRICT, self.on

    def __exit__(self, *exc):
        global STRICT
        STRICT = self.previous


class MissingKey(Exception):
    """Strict mode: a key (or file) the report reads is absent from the C++ outputs."""

    def __init__(self, source, path, noun="key"):
        self.source, self.path, self.noun = source, tuple(path), noun
        where = "/".join(str(k) for k in self.path)
        super().__init__(f"{source or '(data not read from a file)'}: no {noun} '{where}'")


class Record(dict):
    """A JSON object or a CSV row that remembers its file and its place in it, so that strict
    mode's message can name both."""

    def __init__(self, items, source=None, where=(), noun="key"):
        super().__init__(items)
        self.source, self.where, self.noun = source, tuple(where), noun


def _attach(value, source, where=()):
    """The parsed JSON with every object a Record of source and its path."""
    if isinstance(value, dict):
        return Record({k: _attach(v, source, where + (k,)) for k, v in value.items()}, source,
                      where)
    if isinstance(value, list):
        return [_attach(v, source, where + (i,)) for i, v in enumerate(value)]
    return value


def _walk(data, path):
    """(where the walk stopped, how many steps of path it took)."""
    at = data
    for n, key in enumerate(path):
        if isinstance(at, dict) and key in at:
            at = at[key]
        elif isinstance(at, list) and isinstance(key, int) and -len(at) <= key < len(at):
            at = at[key]
        else:
            return at, n
    return at, len(path)


def lookup(data, *path, optional=False):
    """data[path[0]][path[1]]..., or None when any step is missing.

    Strict mode: a missing step raises MissingKey unless optional. None as data (an optional
    file or key that is absent, or a JSON null) gives None without complaint: its absence was
    judged where it was read."""
    at, steps = _walk(data, path)
    if steps == len(path):
        return at
    if STRICT and not optional and at is not None:
        raise MissingKey(getattr(data, "source", None),
                         getattr(data, "where", ()) + path[:steps + 1],
                         getattr(data, "noun", "key"))
    return None


def present(data, *path):
    """Whether the key is there (a JSON null counts): the test before reading an optional key
    whose absence changes what the report says. Never strict."""
    return _walk(data, path)[1] == len(path)


def number(data, *path, optional=False):
    """A finite float at path, else NaN (C++ writes non-finite numbers as null)."""
    value = lookup(data, *path, optional=optional)
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


def read_json(path, optional=False):
    """The parsed file (objects as Records), or None when it is absent (the stage did not run).
    Strict mode: an absent file that is not optional raises MissingKey."""
    try:
        with open(path, encoding="utf-8") as f:
            return _attach(json.load(f), path)
    except FileNotFoundError:
        if STRICT and not optional:
            raise MissingKey(path, (), "file") from None
        return None


class Table:
    """A CSV file with optional leading '#' comment lines, then a header, then rows (Records:
    reading a cell goes through lookup)."""

    def __init__(self, path):
        self.path = path
        self.comments = []
        with open(path, newline="", encoding="utf-8") as f:
            lines = f.read().splitlines()
        while lines and lines[0].startswith("#"):
            self.comments.append(lines.pop(0).lstrip("# ").rstrip())
        reader = csv.reader(lines)
        self.header = next(reader, [])
        self.rows = [Record(zip(self.header, cells), path, noun="column") for cells in reader
                     if cells]
        self.columns = Record({c: c for c in self.header}, path, noun="column")

    def has(self, column, optional=True):
        """Whether the column is there: the test before reading it. optional=False for a column
        the C++ always writes (strict mode: its absence raises MissingKey)."""
        return lookup(self.columns, column, optional=optional) is not None

    def numbers(self, column, rows=None, optional=False):
        import numpy as np
        rows = self.rows if rows is None else rows
        return np.array([to_float(lookup(r, column, optional=optional)) for r in rows],
                        dtype=float)


def read_table(path, optional=False):
    if os.path.isfile(path):
        return Table(path)
    if STRICT and not optional:
        raise MissingKey(path, (), "file")
    return None


def cell(row, column, optional=False):
    """A CSV cell's text, "" when the column is absent (as csv.DictReader's restval)."""
    value = lookup(row, column, optional=optional)
    return "" if value is None else value


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


def plain(text):
    """A key for a table cell or label: the CSV text as is, else a dash."""
    return text if text not in (None, "") else "–"


def slug(text):
    return re.sub(r"[^a-z0-9]+", "_", text.lower()).strip("_") or "value"


# Units of the keys a sweep or stability map commonly varies (the rest are shown as is).
KEY_UNITS = {"Particle/Time step": "tau", "Scene/Density": "rc^-d", "Scene/Temperature": "T0",
             "Particle/Internal energy/Heat capacity": "k",
             "Particle/Conservative force/a0": "k T0 / rc"}


def with_unit(key):
    return f"{key} [{KEY_UNITS[key]}]" if key in KEY_UNITS else key


# ---------------------------------------------------------------------------------------------
# Sweep and stability directories: the grid's description

def varied_keys(table, stop_columns):
    """The columns between exit_code and the first of the command's own columns."""
    header = table.header
    if not table.has("exit_code", optional=False):
        return []
    keys = []
    for column in header[header.index("exit_code") + 1:]:
        if column in stop_columns:
            break
        keys.append(column)
    return keys


def study_case_name(grid, directory):
    """The case's name, else its file's name, else the directory's."""
    name = lookup(grid, "base_parameters", "Case name")
    if name:
        return name
    case_file = lookup(grid, "case_file")
    if case_file:
        return re.sub(r"\.prm$", "", os.path.basename(case_file))
    return os.path.basename(os.path.abspath(directory))
