#!/usr/bin/env bash
# Start-up of small runs (docs/performance.md, "Start-up"): hyperfine, interleaved by its own
# rotation of the commands, of `alphaflex run` on one step of Andrews (no mesh) and of the beam
# spin-up (a gmsh mesh), for a baseline build and this one; the baseline also with the daemon-free
# singleton set by hand, to separate the two changes. Wall and CPU (user + sys) per process.
# Issue 22, second round: also 2 steps of the hammer-struck beam (10 elements, a .geo meshed at run
# time), and the meshed scenes of this build with the mesh cache off (ALPHAFLEX_MESH_CACHE=off: gmsh
# loaded every run) and on (a cache of this script's own, filled by the warm-up runs).
#   bash scripts/startup_benchmark.sh BASELINE_EXE [EXE] [RUNS]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
base=$(realpath "$1")
exe=$(realpath "${2:-$root/build/alphaflex}")
runs=${3:-20}
out=$(mktemp -d)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
andrews="run $root/inputs/andrews.yaml --set solver.t_end=0.0003 -o $out/a"
spinup="run $root/inputs/beam_spinup.yaml --set solver.t_end=0.01 -o $out/b"
hammer="run $root/inputs/beam_hammer_damped.yaml --set solver.t_end=0.002 -o $out/c"
off="env ALPHAFLEX_MESH_CACHE=off"
on="env ALPHAFLEX_MESH_CACHE=$out/cache"
cd "$out"
hyperfine -N -w 2 -r "$runs" --export-json "$out/startup.json" \
  "$base help" "$exe help" \
  "$base $andrews" "env OMPI_MCA_ess_singleton_isolated=1 $base $andrews" "$exe $andrews" \
  "$base $spinup" "$off $exe $spinup" "$on $exe $spinup" \
  "$base $hammer" "$off $exe $hammer" "$on $exe $hammer"
uptime
/usr/bin/python3 - "$out/startup.json" <<'PY'
import json, sys
for r in json.load(open(sys.argv[1]))["results"]:
    print(f"{r['median']:.3f} s wall median, {r['user'] + r['system']:.3f} s CPU mean | {r['command']}")
PY
rm -rf "$out"
