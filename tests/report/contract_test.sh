#!/bin/bash
# ctest ReportContract: the report against the keys the C++ writes today. A fresh tiny
# `twinflow run` (tests/report/tiny_run.prm: every stage, in seconds), then the report in strict
# mode, where every key it reads must be there (a renamed key in the C++ fails here, naming the
# file and the key). Also checks that the run's own report call (TWINFLOW_REPORT_SCRIPT) wrote
# a report, and that strict mode does fail on a renamed JSON key and a renamed CSV column.
# Exit 77 (ctest: skipped) when no python3 can import matplotlib and numpy.
set -u
source_dir=${1:?usage: contract_test.sh SOURCE_DIR TWINFLOW_BINARY}
twinflow=${2:?usage: contract_test.sh SOURCE_DIR TWINFLOW_BINARY}
report="$source_dir/compare/report"
source "$source_dir/tests/report/find_python.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MPLCONFIGDIR="$work/.matplotlib" # matplotlib's cache, away from a read-only home
export PYTHONDONTWRITEBYTECODE=1         # no __pycache__ in the source tree
export TWINFLOW_CACHE=off                # every stage computes (no cached transport result)
unset TWINFLOW_REPORT_STRICT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

run="$work/run"
if ! "$twinflow" run "$source_dir/tests/report/tiny_run.prm" --out "$run" --threads 2 \
  >"$work/run.log" 2>&1; then
  cat "$work/run.log"
  echo "FAIL: twinflow run tests/report/tiny_run.prm exited non-zero"
  exit 1
fi
for file in particle/summary.json particle/wall_layers.csv transport/summary.json \
  continuum/summary.json continuum_calibrated/summary.json compare/metrics.json \
  compare/bins.csv compare/profiles.csv compare/error_vs_time.csv; do
  [ -s "$run/$file" ] || fail "the tiny run wrote no $file (a stage did not run)"
done
[ -s "$run/report/report.md" ] ||
  fail "twinflow run's own report call (TWINFLOW_REPORT_SCRIPT) wrote no report/report.md"

# The contract: every key the report reads is there.
if ! "$python" "$report" --strict "$run" >"$work/strict.log" 2>&1; then
  cat "$work/strict.log"
  echo "FAIL: the strict report of a fresh run failed: a key the report reads is missing"
  exit 1 # the checks below start from a run that passes
fi
for file in report.md report.html fields.png profiles.png wall_layers.png error_vs_time.png; do
  [ -s "$run/report/$file" ] || fail "the strict report wrote no $file"
done
for text in "Distances between the twins" "Particle heat flow" "Wall temperature jumps" \
  "fraction explained" "The walls' layers" "The continuum twins' own errors"; do
  grep -qF -- "$text" "$run/report/report.md" || fail "the strict report lacks '$text'"
done

# The test can fail: a renamed key (as a rename in the C++ would leave it) is reported.
# expect_missing WHAT FILE EXPECTED PYTHON-EDIT: after the edit, strict mode exits 3 with EXPECTED.
expect_missing() {
  local what=$1 file=$2 expected=$3 edit=$4
  rm -rf "$work/renamed"
  cp -r "$run" "$work/renamed"
  "$python" -c "$edit" "$work/renamed/$file"
  "$python" "$report" --strict "$work/renamed" >"$work/renamed.out" 2>"$work/renamed.err"
  local status=$?
  [ "$status" -eq 3 ] || fail "$what: strict mode exited $status, expected 3"
  grep -qF -- "$expected" "$work/renamed.err" ||
    fail "$what: expected '$expected' on stderr, got: $(cat "$work/renamed.err")"
}
expect_missing "a renamed JSON key" compare/metrics.json \
  "compare/metrics.json: no key 'particle/nusselt_stderr'" '
import json, sys
metrics = json.load(open(sys.argv[1]))
metrics["particle"]["nusselt_stderr_renamed"] = metrics["particle"].pop("nusselt_stderr")
json.dump(metrics, open(sys.argv[1], "w"))'
expect_missing "a renamed CSV column" compare/profiles.csv \
  "compare/profiles.csv: no column 'T_particle_se'" '
import sys
text = open(sys.argv[1]).read().replace(",T_particle_se,", ",T_particle_stderr,", 1)
open(sys.argv[1], "w").write(text)'

if [ "$failures" -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "report contract: the strict report of a fresh tiny run passed"
