#!/usr/bin/env python3
"""Kills a running alphaflex with SIGKILL at random moments (seeded, so each failure can be
replayed) and checks what a user finds afterwards: the XDMF index opens in ParaView (pvpython) and
every step it lists reads, in the deformed configuration, from complete files; NAME.h5's links
reach the same steps; the CSV has a row per step up to at least the last indexed step. Results
are committed in part files that are renamed into place only when complete, and the index is
rewritten atomically, so this must hold whenever the kill comes (io/results_writer.hpp).

usage: kill_during_run.py --exe ALPHAFLEX --pvpython PVPYTHON --scene SCENE --outdir DIR
                          [--kills 4] [--seed 1] [--set key=value ...]
"""
import argparse
import os
import random
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

p = argparse.ArgumentParser()
p.add_argument("--exe", required=True)
p.add_argument("--pvpython", required=True)
p.add_argument("--scene", required=True)
p.add_argument("--outdir", required=True)
p.add_argument("--kills", type=int, default=4)
p.add_argument("--seed", type=int, default=1)
p.add_argument("--set", action="append", default=[])
p.add_argument("--earliest", type=float, default=0.5, help="s after the start, the earliest kill")
p.add_argument("--latest", type=float, default=4.0, help="s after the start, the latest kill")
a = p.parse_args()
rng = random.Random(a.seed)
name = os.path.splitext(os.path.basename(a.scene))[0]
check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "paraview_all_steps.py")

opened = 0
for k in range(a.kills):
    out = os.path.abspath(os.path.join(a.outdir, f"kill{k}"))
    shutil.rmtree(out, ignore_errors=True)
    delay = rng.uniform(a.earliest, a.latest)
    cmd = [a.exe, "run", a.scene, "-o", out] + sum((["--set", s] for s in a.set), [])
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    time.sleep(delay)
    if proc.poll() is not None:
        sys.exit(f"kill {k}: the run ended before the kill at {delay:.2f} s; give it a longer solver.t_end")
    proc.send_signal(signal.SIGKILL)
    proc.wait()
    xdmf = os.path.join(out, name + ".xdmf")
    parts = os.path.join(out, name + ".h5.parts")
    committed = [f for f in os.listdir(parts) if f.endswith(".h5")] if os.path.isdir(parts) else []
    if not os.path.exists(xdmf):
        # Killed before the first output step was committed (still reading the scene, or starting):
        # then there must be no committed part either.
        if committed:
            sys.exit(f"kill {k} at {delay:.2f} s (seed {a.seed}): parts {committed} but no index {xdmf}")
        print(f"kill {k} at {delay:.2f} s: before the first output step (no part, no index)")
        continue
    r = subprocess.run([a.pvpython, "--force-offscreen-rendering", check, xdmf], capture_output=True, text=True, timeout=300)
    if r.returncode != 0:
        sys.exit(f"kill {k} at {delay:.2f} s (seed {a.seed}): ParaView cannot read the index:\n{r.stdout}\n{r.stderr}")
    steps = int(r.stdout.split("steps=")[1].split()[0])
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
        groups = sorted(g for g in f.keys() if g.startswith("step_"))
        q = [f[g]["q"][()] for g in groups]  # every linked step reads
        assert all(np.all(np.isfinite(x)) for x in q)
    rows = sum(1 for _ in open(os.path.join(out, name + ".csv"))) - 1
    if len(groups) < steps or rows < 1:
        sys.exit(f"kill {k} at {delay:.2f} s: NAME.h5 links {len(groups)} steps, the index {steps}; CSV rows {rows}")
    print(f"kill {k} at {delay:.2f} s: index with {steps} steps opens in ParaView, {len(groups)} linked steps, {rows} CSV rows")
    opened += 1
if opened == 0:
    sys.exit("no kill found an index to open: the kills came too early (raise --earliest)")
