#!/usr/bin/env bash
# Our DPDE particle solver against LAMMPS DPD-REACT (pair dpd/fdt/energy + fix shardlow + fix nve
# + fix eos/cv) on the same system, in the same run, interleaved (the machine is shared: medians
# of REPS repeats). System: 3D periodic, rho = 3, rc = 1, a0 = 15, sigma = 3, c_v = 200,
# kappa = 40 (inverse heat law, constant kappa), w_C = w_R = 1 - r, w_D = w_H = (1 - r)^2,
# dt = 0.005, box 2L x L x L with N = 6 L^3.
#
# usage: bench/vs_lammps.sh [perf] [scenes] [thermo]      (default: all three)
#   perf    particle-steps/s at SIZES: ours (shardlow, ec-verlet; 1 and 2 OpenMP threads, and 2
#           MPI ranks x 1 thread) and LAMMPS (1 and 2 MPI ranks), ratios to LAMMPS's best, the
#           cost exponent in N,
#           two-thread efficiency, memory per particle (peak RSS difference between sizes)
#   scenes  ours only, N = 48000: ideal, ideal+heat, a0=15, a0=15+heat
#   thermo  N = 6000, 10 tau equilibration + 10 tau sampled: energy drift, T_kinetic,
#           T_internal (harmonic mean of theta), pressure, ours beside LAMMPS
# env: TWINFLOW (default build/app/twinflow), LMP (default /opt/lammps-dpd/build/lmp_dpd, built by
#      as docs/performance.md "Building the LAMMPS peer" says; this script builds nothing), SIZES (default
#      "6000 48000 384000"), REPS (default 3), PS (particle-steps per timed run, default 6e6),
#      OUT (default bench/runs), OMP_WAIT_POLICY / GOMP_SPINCOUNT (default: twinflow's, see
#      below), NOISES (ours' pair noises, default "gaussian uniform": Particle/Noise; LAMMPS
#      draws Gaussians), RANKS (default 1: ours on 2 MPI ranks too; 0: not)
set -euo pipefail
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/.." && pwd)
TW=${TWINFLOW:-$ROOT/build/app/twinflow}
LMP=${LMP:-/opt/lammps-dpd/build/lmp_dpd}
SIZES=${SIZES:-"6000 48000 384000"}
REPS=${REPS:-3}
PS=${PS:-6e6}
NOISES=${NOISES:-"gaussian uniform"}
RANKS=${RANKS:-1} # 1: perf also runs ours on 2 MPI ranks x 1 thread (Gaussian noise); 0: not
OUT=${OUT:-$HERE/runs}
MODES=("$@")
[ ${#MODES[@]} -eq 0 ] && MODES=(perf scenes thermo)
mkdir -p "$OUT"
[ -x "$TW" ] || { echo "no twinflow binary at $TW (scripts/build.sh)"; exit 1; }
HAVE_LMP=1
if [ ! -x "$LMP" ]; then
  HAVE_LMP=0
  echo "LAMMPS: not installed at $LMP -- LAMMPS columns skipped (build it with"
  echo "        as docs/performance.md, \"Building the LAMMPS peer\", says, or set LMP)"
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Ours runs with twinflow's own default of how idle threads wait (a short spin, then sleep:
# GOMP_SPINCOUNT=1000, app/main.cpp), as a user gets it; OMP_WAIT_POLICY=passive or active, or
# GOMP_SPINCOUNT, in the environment measure another choice.
RAW=$OUT/raw.txt # one line per measurement: kind key values
: >"$RAW"
. "$HERE/host.sh"
host_lines | tee -a "$RAW"

edge() { python3 -c "print('%.10g' % round(($1 / 6.0) ** (1 / 3.0), 9))"; }
steps_for() { python3 -c "print(max(20, int(round(float('$PS') / $1))))"; }

ours() { # N scene integrator threads steps noise -> "particle-steps/s peak-RSS-kB"
  "$TW" bench --force -o "$OUT/twinflow" --set "Bench/N=$1" --set "Bench/Scenes=$2" \
    --set "Bench/Integrators=$3" --set "Bench/Threads=$4" --set "Bench/Steps=$5" \
    --set "Bench/Noise=${6:-gaussian}" |
    awk -F'|' '/^\| 3 \|/ {gsub(/ /, "", $9); gsub(/ /, "", $11); print $9, $11}'
}
label() { [ "$2" = gaussian ] && echo "$1" || echo "$1+$2"; } # integrator noise -> key

ours_ranks() { # N integrator steps -> "particle-steps/s peak-RSS-kB" on 2 MPI ranks x 1 thread
  OMP_NUM_THREADS=1 mpirun -np 2 --bind-to none "$TW" bench --force -o "$OUT/twinflow" \
    --threads 1 --set "Bench/N=$1" --set Bench/Scenes=a0=15+heat --set "Bench/Integrators=$2" \
    --set Bench/Threads=1 --set "Bench/Steps=$3" |
    awk -F'|' '/^\| 3 \|/ {gsub(/ /, "", $9); gsub(/ /, "", $11); print $9, $11}'
}

lammps() { # N ranks steps -> "particle-steps/s peak-RSS-kB"
  local n=$1 ranks=$2 steps=$3 l log
  l=$(edge "$n")
  log=$OUT/lammps_${n}_${ranks}.log
  local args=(-in "$HERE/in.dpde_bench.lmp" -log "$log" -screen none -var Lx "$(python3 -c "print(2*$l)")"
    -var Ly "$l" -var Lz "$l" -var nsteps "$steps" -var neq 20 -var every "$steps")
  if [ "$ranks" = 1 ]; then
    OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "$OUT/rss" "$LMP" "${args[@]}" >/dev/null
  else
    OMP_NUM_THREADS=1 /usr/bin/time -f "%M" -o "$OUT/rss" mpirun --oversubscribe -np "$ranks" \
      "$LMP" "${args[@]}" >/dev/null
  fi
  # "Loop time of T on P procs for S steps with N atoms" of the measured (last) run
  grep "^Loop time of" "$log" | tail -1 |
    awk -v rss="$(tail -1 "$OUT/rss")" '{printf "%.6g %s\n", $12 * $9 / $4, rss}'
}

do_perf() {
  echo "== perf: a0=15+heat, REPS=$REPS, $PS particle-steps per timed run (set-up excluded)"
  for rep in $(seq 1 "$REPS"); do
    for n in $SIZES; do
      s=$(steps_for "$n")
      for integ in shardlow ec-verlet; do
        for noise in $NOISES; do
          for t in 1 2; do
            read -r ps rss <<<"$(ours "$n" a0=15+heat "$integ" "$t" "$s" "$noise")"
            echo "perf ours:$(label "$integ" "$noise"):$t:$n $ps $rss" | tee -a "$RAW"
          done
        done
        if [ "$RANKS" = 1 ]; then # 2 MPI ranks x 1 thread, beside LAMMPS's 2 ranks
          read -r ps rss <<<"$(ours_ranks "$n" "$integ" "$s")"
          echo "perf ours-2ranks:$integ:1:$n $ps $rss" | tee -a "$RAW"
        fi
      done
      if [ $HAVE_LMP = 1 ]; then
        for r in 1 2; do
          read -r ps rss <<<"$(lammps "$n" "$r" "$s")"
          echo "perf lammps:shardlow:$r:$n $ps $rss" | tee -a "$RAW"
        done
      fi
    done
  done
}

do_scenes() {
  echo "== scenes: ours, N = 48000, REPS=$REPS"
  s=$(steps_for 48000)
  for rep in $(seq 1 "$REPS"); do
    for scene in ideal ideal+heat a0=15 a0=15+heat; do
      for integ in shardlow ec-verlet; do
        for t in 1 2; do
          read -r ps rss <<<"$(ours 48000 "$scene" "$integ" "$t" "$s")"
          echo "scene $scene:$integ:$t $ps $rss" | tee -a "$RAW"
        done
      done
    done
  done
}

do_thermo() {
  echo "== thermo: N = 6000, 2000 steps equilibration + 2000 sampled, 2 threads / 1 rank"
  for integ in shardlow ec-verlet; do
    for noise in $NOISES; do
      "$TW" bench --force -o "$OUT/twinflow" --threads 2 --set Bench/N=6000 \
        --set Bench/Scenes=a0=15+heat --set "Bench/Integrators=$integ" --set Bench/Threads=2 \
        --set "Bench/Noise=$noise" --set Bench/Thermo=2000 |
        awk -F'|' -v i="$(label "$integ" "$noise")" '/^\| 3 \|/ {
          print "thermo ours:" i " |" $10 "|" $11 "|" $12 "|" $13}' | tee -a "$RAW"
    done
  done
  if [ $HAVE_LMP = 1 ]; then
    log=$OUT/lammps_thermo.log
    OMP_NUM_THREADS=1 "$LMP" -in "$HERE/in.dpde_bench.lmp" -log "$log" -screen none \
      -var neq 2000 -var nsteps 2000 -var every 10 >/dev/null
    python3 - "$log" <<'EOF' | tee -a "$RAW"
import statistics as st, sys
runs, cur, cols = [], None, None
for line in open(sys.argv[1]):
    w = line.split()
    if w[:2] == ["Step", "v_tau"]:
        cols, cur = w, []
        runs.append(cur)
    elif cur is not None and w and w[0].isdigit() and len(w) == len(cols):
        cur.append([float(x) for x in w])
    elif w[:1] == ["Loop"]:
        cur = None
rows = runs[0] + runs[1]
e0 = rows[0][cols.index("v_Etot")]
drift = max(abs(r[cols.index("v_Etot")] - e0) / abs(e0) for r in rows)
def mean_se(key, data=runs[1], blocks=10):
    x = [r[cols.index(key)] for r in data]
    per = len(x) // blocks
    b = [st.mean(x[k * per:(k + 1) * per]) for k in range(blocks)]
    return "%.5f +- %.5f" % (st.mean(x), st.stdev(b) / blocks ** 0.5)
print("thermo lammps:shardlow | %.2e | %s | %s | %s" % (
    drift, mean_se("Temp"), mean_se("c_dpdU[4]"), mean_se("Press")))
EOF
  fi
}

for m in "${MODES[@]}"; do
  case $m in
  perf) do_perf ;;
  scenes) do_scenes ;;
  thermo) do_thermo ;;
  *) echo "unknown mode $m (perf, scenes, thermo)"; exit 2 ;;
  esac
done
python3 "$HERE/summarise.py" "$RAW" | tee "$OUT/summary.md"
