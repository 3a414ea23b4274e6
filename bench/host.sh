# Sourced by the bench scripts: the host a measurement ran on, as "host KEY VALUE" lines of the
# raw file (bench/host.py prints them first in every summary: a ratio is read with its host).
# The host itself is `twinflow --version`'s (io::host_record, the one place that reads the CPU).
# Needs TW (the twinflow binary); LMP optional.
host_lines() {
  local version host
  version=$("$TW" --version)
  host=$(sed -n 's/^host: //p' <<<"$version")
  echo "host date $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "host cpu ${host%, * cores, isa *}"
  echo "host cores $(sed -n 's/.*), \([0-9]*\) cores, isa .*/\1/p' <<<"$host")" \
    "(online: $(getconf _NPROCESSORS_ONLN))"
  echo "host isa ${host##*, isa }"
  echo "host twinflow $(head -1 <<<"$version")"
  echo "host kernels $(sed -n 's/^particle kernels: //p' <<<"$version")${TWINFLOW_ISA:+ (TWINFLOW_ISA=$TWINFLOW_ISA)}"
  if [ -n "${LMP:-}" ] && [ -x "$LMP" ]; then
    echo "host lammps $LMP ($(strings "$LMP" | grep -m1 -o 'LAMMPS ([0-9A-Za-z ]*)' || echo 'version unknown'))"
  fi
}
