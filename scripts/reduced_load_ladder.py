#!/usr/bin/env python3
"""Where reduction fails (issue 19): the cantilever elastica (inputs/beam_elastica.yaml, static,
PL²/EI = 10 at load factor 1) reduced vs full at growing load levels. At each level it runs the
ladder (rigid, k Craig–Bampton modes on [root, tip], full = the reference, the nonlinear mesh) and
prints the error of each rung — max |Δ tip_ux|, |Δ tip_uy| over the full run's tip deflection |u| —
the lightest rung within the tolerance, and the level where that rung changes.

The reduced body's strain is linear in its floating frame (docs/theory/reduced_bodies.md), so its
tip deflection is PL³/3EI at every level and it misses the elastica's shortening (tip_ux): its
error grows with the load, like (PL²/EI)·const for small loads.

A stop-gap for the `fidelity` study's load axis (not yet in src/study/): same measure, run here.
Usage: reduced_load_ladder.py EXE SOURCE_DIR OUTDIR [--factors 0.01,0.03,0.1,0.3,1] [--tol 0.01]
"""
import argparse, csv, math, os, subprocess, sys

ap = argparse.ArgumentParser()
ap.add_argument("exe"); ap.add_argument("src"); ap.add_argument("out")
ap.add_argument("--factors", default="0.01,0.03,0.1,0.3,1")
ap.add_argument("--ladder", default="rigid,2,8,full")
ap.add_argument("--tol", type=float, default=0.01)
a = ap.parse_args()
scene = os.path.join(a.src, "inputs", "beam_elastica.yaml")


def tip(factor, rung):
    d = os.path.join(a.out, f"f{factor}_{rung}")
    cmd = [a.exe, "run", scene, "-o", d, "--set", f"load.factor={factor}"]
    if rung == "rigid":
        cmd.append("--set=beams.0.reduction={method: rigid, interface: [root, tip]}")
    elif rung != "full":
        cmd.append(f"--set=beams.0.reduction={{method: craig_bampton, modes: {rung}, interface: [root, tip]}}")
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    last = list(csv.DictReader(open(os.path.join(d, "beam_elastica.csv"))))[-1]
    return float(last["tip_ux"]), float(last["tip_uy"])


ladder = a.ladder.split(",")
prev = None
changes = []
print(f"{'PL2/EI':>8} " + " ".join(f"{r:>10}" for r in ladder) + "   lightest within " + str(a.tol))
for f in a.factors.split(","):
    ref = tip(f, "full")
    scale = math.hypot(*ref)
    errs = []
    for r in ladder:
        u = ref if r == "full" else tip(f, r)
        errs.append(max(abs(u[0] - ref[0]), abs(u[1] - ref[1])) / scale)
    best = next(r for r, e in zip(ladder, errs) if e <= a.tol)
    print(f"{10 * float(f):8.3g} " + " ".join(f"{e:10.2e}" for e in errs) + f"   {best}")
    if prev is not None and best != prev[1]:
        changes.append(f"the lightest acceptable rung changes from '{prev[1]}' (PL2/EI = {10 * float(prev[0]):g}) to '{best}' (PL2/EI = {10 * float(f):g})")
    prev = (f, best)
for c in changes:
    print(c)
if not changes:
    print("the lightest acceptable rung is the same at every level")
