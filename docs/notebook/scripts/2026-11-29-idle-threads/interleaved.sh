#!/bin/bash
# Interleaved, N = 48000: LAMMPS on 2 ranks, then ours on 2 threads under each spin count; 6
# repeats. From the repository's root; OUT (default /tmp/wait) holds the logs.
set -e
ROOT=$(pwd)
mkdir -p "${OUT:-/tmp/wait}"
source <(sed -n '/^edge()/,/^steps_for/p' bench/vs_lammps.sh)
HERE=$ROOT/bench; LMP=/opt/lammps-dpd/build/lmp_dpd; OUT=${OUT:-/tmp/wait}; TW=$ROOT/build/app/twinflow
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
source <(sed -n '/^lammps()/,/^}/p' bench/vs_lammps.sh)
N=48000; S=100
for rep in 1 2 3 4 5 6; do
  echo "lammps2 $(lammps $N 2 $S)"
  for pol in GOMP_SPINCOUNT=1000 GOMP_SPINCOUNT=3000; do
    env $pol $TW bench --force -o $OUT/tw --set Bench/N=$N --set Bench/Scenes=a0=15+heat --set Bench/Integrators=shardlow,ec-verlet --set Bench/Threads=2 --set Bench/Steps=$S | awk -F'|' -v p=$pol '/^\| 3 \|/ {gsub(/ /,"",$5); gsub(/ /,"",$9); print p, $5, $9}'
  done
done
