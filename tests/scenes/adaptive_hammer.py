#!/usr/bin/env python3
"""Adaptive steps beat fixed steps in steps at equal error on the hammer-struck damped beam (issue 17;
docs/performance.md, "Adaptive steps, fourth round", where CPU is measured over a whole sweep).

inputs/beam_hammer_damped.yaml (a 0.3 ms blow at t = 0.10037 s on a cantilever with material
damping η = 0.01 s) to t = 0.2 s (the blow and the overdamped decay of what it excites in the higher
modes). Reference: the same scene with fixed h = 1e-5 s, a step that lands on the blow's three
breakpoints (0.10037, 0.10052, 0.10067 s) and converges there with order 2. One adaptive run
(tol = 1e-5) must reach an error in tip_y at t_end no larger than that of the fixed step h = 1e-4 s
(a step that does not land on the blow) with fewer steps (measured: adaptive 339 steps, 6.8e-6 m; fixed 2000 steps, 2.6e-3 m). Steps, not
time: no timing in tests.

usage: adaptive_hammer.py ALPHAFLEX INPUTS_DIR OUTDIR
"""
import os
import re
import subprocess
import sys

import numpy as np

exe, inputs, out = sys.argv[1:4]
scene = os.path.join(inputs, "beam_hammer_damped.yaml")
t_end = 0.2


def run(tag, sets):
    d = os.path.join(out, tag)
    cmd = [exe, "run", scene, "-o", d, "--set", "output.hdf5=off", "--set", f"solver.t_end={t_end}"]
    for s in sets:
        cmd += ["--set", s]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, f"{' '.join(cmd)}: exit {r.returncode}\n{r.stdout}\n{r.stderr}"
    m = re.search(r"steps\s+(\d+)", r.stdout)  # the summary's "steps  N [accepted, ...]"
    steps = int(m.group(1)) if m else -1
    csv = np.genfromtxt(os.path.join(d, "beam_hammer_damped.csv"), delimiter=",", names=True)
    return csv["tip_y"][-1], steps, r.stdout


ref, ref_steps, _ = run("reference", ["solver.h=1e-5", "output.every=1000"])
fixed, fixed_steps, _ = run("fixed_1e-4", ["solver.h=1e-4"])
tl = 1e-5
ad, ad_steps, ad_out = run("adaptive", [f"solver.tolerance.rtol={tl}", f"solver.tolerance.atol={tl}"])
e_fixed, e_ad = abs(fixed - ref), abs(ad - ref)
print(f"beam_hammer_damped to {t_end} s, tip_y against fixed h = 1e-5 s ({ref_steps} steps): "
      f"fixed h = 1e-4 s: {fixed_steps} steps, error {e_fixed:.3e} m; adaptive tol {tl:g}: {ad_steps} steps, error {e_ad:.3e} m")
assert fixed_steps == round(t_end / 1e-4), f"unexpected fixed step count {fixed_steps}"
assert ad_steps > 0, ad_out
assert e_ad <= e_fixed, f"adaptive error {e_ad:.3e} m above the fixed step's {e_fixed:.3e} m"
assert ad_steps < fixed_steps, f"adaptive took {ad_steps} steps, the fixed step {fixed_steps}"
