#!/usr/bin/env bash
# One-command set-up for a fresh Debian 12 machine (run as root, from the repository root):
#   bash scripts/setup.sh run    install dependencies, build, run the default scene
#   bash scripts/setup.sh test   install dependencies, build, run the whole test suite (ctest), then
#                                the sanitizer run (scripts/sanitize.sh)
set -euo pipefail
mode=${1:-run}
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

bash scripts/install-deps.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
jobs=$(nproc 2>/dev/null || echo 2)
# Ninja for a new build tree (docs/testing.md, "Time of the suite"): it compiles a target's sources
# while the libraries it links are still being built, so both cores stay busy to the end; an
# existing tree keeps the generator it was made with (CMake refuses to switch).
generator=(); [ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DALPHAFLEX_UNITY_BUILD=ON
case "$mode" in
  run)
    cmake --build build -j"$jobs" --target alphaflex_exe
    scene=${2:-inputs/andrews.yaml}
    ./build/alphaflex run "$scene" -o out
    echo "Results are in $root/out: open $root/out/$(basename "$scene" .yaml).xdmf in ParaView (by its absolute path)."
    ;;
  test)
    start=$(date +%s)
    cmake --build build -j"$jobs"
    echo "setup: build $(( $(date +%s) - start )) s"
    start=$(date +%s)
    (cd build && ctest -j"$jobs" --output-on-failure --timeout 900)
    echo "setup: ctest $(( $(date +%s) - start )) s"
    # Then the unit tests and the fuzz test under AddressSanitizer + UBSan (docs/testing.md).
    bash scripts/sanitize.sh build-asan
    ;;
  *)
    echo "usage: bash scripts/setup.sh run [SCENE.yaml] | test" >&2
    exit 2
    ;;
esac
