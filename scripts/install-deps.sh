#!/usr/bin/env bash
# Installs alphaflex's build and test dependencies from Debian 12 packages (run as root).
# Idempotent: packages already present are skipped, so a second run costs a few seconds.
set -euo pipefail
# libblas-dev and liblapack-dev (which petsc-dev pulls in too): cblas.h and the link names of the
# BLAS and LAPACK that alphaflex's own small dense kernels call (CMakeLists.txt), OpenBLAS below.
PKGS=(build-essential cmake ninja-build pkg-config git
      petsc-dev libopenmpi-dev openmpi-bin libhdf5-openmpi-dev libmetis-dev
      libblas-dev liblapack-dev libopenblas0-serial libgmsh-dev gmsh libeigen3-dev libyaml-cpp-dev nlohmann-json3-dev libgtest-dev libsundials-dev hyperfine
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

# MUMPS' and ScaLAPACK's dense kernels run on whatever libblas.so.3/liblapack.so.3 Debian's
# alternatives point to. OpenBLAS, single-threaded (one rank per core, no oversubscription under
# mpirun): measured against the reference BLAS and the pthread build in docs/performance.md (dense
# kernels). Set explicitly, because libopenblas0-pthread, if some other package installs it, has the
# higher priority in auto mode. Three links: OpenBLAS' libblas.so.3 and liblapack.so.3 forward to
# the libopenblas.so.0 found next to the link they were loaded through, so that third alternative
# decides serial or pthread (alphaflex's run summary shows what was loaded: BLAS line).
# Idempotent: nothing is changed when the links already point there.
for lib in blas.so.3 lapack.so.3 openblas.so.0; do
  target=/usr/lib/x86_64-linux-gnu/openblas-serial/lib$lib
  name=lib$lib-x86_64-linux-gnu
  if [ "$(readlink -f /etc/alternatives/$name)" != "$target" ]; then
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO=sudo
    $SUDO update-alternatives --quiet --set "$name" "$target"
  fi
done
