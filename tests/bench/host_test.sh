#!/usr/bin/env bash
# The bench summaries name their host (issue 48): bench/host.sh's lines for this machine, and
# bench/summarise.py printing them before its first table.
# usage: host_test.sh SOURCE_DIR TWINFLOW
set -euo pipefail
SRC=$1
export TW=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
. "$SRC/bench/host.sh"
host_lines >"$OUT/raw.txt"
for key in date cpu cores isa twinflow kernels; do
  grep -q "^host $key ." "$OUT/raw.txt" || { echo "no '$key' line:"; cat "$OUT/raw.txt"; exit 1; }
done
grep -q "^host cores $(nproc) " "$OUT/raw.txt" || { echo "cores wrong"; exit 1; }
grep -q "^host kernels $("$TW" --version | sed -n 's/^particle kernels: \(.*\) (this.*/\1/p')" \
  "$OUT/raw.txt" || { echo "kernels line is not --version's path"; exit 1; }
echo "perf ours:shardlow:1:6000 1.0e6 100000" >>"$OUT/raw.txt"
python3 "$SRC/bench/summarise.py" "$OUT/raw.txt" >"$OUT/summary.md"
first_table=$(grep -n '^| N |' "$OUT/summary.md" | head -1 | cut -d: -f1)
host_line=$(grep -n '^- kernels: ' "$OUT/summary.md" | head -1 | cut -d: -f1)
[ -n "$host_line" ] && [ -n "$first_table" ] && [ "$host_line" -lt "$first_table" ] ||
  { echo "summary.md does not name the host before its table:"; cat "$OUT/summary.md"; exit 1; }
echo "ok: $(grep '^- cpu' "$OUT/summary.md")"
