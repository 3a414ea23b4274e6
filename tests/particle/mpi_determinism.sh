#!/usr/bin/env bash
# The particle solver on MPI gives the one-process answer, bit for bit (particle/decomposition.hpp):
# thermo.csv and fields.csv are byte-identical for (ranks, threads) = (1, 1), (1, 2), (2, 1) on
# a shrunken default cavity (2D, walls), the periodic slab (3D, heat slabs), a 3D walled cavity
# and the repulsive column (2D, a pair force, gravity, walls), for each integrator; and a run
# checkpointed on 2 ranks continues on 1 (and the other way) to the uninterrupted run's files.
#
# usage: mpi_determinism.sh TWINFLOW SOURCE_DIR WORK_DIR MPIRUN [restart]
set -u
twinflow=$1 source_dir=$2 work=$3 mpirun=$4 part=${5:-determinism}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
rm -rf "$work" && mkdir -p "$work"
failures=0

# A scene: its case file and the --set options that shrink it to a few seconds.
cavity_2d=("$source_dir/cases/heated_cavity_2d.prm" --set "Scene/Box size=12, 12"
           --set "Scene/Field bins=4, 4" --set "Particle/Equilibration steps=20"
           --set "Particle/Steps=100")
slab_3d=("$source_dir/cases/slab_conduction_periodic.prm" --set "Scene/Box size=8, 4, 8"
         --set "Scene/Field bins=8, 1, 1" --set "Scene/Heat slabs/Hot slab=4, 4.5"
         --set "Scene/Heat slabs/Cold slab=0, 0.5" --set "Scene/Heat slabs/Power=20"
         --set "Particle/Equilibration steps=20" --set "Particle/Steps=100")
# The column: a pair force, gravity and walls (shardlow's offset pooled over the ranks).
column_2d=("$source_dir/cases/conduction_column_repulsive_2d.prm" --set "Scene/Box size=8, 12"
           --set "Scene/Field bins=1, 4" --set "Particle/Equilibration steps=20"
           --set "Particle/Steps=100")
cavity_3d=("$source_dir/cases/heated_cavity_3d.prm" --set "Scene/Box size=6, 4, 8"
           --set "Scene/Field bins=2, 1, 2" --set "Particle/Equilibration steps=20"
           --set "Particle/Steps=100")

# run NAME RANKS THREADS SCENE... : one particle run into $work/NAME (1 rank: no launcher).
run() {
  local name=$1 ranks=$2 threads=$3
  shift 3
  local launcher=()
  [ "$ranks" -gt 1 ] && launcher=("$mpirun" -np "$ranks" --bind-to none)
  OMP_NUM_THREADS=$threads "${launcher[@]}" "$twinflow" particle "$@" --threads "$threads" \
    --out "$work/$name" --force >"$work/$name.log" 2>&1
}

same() { # same A B: thermo.csv and fields.csv of two runs byte for byte
  local ok=0
  for f in thermo.csv fields.csv; do
    if ! cmp -s "$work/$1/particle/$f" "$work/$2/particle/$f"; then
      echo "FAIL: $f of $2 differs from $1"
      diff <(head -c 2000 "$work/$1/particle/$f") <(head -c 2000 "$work/$2/particle/$f") | head -5
      ok=1
    fi
  done
  [ -s "$work/$1/particle/thermo.csv" ] || { echo "FAIL: $1 wrote no thermo.csv"; ok=1; }
  return $ok
}

if [ "$part" = determinism ]; then
  for scene in cavity_2d slab_3d cavity_3d column_2d; do
    declare -n args=$scene
    for integrator in shardlow ec-verlet euler; do
      set_integrator=(--set "Particle/Integrator=$integrator")
      base=${scene}_${integrator}
      for config in "1 1" "1 2" "2 1"; do
        read -r ranks threads <<<"$config"
        if ! run "${base}_${ranks}x${threads}" "$ranks" "$threads" "${args[@]}" \
          "${set_integrator[@]}"; then
          echo "FAIL: ${base}_${ranks}x${threads} exited non-zero:"
          tail -3 "$work/${base}_${ranks}x${threads}.log"
          failures=$((failures + 1))
        fi
      done
      for other in 1x2 2x1; do
        same "${base}_1x1" "${base}_$other" || failures=$((failures + 1))
      done
      echo "$base: (1,1) (1,2) (2,1) compared"
    done
    unset -n args
  done
fi

if [ "$part" = restart ]; then
  # Interrupted by the wall-time limit (a checkpoint, exit 5) on R ranks, continued on R'.
  # ~3 s of work on one process, stopped by the wall-time limit midway.
  long=("${cavity_2d[@]}" --set "Particle/Steps=4000")
  for integrator in shardlow ec-verlet euler; do
    set_integrator=(--set "Particle/Integrator=$integrator")
    # The cavity's dt = 0.01 is shardlow's; the explicit integrators need a smaller one.
    [ $integrator != shardlow ] && set_integrator+=(--set "Particle/Time step=0.0025")
    run "whole_$integrator" 1 1 "${long[@]}" "${set_integrator[@]}" ||
      { echo "FAIL: whole_$integrator"; failures=$((failures + 1)); }
    for pair in "2 1" "1 2"; do
      read -r first then <<<"$pair"
      name=restart_${integrator}_${first}to${then}
      # A third of the whole run's own time: midway on one process, and on two ranks too (they
      # run faster but spend more starting), however fast or busy the host is.
      wall_time=$(python3 -c "import json,sys; print(max(0.2, json.load(open(sys.argv[1]))['results']['wall_seconds'] / 3))" \
        "$work/whole_$integrator/particle/summary.json" 2>/dev/null || echo 0.5)
      run "$name" "$first" 1 "${long[@]}" "${set_integrator[@]}" --wall-time $wall_time
      code=$?
      if [ $code -ne 5 ]; then
        echo "FAIL: $name was not interrupted (exit $code; wanted 5: a checkpoint)"
        failures=$((failures + 1))
        continue
      fi
      grep -h "checkpoint written" "$work/$name.log" | head -1
      launcher=()
      [ "$then" -gt 1 ] && launcher=("$mpirun" -np "$then" --bind-to none)
      OMP_NUM_THREADS=1 "${launcher[@]}" "$twinflow" particle "${long[@]}" "${set_integrator[@]}" \
        --threads 1 --out "$work/$name" --restart >"$work/$name.restart.log" 2>&1 ||
        { echo "FAIL: $name restart"; tail -3 "$work/$name.restart.log"; failures=$((failures + 1)); }
      same "whole_$integrator" "$name" || failures=$((failures + 1))
      echo "$name: continued and compared"
    done
  done
fi

echo "failures: $failures"
[ $failures -eq 0 ]
