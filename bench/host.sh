# Sourced by the bench scripts: the host a measurement ran on, as "host KEY VALUE" lines of the
# raw file (bench/host.py prints them first in every summary: a ratio is read with its host).
# Needs TW (the twinflow binary); LMP optional.
host_lines() {
  local flags isa
  flags=$(grep -m1 '^flags' /proc/cpuinfo || true)
  isa=""
  for f in avx2 fma avx512f avx512vl; do [[ " $flags " == *" $f "* ]] && isa="$isa $f"; done
  echo "host date $(date -u +%Y-%m-%dT%H:%MZ)"
  local field='s/^[^:]*: *//'
  echo "host cpu $(grep -m1 '^model name' /proc/cpuinfo | sed "$field") (family" \
    "$(grep -m1 '^cpu family' /proc/cpuinfo | sed "$field"), model" \
    "$(grep -m1 '^model\s*:' /proc/cpuinfo | sed "$field"))"
  echo "host cores $(nproc) (online: $(getconf _NPROCESSORS_ONLN))"
  echo "host isa${isa:- none of avx2 fma avx512f avx512vl}"
  echo "host twinflow $("$TW" --version | head -1)"
  echo "host kernels $("$TW" --version | sed -n 's/^particle kernels: //p')${TWINFLOW_ISA:+ (TWINFLOW_ISA=$TWINFLOW_ISA)}"
  if [ -n "${LMP:-}" ] && [ -x "$LMP" ]; then
    echo "host lammps $LMP ($(strings "$LMP" | grep -m1 -o 'LAMMPS ([0-9A-Za-z ]*)' || echo 'version unknown'))"
  fi
}
