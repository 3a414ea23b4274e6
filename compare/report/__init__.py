"""twinflow's report: figures (PNG) and report.md/report.html for a run, sweep or stability
directory, read from the C++ stages' files. Only Debian's python3, python3-numpy and
python3-matplotlib.

    data.py       reading JSON/CSV, the one lookup helper (strict mode), number formatting
    document.py   the Document: one list of blocks as Markdown and as HTML
    figures.py    plotting helpers shared by the reports (colours, Axis, log ticks)
    run.py        the report of a run
    sweep.py      the report of a sweep
    stability.py  the report of a stability map
    __main__.py   the command line: python3 compare/report [--strict] DIR

Every number shown is read from the C++ stages' files; the report only reads, arranges and
plots them (the one derived number is the run report's "fraction explained",
1 - gap_cal / gap_nom).
"""
