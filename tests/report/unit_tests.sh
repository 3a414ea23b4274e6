#!/bin/bash
# ctest ReportUnit: the Python unittest tests of the report's pieces (tests/report/test_*.py:
# formatting, lookups and strict mode, the Document, Axis, verdict sentences, the command line).
# Exit 77 (ctest: skipped) when no python3 can import matplotlib and numpy.
set -u
source_dir=${1:?usage: unit_tests.sh SOURCE_DIR}
source "$source_dir/tests/report/find_python.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MPLCONFIGDIR="$work/.matplotlib" # matplotlib's cache, away from a read-only home
export PYTHONDONTWRITEBYTECODE=1         # no __pycache__ in the source tree
"$python" -m unittest discover -s "$source_dir/tests/report" -p 'test_*.py'
