#!/bin/bash
# ctest -L client: a real client opens the field files. A quick particle run and its continuum
# twin, then ParaView's pvbatch (Debian paraview + python3-paraview, rendering under xvfb-run)
# opens particle/fields.xdmf and continuum/fields.xdmf, lists their time steps and arrays,
# checks them and renders the particle temperature to a PNG (kept in $TWINFLOW_CLIENT_PNG when
# set, to look at). Exit 77 (ctest: skipped) without pvbatch or xvfb-run.
#   paraview_test.sh SOURCE_DIR TWINFLOW_BINARY
set -u
source_dir=${1:?usage: paraview_test.sh SOURCE_DIR TWINFLOW_BINARY}
twinflow=${2:?usage: paraview_test.sh SOURCE_DIR TWINFLOW_BINARY}
for tool in pvbatch xvfb-run; do
  command -v $tool >/dev/null 2>&1 || {
    echo "skipped: no $tool (Debian: apt-get install paraview python3-paraview xvfb xauth)"
    exit 77
  }
done
source "$(dirname "$0")/tiny_case.sh"
tiny+=(--set 'Transport/Source=estimated')
for stage in particle continuum; do
  "$twinflow" $stage "$case" "${tiny[@]}" --out "$work/run" >"$work/$stage.log" 2>&1 ||
    { cat "$work/$stage.log"; echo "FAIL: twinflow $stage"; exit 1; }
done
png="${TWINFLOW_CLIENT_PNG:-$work/particle_temperature.png}"
timeout 300 xvfb-run -a pvbatch "$source_dir/tests/client/paraview_fields.py" \
  "$work/run/particle/fields.xdmf" "$work/run/continuum/fields.xdmf" "$png" >"$work/pv.log" 2>&1
code=$?
grep -v '^ *[0-9]* *0x' "$work/pv.log" | grep -E "^/|FAIL|paraview:|Error" | cut -c1-400
exit $code
