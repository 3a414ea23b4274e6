"""Figures (PNG) and a report (report.md, report.html) for a twinflow result directory.

    python3 compare/report [--strict] DIR      (the folder as a script, as twinflow runs it;
                                                 compare/report/__main__.py works too)
    python3 -m compare.report [--strict] DIR   (from the source directory)

DIR is one of
  a run        (DIR/compare/metrics.json)           -> DIR/report/
  a sweep      (DIR/sweep.csv + DIR/sweep.json)     -> DIR/report/
  a stability  (DIR/stability.csv + .json)          -> DIR/report/

--strict (or TWINFLOW_REPORT_STRICT=1): every key the report reads from the C++ stages' files
must be there, except those the report declares optional; a missing one is an error (exit 3,
naming the file and the key) instead of a blank table cell. The contract test (ctest
ReportContract) runs it on a fresh run.

Exit codes: 0 written, 2 DIR is none of the above (one line on stderr), 3 strict mode found a
key missing (one line on stderr, nothing written).
"""

import importlib
import os
import shutil
import sys
import tempfile

if not __package__:
    # Run as a file or folder (python3 compare/report DIR): import the package by its name, with
    # compare/ in place of compare/report/ on the path so no module is imported twice (PEP 366).
    sys.path[0] = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    importlib.import_module("report")  # the parent package of the relative imports below
    __package__ = "report"

from . import data  # noqa: E402
from .run import report_run  # noqa: E402
from .stability import report_stability  # noqa: E402
from .sweep import report_sweep  # noqa: E402

EXIT_BAD_INPUT = 2
EXIT_MISSING_KEY = 3
USAGE = "usage: python3 compare/report [--strict] DIR (a run, sweep or stability directory)"


def fail(message, code=EXIT_BAD_INPUT):
    print(f"report: {message}", file=sys.stderr)
    sys.exit(code)


def kind_of(directory):
    if os.path.isfile(os.path.join(directory, "compare", "metrics.json")):
        return "run"
    if all(os.path.isfile(os.path.join(directory, f)) for f in ("sweep.csv", "sweep.json")):
        return "sweep"
    if all(os.path.isfile(os.path.join(directory, f)) for f in ("stability.csv", "stability.json")):
        return "stability"
    return None


def write_report(kind, directory):
    """The report of directory in directory/report; the path."""
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
    return final


def main(argv):
    arguments = argv[1:]
    strict = os.environ.get("TWINFLOW_REPORT_STRICT", "") not in ("", "0")
    if arguments and arguments[0] == "--strict":
        strict, arguments = True, arguments[1:]
    if len(arguments) != 1 or arguments[0] in ("-h", "--help"):
        fail(USAGE)
    directory = arguments[0]
    kind = kind_of(directory)
    if kind is None:
        fail(f"{directory}: not a run (compare/metrics.json), sweep (sweep.csv, sweep.json) or "
             "stability (stability.csv, stability.json) directory")
    try:
        import matplotlib
        matplotlib.use("Agg")
    except ImportError:
        fail("matplotlib is missing (Debian: apt-get install python3-matplotlib)")
    data.STRICT = strict
    try:
        final = write_report(kind, directory)
    except data.MissingKey as missing:
        fail(f"strict: {missing}", EXIT_MISSING_KEY)
    written = sorted(os.listdir(final))
    print(f"report: {kind} report in {final}: {', '.join(written)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
