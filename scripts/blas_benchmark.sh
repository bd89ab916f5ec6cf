#!/usr/bin/env bash
# Dense kernels under MUMPS (docs/performance.md, "Dense kernels"): the same alphaflex binary on the
# reference BLAS, OpenBLAS serial, and OpenBLAS pthread with 1 and 2 threads, switched through
# Debian's alternatives between runs and interleaved (the order reversed on even repetitions), on
# one step of the gridshell at several sizes and on a long beam. Prints one line per run:
#   variant|case|unknowns|numeric factorizations|factorization (s)|run wall (s)|process wall user sys|BLAS
# Run as root (it switches the system's libblas.so.3/liblapack.so.3); it leaves OpenBLAS serial set,
# as scripts/install-deps.sh does.
#   bash scripts/blas_benchmark.sh [EXE] [REPETITIONS] > blas.txt
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
exe=$(realpath "${1:-$root/build/alphaflex}")
reps=${2:-2}
in=$root/inputs
lib=/usr/lib/x86_64-linux-gnu
out=$(mktemp -d)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# libblas.so.3 and liblapack.so.3 of OpenBLAS forward to libopenblas.so.0, found next to the link
# they are loaded through (/usr/lib/x86_64-linux-gnu/libopenblas.so.0): a third alternative, which
# decides serial or pthread whatever the first two say.
setalt() {
  update-alternatives --quiet --set libblas.so.3-x86_64-linux-gnu "$lib/$1/libblas.so.3"
  update-alternatives --quiet --set liblapack.so.3-x86_64-linux-gnu "$lib/$2/liblapack.so.3"
  [ "$1" = blas ] || update-alternatives --quiet --set libopenblas.so.0-x86_64-linux-gnu "$lib/$1/libopenblas.so.0"
}
run() {  # variant case scene-arguments...
  local v=$1 c=$2 envs=() text
  shift 2
  case $v in
    reference) setalt blas lapack ;;
    serial) setalt openblas-serial openblas-serial ;;
    pthread1) setalt openblas-pthread openblas-pthread; envs=(OPENBLAS_NUM_THREADS=1) ;;
    pthread2) setalt openblas-pthread openblas-pthread; envs=(OPENBLAS_NUM_THREADS=2) ;;
  esac
  text=$(cd "$out" && env "${envs[@]}" /usr/bin/time -f "TIME %e %U %S" "$exe" run "$@" -o "$out/run" 2>&1)
  # The run's figures from OUTDIR/NAME.summary.json (python/alphaflex_results.py).
  local figures
  figures=$(/usr/bin/python3 - "$out/run" "$(basename "$1" .yaml)" "$root/python" <<'PY'
import sys
sys.path.insert(0, sys.argv[3])
import alphaflex_results as ar
j = ar.load_summary(sys.argv[1], sys.argv[2])
print(f"{j['unknowns']}|{j['factorizations']['numeric']}|{j['wall_time']['factorization']['s']:.3f}|{j['wall_time']['s']:.3f}")
print(j["blas"])
PY
)
  echo "$v|$c|$(head -1 <<<"$figures")|$(grep '^TIME' <<<"$text" | cut -d' ' -f2-)|$(tail -1 <<<"$figures")"
}
for ((rep = 1; rep <= reps; rep++)); do
  for c in g16 g32 g48 beam; do
    case $c in
      g16 | g32 | g48) a=("$in/gridshell.yaml" --set "mesh.parameters.n=${c#g}" --set solver.t_end=0.01) ;;
      beam) a=("$in/beam_spinup.yaml" --set mesh.elements=20000 --set solver.t_end=0.02) ;;
    esac
    vs=(reference serial pthread1 pthread2)
    ((rep % 2 == 0)) && vs=(pthread2 pthread1 serial reference)
    for v in "${vs[@]}"; do run "$v" "$c" "${a[@]}"; done
  done
done
setalt openblas-serial openblas-serial
rm -rf "$out"
