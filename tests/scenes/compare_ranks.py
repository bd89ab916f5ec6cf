#!/usr/bin/env python3
"""Runs a scene with 1 rank and with N ranks (mpirun) and checks that the sensors (CSV, every
step) and the final generalized state (HDF5: q, v, lambda) agree within 1e-10 relative per
quantity (relative to its largest magnitude over the run), as issue 'core engine' item 4 asks.

usage: compare_ranks.py --exe ALPHAFLEX --mpirun MPIEXEC [--mpiflags '...'] --ranks 2
                        --scene inputs/X.yaml --outdir DIR [--set key=value ...]
"""
import argparse
import os
import shlex
import subprocess
import sys

import h5py
import numpy as np

p = argparse.ArgumentParser()
p.add_argument("--exe", required=True)
p.add_argument("--mpirun", required=True)
p.add_argument("--mpiflags", default="")
p.add_argument("--ranks", type=int, default=2)
p.add_argument("--scene", required=True)
p.add_argument("--outdir", required=True)
p.add_argument("--set", action="append", default=[])
p.add_argument("--rtol", type=float, default=1e-10)
a = p.parse_args()

sets = sum((["--set", s] for s in a.set), [])
name = None
results = {}
for n in (1, a.ranks):
    out = os.path.join(a.outdir, f"np{n}")
    cmd = [a.exe, "run", a.scene, "-o", out] + sets
    if n > 1:
        cmd = [a.mpirun] + shlex.split(a.mpiflags) + ["-np", str(n)] + cmd
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if r.returncode != 0:
        sys.exit(f"run with {n} rank(s) failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    csv = [f for f in os.listdir(out) if f.endswith(".csv")]
    assert len(csv) == 1, csv
    name = csv[0][:-4]
    data = np.genfromtxt(os.path.join(out, csv[0]), delimiter=",", names=True)
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
        last = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
        state = {k: f[last][k][()] for k in ("q", "v", "lambda")}
    results[n] = (data, state)

(d1, s1), (dn, sn) = results[1], results[a.ranks]
worst = 0.0
failed = []
if d1.shape != dn.shape:
    sys.exit(f"different number of steps: {d1.shape} vs {dn.shape}")
for col in d1.dtype.names:
    scale = max(np.max(np.abs(d1[col])), 1e-300)
    rel = np.max(np.abs(d1[col] - dn[col])) / scale
    worst = max(worst, rel)
    if rel > a.rtol:
        failed.append(f"sensor {col}: {rel:.3e}")
for k in s1:
    scale = max(np.max(np.abs(s1[k])), 1e-300)
    rel = np.max(np.abs(s1[k] - sn[k])) / scale if s1[k].size else 0.0
    worst = max(worst, rel)
    if rel > a.rtol:
        failed.append(f"final {k}: {rel:.3e}")
print(f"{name}: 1 vs {a.ranks} ranks, largest relative difference {worst:.3e} (limit {a.rtol:g})")
if failed:
    sys.exit("disagreement beyond the limit:\n  " + "\n  ".join(failed))
