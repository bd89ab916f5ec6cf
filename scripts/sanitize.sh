#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run (docs/testing.md): configures BUILD_DIR
# (default build-asan) with -DALPHAFLEX_SANITIZE=ON, builds the library, the unit tests and the fuzz
# test, and runs them; any sanitizer report ends that run with an error, and so this script.
#   bash scripts/sanitize.sh [BUILD_DIR] [--build-only]   (JOBS=N for the build; default: all cores)
# `scripts/setup.sh test` (so CI: .ci/run) calls it with --build-only and runs the sanitized unit
# tests and fuzz test inside ctest (ALPHAFLEX_SANITIZED_TESTS, tests/CMakeLists.txt).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$root/build-asan}
mode=all; [ "${2:-}" = --build-only ] && mode=build
jobs=${JOBS:-$(nproc 2>/dev/null || echo 2)}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# -O1: the sanitizers' usual level (fast enough to run, keeps frames for the reports); -g1: line
# numbers in reports at a fraction of the compile time of -g.
mkdir -p "$dir"
generator=(); [ -f "$dir/CMakeCache.txt" ] || generator=(-G Ninja)   # as scripts/setup.sh
cmake -S "$root" -B "$dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
      -DALPHAFLEX_SANITIZE=ON -DALPHAFLEX_UNITY_BUILD=ON > "$dir/configure.log" 2>&1 || { cat "$dir/configure.log"; exit 1; }
start=$(date +%s)
cmake --build "$dir" -j"$jobs" --target unit_tests fuzz_inputs
echo "sanitize: build $(( $(date +%s) - start )) s"
[ "$mode" = build ] && exit 0

# The sanitizers' run-time options (why leaks are not checked: in the file).
set -a; . "$root/scripts/sanitizer.env"; set +a

# Unit tests without the three slowest: the shell benchmarks of Sze et al. (larger meshes of the
# elements that ReissnerMindlinShell.* and ShellScenes.* test), the order-2 convergence study of
# the spinning shell (many runs of one model) and MUMPS' block low-rank factorization (a plate of
# 6·10⁴ unknowns, 0.9 GB, the only size MUMPS compresses: library code, no element of ours that
# other tests do not cover): most of the budget under the sanitizers (docs/testing.md).
slow='SzeShellBenchmarks.*:ShellDynamics.SpinUpConvergesWithOrderTwoInTimeForRhoPointSeven:LowRankFactorization.*'
# The unit tests and the fuzz test side by side, one process on each core: the fuzz test's budget is
# its number of cases (--time-limit is its watchdog for one case, whose slowest takes ~3 s), so
# running beside the unit tests costs it no cases.
start=$(date +%s)
(cd "$dir/tests/fuzz" && ALPHAFLEX_MESH_CACHE=off ./fuzz_inputs --work "$dir/tests/fuzz/work" --time-limit 30 > "$dir/fuzz.log" 2>&1) &
fuzz=$!
unit=0
(cd "$dir/tests" && ./unit_tests --gtest_filter="-$slow" --gtest_brief=1) || unit=$?
echo "sanitize: unit tests $(( $(date +%s) - start )) s"
fuzz_status=0
wait "$fuzz" || fuzz_status=$?
cat "$dir/fuzz.log"
echo "sanitize: fuzz test (beside the unit tests) $(( $(date +%s) - start )) s"
[ "$unit" -eq 0 ] || { echo "sanitize: unit tests failed (exit $unit)" >&2; exit "$unit"; }
[ "$fuzz_status" -eq 0 ] || { echo "sanitize: fuzz test failed (exit $fuzz_status)" >&2; exit "$fuzz_status"; }
echo "sanitize: no sanitizer reports"
