#!/usr/bin/env bash
# Installs the Debian 12 packages twinflow needs; idempotent (installs only what is missing).
set -euo pipefail
packages=(
  build-essential cmake clang-format
  libdeal.ii-dev libeigen3-dev libboost-program-options-dev libgtest-dev
  librandom123-dev libhdf5-openmpi-dev hdf5-tools nlohmann-json3-dev
  python3-h5py python3-matplotlib libxml2-utils openmpi-bin
)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
