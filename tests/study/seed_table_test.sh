#!/bin/bash
# scripts/seed_table.py on a two-seed sweep of the shrunken quick start (each seed with its own
# transport stage and twins): one row per seed, the chi^2 checks and the verdict counts.
#   seed_table_test.sh SOURCE_DIR TWINFLOW_BINARY
set -eu
source_dir=${1:?usage: seed_table_test.sh SOURCE_DIR TWINFLOW_BINARY}
twinflow=${2:?usage: seed_table_test.sh SOURCE_DIR TWINFLOW_BINARY}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
TWINFLOW_CACHE=off "$twinflow" sweep "$source_dir/cases/quickstart_2d.prm" --out "$out/seeds" \
  --vary 'Particle/Seed=1,2' --set 'Particle/Steps=4000' --jobs 1 --threads 2 >"$out/log" 2>&1 ||
  { tail -20 "$out/log"; exit 1; }
python3 "$source_dir/scripts/seed_table.py" "$out/seeds" | tee "$out/table"
grep -q '^| 1 | ' "$out/table" && grep -q '^| 2 | ' "$out/table"
grep -q '^chi^2/dof over 2 runs' "$out/table"
grep -q '^- heat flow across the heated walls: ' "$out/table"
grep -q "^- particle Nu (the heat flow's and its conduction flux's kappa errors): " "$out/table"
grep -q '^- strict verdict, temperature within errors: [0-2] of 2' "$out/table"
# fewer than two finished runs: said, exit 1
if python3 "$source_dir/scripts/seed_table.py" "$out/seeds/points/000" 2>/dev/null; then exit 1; fi
echo "seed_table_test: passed"
