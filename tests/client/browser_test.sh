#!/bin/bash
# ctest -L client: the report in a real browser. A quick run and a two-point sweep (tiny, the
# default cavity shrunk), then headless Chromium opens both reports (tests/client/browser_test.py:
# images decode, links and anchors resolve, no console errors, the verdict first). Exit 77
# (skipped) without Chromium; TWINFLOW_CLIENT_PNG=FILE keeps a screenshot of the run's report.
#   browser_test.sh SOURCE_DIR TWINFLOW_BINARY
set -u
source_dir=${1:?usage: browser_test.sh SOURCE_DIR TWINFLOW_BINARY}
twinflow=${2:?usage: browser_test.sh SOURCE_DIR TWINFLOW_BINARY}
for tool in chromium chromedriver; do
  command -v $tool >/dev/null 2>&1 || {
    echo "skipped: no $tool (Debian: apt-get install chromium chromium-driver python3-selenium)"
    exit 77
  }
done
/usr/bin/python3 -c 'import selenium' 2>/dev/null || {
  echo "skipped: no python3-selenium (Debian: apt-get install python3-selenium)"
  exit 77
}
source "$(dirname "$0")/tiny_case.sh"
tiny+=(--set 'Transport/Measure kappa and eta=false')
"$twinflow" run "$case" "${tiny[@]}" --out "$work/run" >"$work/run.log" 2>&1 ||
  { cat "$work/run.log"; echo "FAIL: twinflow run"; exit 1; }
"$twinflow" sweep "$case" "${tiny[@]}" --vary 'Particle/Seed=1,2' --jobs 1 \
  --out "$work/sweep" >"$work/sweep.log" 2>&1 ||
  { cat "$work/sweep.log"; echo "FAIL: twinflow sweep"; exit 1; }
exec /usr/bin/python3 "$source_dir/tests/client/browser_test.py" "$work/run/report/report.html" \
  "$work/sweep/report/report.html"
