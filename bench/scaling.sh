#!/usr/bin/env bash
# The particle solver on MPI: the measured inputs of its scaling model and the model's projection
# (docs/performance.md, "On MPI"). Measures, on this host:
#   - the MPI library's exchange cost between two ranks (bench/mpi/mpi_exchange.c: one
#     MPI_Sendrecv of b bytes each way, the halo's pattern; an MPI_Allreduce of one double);
#   - what a 2-rank particle run sends per step (bench/mpi/mpi_counts.c, a PMPI interposer:
#     calls, bytes and seconds per call kind, from the difference of two run lengths);
#   - particle-steps/s for 1 rank x 1 thread, 1 rank x 2 threads and 2 ranks x 1 thread
#     (twinflow bench, medians of REPS, interleaved);
# then bench/scaling_model.py checks the model against the 1- and 2-rank runs and projects it.
# usage: bench/scaling.sh      env: TWINFLOW (default build/app/twinflow), SIZES (default
#        "48000 384000"), INTEGRATORS (default "shardlow ec-verlet"), REPS (default 3), PS
#        (particle-steps per timed run, default 2e7), OUT (default bench/runs/scaling)
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
TW=${TWINFLOW:-$ROOT/build/app/twinflow}
SIZES=${SIZES:-"48000 384000"}
INTEGRATORS=${INTEGRATORS:-"shardlow ec-verlet"}
REPS=${REPS:-3}
PS=${PS:-2e7}
OUT=${OUT:-$HERE/runs/scaling}
[ -x "$TW" ] || { echo "no twinflow binary at $TW (scripts/build.sh)"; exit 1; }
command -v mpicc >/dev/null || { echo "mpicc not found (Debian: libopenmpi-dev)"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mkdir -p "$OUT"
mpicc -O2 -o "$OUT/mpi_exchange" "$HERE/mpi/mpi_exchange.c"
mpicc -O2 -shared -fPIC -o "$OUT/libmpi_counts.so" "$HERE/mpi/mpi_counts.c"
MPIRUN=(mpirun -np 2 --bind-to none)
RAW=$OUT/raw.txt # one line per measurement: kind key values
: >"$RAW"
. "$HERE/host.sh"
host_lines | tee -a "$RAW"

echo "== exchange cost, 2 ranks"
"${MPIRUN[@]}" "$OUT/mpi_exchange" | sed 's/^/exchange /' | tee -a "$RAW"

bench() { # N integrator threads steps [mpirun prefix...] -> particle-steps/s
  local n=$1 integ=$2 t=$3 s=$4
  shift 4
  OMP_NUM_THREADS=$t "$@" "$TW" bench --force -o "$OUT/twinflow" --threads "$t" \
    --set "Bench/N=$n" --set Bench/Scenes=a0=15+heat --set "Bench/Integrators=$integ" \
    --set "Bench/Threads=$t" --set "Bench/Steps=$s" 2>/dev/null |
    awk -F'|' '/^\| 3 \|/ {gsub(/ /, "", $9); print $9}'
}

echo "== messages per step, 2 ranks x 1 thread"
for n in $SIZES; do
  for integ in $INTEGRATORS; do
    for s in 20 120; do
      OMP_NUM_THREADS=1 "${MPIRUN[@]}" -x LD_PRELOAD="$OUT/libmpi_counts.so" \
        -x MPI_COUNTS_OUT="$OUT/counts_${n}_${integ}_$s" "$TW" bench --force \
        -o "$OUT/twinflow" --threads 1 --set "Bench/N=$n" --set Bench/Scenes=a0=15+heat \
        --set "Bench/Integrators=$integ" --set Bench/Threads=1 --set "Bench/Steps=$s" >/dev/null 2>&1
    done
    for r in 0 1; do # per step: the difference of the two run lengths
      join "$OUT/counts_${n}_${integ}_20.$r" "$OUT/counts_${n}_${integ}_120.$r" |
        awk -v key="$n:$integ:$r" '{printf "counts %s %s %.4g %.6g %.6g\n", key, $1,
          ($5 - $2) / 100, ($6 - $3) / 100, ($7 - $4) / 100}' | tee -a "$RAW"
    done
  done
done

echo "== speed, REPS=$REPS, $PS particle-steps per timed run"
for rep in $(seq 1 "$REPS"); do
  for n in $SIZES; do
    s=$(python3 -c "print(max(10, int(round(float('$PS') / $n))))")
    for integ in $INTEGRATORS; do
      echo "speed $n:$integ:1x1 $(bench "$n" "$integ" 1 "$s")" | tee -a "$RAW"
      echo "speed $n:$integ:1x2 $(bench "$n" "$integ" 2 "$s")" | tee -a "$RAW"
      echo "speed $n:$integ:2x1 $(bench "$n" "$integ" 1 "$s" "${MPIRUN[@]}")" | tee -a "$RAW"
    done
  done
done
python3 "$HERE/scaling_model.py" "$RAW" | tee "$OUT/summary.md"
