#!/bin/bash
# ctest -L faults: injected faults end with their documented exit code, a message that names
# the cause, and no incomplete file under a final name (every .h5 opens, every .json parses, no
# temporary file left where the command could clean up).
#   faults_test.sh SOURCE_DIR TWINFLOW_BINARY CASE
# CASE: disk-full | read-only | transport-cache | truncated-checkpoint | signals
set -u
source_dir=${1:?usage: faults_test.sh SOURCE_DIR TWINFLOW_BINARY CASE}
twinflow=${2:?usage: faults_test.sh SOURCE_DIR TWINFLOW_BINARY CASE}
case_name=${3:?usage: faults_test.sh SOURCE_DIR TWINFLOW_BINARY CASE}
cavity="$source_dir/cases/heated_cavity_2d.prm"
work=$(mktemp -d /tmp/twinflow_faults.XXXXXX)
chmod 755 "$work"
trap 'rm -rf "$work"' EXIT
export TWINFLOW_CACHE=off
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# The default cavity shrunk to a second: 10 x 10 rc at density 1, 5 x 5 bins, a 4 x 4 mesh.
tiny=(--threads 1 --set 'Scene/Box size=10, 10' --set 'Scene/Density=1'
  --set 'Scene/Field bins=5, 5' --set 'Particle/Equilibration steps=200'
  --set 'Particle/Steps=400' --set 'Continuum/Mesh/Cells=4' --set 'Continuum/Mesh/Refinements=1'
  --set 'Transport/Measure kappa and eta=false' --set 'Transport/Kappa from walls=false')

# expect CODE PATTERN LOG WHAT: the exit code and a message naming the cause.
expect() {
  local code=$1 pattern=$2 log=$3 what=$4 got=$5
  [ "$got" = "$code" ] || fail "$what: exit $got, expected $code; output:
$(tail -5 "$log")"
  grep -qE "$pattern" "$log" || fail "$what: no message matching '$pattern'; output:
$(tail -5 "$log")"
}

# Every file under a final name is complete: .h5 opens, .json parses; no temporary file.
complete_files() {
  local dir=$1 what=$2 temporaries=${3:-none}
  [ -d "$dir" ] || return 0
  while IFS= read -r f; do
    case "$f" in
    *.tmp | *.tmp.*)
      [ "$temporaries" = allowed ] || fail "$what: temporary file left: $f"
      ;;
    *.h5) h5dump -H "$f" >/dev/null 2>&1 || fail "$what: $f does not open as HDF5" ;;
    *.json) /usr/bin/python3 -m json.tool "$f" >/dev/null 2>&1 || fail "$what: $f is not JSON" ;;
    esac
  done < <(find "$dir" -type f)
}

case "$case_name" in
disk-full)
  # A file-size limit with SIGXFSZ ignored: a write past it fails with EFBIG ("File too large"),
  # as on a full disk. Limits between the sizes of the run's files fail it at several points:
  # the particle stage's CSVs, its fields.h5, the continuum twins' fields.h5, the report.
  # The transport measurement once, from a cache afterwards (the faults are in the writes).
  export TWINFLOW_CACHE="$work/cache"
  # Open MPI's start-up writes shared-memory segments larger than the limit: keep them out
  # (PMIx's hash store, no shared-memory transport: one process needs neither).
  export PMIX_MCA_gds=hash OMPI_MCA_btl=self
  "$twinflow" run "$cavity" "${tiny[@]}" --out "$work/reference" >"$work/reference.log" 2>&1 ||
    { cat "$work/reference.log"; fail "the reference run failed"; exit 1; }
  mapfile -t sizes < <(find "$work/reference" -type f -printf '%s\n' | sort -n | uniq)
  n=${#sizes[@]}
  points=0
  for index in $((n - 1)) $((n * 2 / 3)) $((n / 3)); do
    limit=$((sizes[index] - 1))
    [ "$limit" -gt 0 ] || continue
    dir="$work/full_$limit"
    bash -c 'trap "" XFSZ; exec prlimit --fsize='"$limit"' "$@"' _ \
      "$twinflow" run "$cavity" "${tiny[@]}" --out "$dir" >"$dir.log" 2>&1
    code=$?
    points=$((points + 1))
    if [ "$code" = 0 ]; then
      # The only files above the limit were the report's (written by Python, a warning only).
      grep -q "the report failed" "$dir.log" || fail "limit $limit: exit 0 and no report warning"
    else
      expect 6 "output failed: cannot write .*: File too large" "$dir.log" "limit $limit" "$code"
    fi
    complete_files "$dir" "limit $limit"
    grep -qi "segmentation\|core dumped" "$dir.log" && fail "limit $limit: crashed"
  done
  [ "$points" -ge 3 ] || fail "fewer than 3 fault points ($points)"
  # The directory can be run again once there is room: the same command completes it (reusing
  # the stages that had finished).
  last="$work/full_$((sizes[n / 3] - 1))"
  "$twinflow" run "$cavity" "${tiny[@]}" --out "$last" >"$last.again.log" 2>&1 ||
    fail "the rerun after the disk-full failure exited non-zero: $(tail -3 "$last.again.log")"
  complete_files "$last" "rerun"
  ;;
read-only)
  # As root the permission bits do not stop writes: run as nobody there.
  as_user=()
  [ "$(id -u)" = 0 ] && as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  mkdir -p "$work/ro"
  chmod 555 "$work/ro"
  "${as_user[@]}" "$twinflow" particle "$cavity" "${tiny[@]}" --out "$work/ro/run" \
    >"$work/ro.log" 2>&1
  expect 6 "output failed: .*Permission denied" "$work/ro.log" "read-only --out" $?
  [ -e "$work/ro/run" ] && fail "read-only: something was written"
  # A run directory whose particle folder became read-only after the stage started.
  mkdir -p "$work/rw/particle"
  chmod 777 "$work/rw" && chmod 555 "$work/rw/particle"
  "${as_user[@]}" "$twinflow" particle "$cavity" "${tiny[@]}" --out "$work/rw" \
    >"$work/rw.log" 2>&1
  expect 6 "output failed: cannot write .*particle/.*: Permission denied" "$work/rw.log" \
    "read-only particle folder" $?
  complete_files "$work/rw" "read-only particle folder"
  ;;
transport-cache)
  cache="$work/cache"
  export TWINFLOW_CACHE="$cache"
  "$twinflow" transport "$cavity" "${tiny[@]}" --out "$work/a" >"$work/a.log" 2>&1 ||
    { cat "$work/a.log"; fail "transport failed"; exit 1; }
  entry=$(find "$cache/transport" -mindepth 1 -maxdepth 1 -type d | head -1)
  [ -n "$entry" ] || { fail "no cache entry written"; exit 1; }
  # A truncated coefficients.csv: a miss with a warning, measured again, the same coefficients.
  truncate -s 40 "$entry/coefficients.csv"
  "$twinflow" transport "$cavity" "${tiny[@]}" --out "$work/b" >"$work/b.log" 2>&1
  expect 0 "cache entry .*coefficients.csv is truncated or altered.*measuring" "$work/b.log" \
    "truncated cache coefficients.csv" $?
  cmp -s "$work/a/transport/coefficients.csv" "$work/b/transport/coefficients.csv" ||
    fail "the re-measured coefficients differ from the first measurement"
  for d in a b; do complete_files "$work/$d" "cache $d"; done
  complete_files "$cache" "the cache"
  # A truncated summary.json, then garbage instead of JSON: a miss with a one-line warning at
  # the start (the measurement that follows need not finish: it is the one above).
  for damage in truncated garbage; do
    if [ $damage = truncated ]; then
      head -c 100 "$entry/summary.json" >"$work/cut" && cat "$work/cut" >"$entry/summary.json"
    else
      head -c 3000 /dev/urandom >"$entry/summary.json"
    fi
    log="$work/$damage.log"
    "$twinflow" transport "$cavity" "${tiny[@]}" --out "$work/$damage" >"$log" 2>&1 &
    pid=$!
    for _ in $(seq 600); do
      grep -q "cache entry" "$log" 2>/dev/null || ! kill -0 $pid 2>/dev/null && break
      sleep 0.1
    done
    kill -TERM $pid 2>/dev/null
    wait $pid
    grep -qaE "cache entry .*unreadable.*measuring" "$log" ||
      fail "$damage cache summary.json: no warning: $(head -3 "$log")"
    grep -a "cache entry" "$log" | grep -q $'[\x01-\x08]' &&
      fail "$damage cache summary.json: the warning quotes unprintable bytes"
  done
  ;;
truncated-checkpoint)
  run=(particle "$cavity" "${tiny[@]}" --set 'Particle/Steps=200000' --out "$work/cp")
  "$twinflow" "${run[@]}" --wall-time 1 >"$work/stop.log" 2>&1
  expect 5 "continue with: .*--restart" "$work/stop.log" "wall-time stop" $?
  checkpoint="$work/cp/particle/checkpoint.twfc"
  [ -s "$checkpoint" ] || { fail "no checkpoint"; exit 1; }
  size=$(stat -c %s "$checkpoint")
  truncate -s $((size / 2)) "$checkpoint"
  "$twinflow" "${run[@]}" --restart >"$work/restart.log" 2>&1
  expect 2 "checkpoint.twfc: truncated or corrupt checkpoint" "$work/restart.log" \
    "truncated checkpoint" $?
  printf 'not a checkpoint' >"$checkpoint"
  "$twinflow" "${run[@]}" --restart >"$work/restart2.log" 2>&1
  expect 2 "checkpoint.twfc: not a twinflow checkpoint" "$work/restart2.log" "garbage checkpoint" $?
  complete_files "$work/cp" "truncated checkpoint"
  ;;
signals)
  # SIGTERM at a random moment: exit 5 and a checkpoint; SIGKILL: whatever is there is complete
  # (a temporary file may be left by the kill itself), and the next run cleans up and finishes.
  long=(particle "$cavity" "${tiny[@]}" --set 'Particle/Steps=20000'
    --set 'Particle/Checkpoint interval=0.005')
  for round in 1 2; do
    dir="$work/term$round"
    "$twinflow" "${long[@]}" --out "$dir" >"$dir.log" 2>&1 &
    pid=$!
    sleep "0.$((RANDOM % 9 + 1))"
    until [ -d "$dir/particle" ] || ! kill -0 $pid 2>/dev/null; do sleep 0.05; done
    sleep "0.$((RANDOM % 5))"
    kill -TERM $pid 2>/dev/null
    wait $pid
    code=$?
    if [ "$code" != 0 ]; then # it may have finished first
      expect 5 "interrupted by a signal.*|continue with:" "$dir.log" "SIGTERM round $round" "$code"
      [ -s "$dir/particle/checkpoint.twfc" ] || fail "SIGTERM round $round: no checkpoint"
    fi
    complete_files "$dir" "SIGTERM round $round"

    dir="$work/kill$round"
    "$twinflow" "${long[@]}" --out "$dir" >"$dir.log" 2>&1 &
    pid=$!
    until [ -d "$dir/particle" ] || ! kill -0 $pid 2>/dev/null; do sleep 0.05; done
    sleep "0.$((RANDOM % 9))"
    kill -KILL $pid 2>/dev/null
    wait $pid 2>/dev/null
    complete_files "$dir" "SIGKILL round $round" allowed
    if [ -s "$dir/particle/checkpoint.twfc" ]; then
      "$twinflow" "${long[@]}" --out "$dir" --restart >"$dir.restart.log" 2>&1 ||
        fail "SIGKILL round $round: --restart failed: $(tail -3 "$dir.restart.log")"
      grep -q "resumed from step [0-9]* (checkpoint of " "$dir.restart.log" ||
        fail "SIGKILL round $round: no 'resumed from step N' line"
    else
      "$twinflow" "${long[@]}" --out "$dir" --force >"$dir.again.log" 2>&1 ||
        fail "SIGKILL round $round: the rerun failed: $(tail -3 "$dir.again.log")"
    fi
    complete_files "$dir" "after SIGKILL round $round"
  done
  ;;
*)
  echo "unknown case $case_name"
  exit 2
  ;;
esac
[ "$failures" = 0 ] && echo "faults $case_name: passed"
exit $((failures > 0))
