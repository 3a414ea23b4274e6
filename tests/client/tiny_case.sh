# Sourced by the client tests: a scratch folder removed on exit, no transport cache, and the
# default cavity shrunk to seconds ("${tiny[@]}", the case in $case).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export TWINFLOW_CACHE=off
tiny=(--threads 2 --set 'Scene/Box size=10, 10' --set 'Scene/Density=2'
  --set 'Scene/Field bins=5, 5' --set 'Particle/Equilibration steps=200'
  --set 'Particle/Steps=1000' --set 'Continuum/Mesh/Cells=8' --set 'Continuum/Mesh/Refinements=0')
case="$source_dir/cases/heated_cavity_2d.prm"
