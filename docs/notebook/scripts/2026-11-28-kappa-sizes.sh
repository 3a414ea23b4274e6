#!/bin/bash
# kappa from the transport stage's periodic heat slabs at several scene sizes (period 2L)
B=/work/main/build/app/twinflow
C=/work/main/cases/heated_cavity_2d.prm
for spec in "$@"; do
  L=${spec%:*}; s=${spec#*:}
  out=/work/runs/s21/kbox/L${L}_s${s}
  [ -f $out/transport/summary.json ] && continue
  TWINFLOW_CACHE=off $B transport $C --out $out --seed $s --threads 2 --force \
    --set Transport/Temperature=0.887 --set "Scene/Box size=$L, $L" \
    --set 'Transport/Flow particles=100' --set 'Transport/Flow repeats=1' \
    --set 'Transport/Viscosity along the isobar=false' > $out.log 2>&1
  echo "L=$L seed=$s rc=$? $(date +%T)"
done
