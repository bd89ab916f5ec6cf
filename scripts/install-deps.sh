#!/usr/bin/env bash
# Installs alphaflex's build and test dependencies from Debian 12 packages (run as root).
# Idempotent: packages already present are skipped, so a second run costs a few seconds.
set -euo pipefail
PKGS=(build-essential cmake pkg-config git
      petsc-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev
      libgmsh-dev gmsh libeigen3-dev libyaml-cpp-dev libgtest-dev libsundials-dev
      slepc-dev python3-matplotlib python3-numpy python3-h5py python3-scipy paraview python3-paraview xvfb)
missing=()
for p in "${PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
