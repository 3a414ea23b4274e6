#!/bin/bash
# ctest StudyReport: the report (python3 compare/report DIR) on the fixtures of
# tests/study/fixtures (copied to a temporary directory): every expected figure and
# report.md/html is written and non-empty, a second report replaces the first, missing columns
# are tolerated, and a directory that is no run, sweep or stability directory exits 2. Exit 77
# (ctest: skipped) when no python3 can import matplotlib and numpy.
set -u
source_dir=${1:?usage: report_test.sh SOURCE_DIR}
report="$source_dir/compare/report"

source "$source_dir/tests/report/find_python.sh"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export MPLCONFIGDIR="$work/.matplotlib" # matplotlib's cache, away from a read-only home
cp -r "$source_dir/tests/study/fixtures/." "$work/"
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect_report DIR FILE...: the report of DIR exits 0 and writes report.md, report.html and FILEs.
expect_report() {
  local dir=$1
  shift
  if ! "$python" "$report" "$work/$dir" >"$work/$dir.log" 2>&1; then
    fail "the report of $dir exited non-zero:"
    cat "$work/$dir.log"
    return
  fi
  local file
  for file in report.md report.html "$@"; do
    [ -s "$work/$dir/report/$file" ] || fail "$dir/report/$file missing or empty"
  done
  for file in "$@"; do
    case $file in
      *.png)
        [ "$(head -c 4 "$work/$dir/report/$file" | tail -c 3)" = "PNG" ] ||
          fail "$dir/report/$file is not a PNG"
        grep -q "($file)" "$work/$dir/report/report.md" || fail "$dir: report.md does not show $file"
        grep -q "src=\"$file\"" "$work/$dir/report/report.html" ||
          fail "$dir: report.html does not show $file"
        ;;
    esac
  done
  if ls -A "$work/$dir" | grep -q '^\.report-'; then
    fail "$dir: a temporary report folder was left behind"
  fi
}

# expect_text DIR TEXT: report.md of DIR contains TEXT.
expect_text() {
  grep -qF -- "$2" "$work/$1/report/report.md" || fail "$1/report/report.md lacks '$2'"
}

run_figures="fields.png profiles.png error_vs_time.png"
expect_report run_2d $run_figures
expect_text run_2d "excluded thickness 2 rc"
expect_text run_2d "not within noise"
expect_report run_2d_calibrated $run_figures
expect_text run_2d_calibrated "fraction explained"
expect_text run_2d_calibrated "x_lower"
expect_report run_3d $run_figures
expect_text run_3d "the bin layer at y = 3 rc"
expect_report sweep_rayleigh nusselt_vs_rayleigh.png errors_vs_rayleigh.png cost.png
expect_text sweep_rayleigh "de Vahl Davis"
expect_text sweep_rayleigh "the particle run went unstable at step 812"
expect_report sweep_two_keys nusselt_vs_particle_time_step.png \
  errors_vs_particle_time_step.png cost.png pareto.png
expect_text sweep_two_keys "Pareto front (no other point"
expect_report sweep_seeds nusselt_vs_particle_seed.png cost.png
expect_text sweep_seeds "Over 4 realisations: particle / twin - 1 = 3.7 % ± 0.8 %"
expect_report stability_two_keys stability_map.png
expect_text stability_two_keys "negative_internal_energy"
expect_report stability_time_step stability_map.png

# A second report replaces the first.
touch "$work/run_2d/report/stale.txt"
expect_report run_2d $run_figures
[ -e "$work/run_2d/report/stale.txt" ] && fail "run_2d: the old report was not replaced"

# Missing keys and columns: a heat-conduction-like run (no velocity, no calibrated twin) and a
# sweep table with only the fixed columns.
mkdir -p "$work/run_no_velocity"
cp -r "$work/run_2d/compare" "$work/run_2d/particle" "$work/run_no_velocity/"
"$python" - "$work/run_no_velocity/compare" <<'EOF'
import csv, json, os, sys
folder = sys.argv[1]
metrics = json.load(open(os.path.join(folder, "metrics.json")))
for twin in metrics["twins"].values():
    twin.pop("velocity", None)
metrics.pop("table_row", None)
json.dump(metrics, open(os.path.join(folder, "metrics.json"), "w"))
for name in ("bins.csv", "profiles.csv", "error_vs_time.csv"):
    lines = open(os.path.join(folder, name)).read().splitlines()
    rows = list(csv.reader(lines[1:]))
    keep = [i for i, column in enumerate(rows[0]) if not column.startswith(("v", "velocity"))]
    with open(os.path.join(folder, name), "w", newline="") as f:
        f.write(lines[0] + "\n")
        csv.writer(f).writerows([[row[i] for i in keep] for row in rows])
EOF
expect_report run_no_velocity $run_figures
mkdir -p "$work/sweep_few_columns"
printf 'point,status,reason,exit_code,Particle/Time step,wall_seconds\n000,done,,0,0.01,12\n001,failed,"a reason, with a comma",4,0.02,3\n' \
  >"$work/sweep_few_columns/sweep.csv"
echo '{"command": "sweep"}' >"$work/sweep_few_columns/sweep.json"
expect_report sweep_few_columns cost.png

# Not a result directory: exit 2, one line on stderr, nothing written.
mkdir -p "$work/not_a_result"
"$python" "$report" "$work/not_a_result" >"$work/bad.out" 2>"$work/bad.err"
status=$?
[ "$status" -eq 2 ] || fail "a bad directory exited $status, expected 2"
[ "$(wc -l <"$work/bad.err")" -eq 1 ] || fail "a bad directory printed more than one line"
[ -z "$(ls -A "$work/not_a_result")" ] || fail "a bad directory got files written into it"
"$python" "$report" "$work/does_not_exist" >/dev/null 2>&1
status=$?
[ "$status" -eq 2 ] || fail "a missing directory exited $status, expected 2"

if [ "$failures" -gt 0 ]; then
  echo "$failures check(s) failed"
  exit 1
fi
echo "report: all checks passed"
