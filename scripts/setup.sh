#!/usr/bin/env bash
# One-command set-up for a fresh Debian 12 machine (run as root, from the repository root):
#   bash scripts/setup.sh run    install dependencies, build, run the default scene
#   bash scripts/setup.sh test   install dependencies, build the Release tree and the sanitizer tree
#                                (scripts/sanitize.sh), run the whole test suite (ctest), whose unit
#                                tests and fuzz test are the sanitized ones
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
# test: ctest runs the unit tests and the fuzz test from the sanitizer tree build-asan (built below
# by scripts/sanitize.sh), so they are compiled and run once, under the sanitizers, and this tree
# builds the library, the executable and the other tests (tests/CMakeLists.txt, docs/testing.md).
sanitized=(); [ "$mode" = test ] && sanitized=("-DALPHAFLEX_SANITIZED_TESTS=$root/build-asan")
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DALPHAFLEX_UNITY_BUILD=ON "${sanitized[@]}"
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
    # The unit tests and the fuzz test under AddressSanitizer + UBSan, built here, run by ctest.
    bash scripts/sanitize.sh "$root/build-asan" --build-only
    start=$(date +%s)
    (cd build && ctest -j"$jobs" --output-on-failure --timeout 900)
    echo "setup: ctest $(( $(date +%s) - start )) s"
    ;;
  *)
    echo "usage: bash scripts/setup.sh run [SCENE.yaml] | test" >&2
    exit 2
    ;;
esac
