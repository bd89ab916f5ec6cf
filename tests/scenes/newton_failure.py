#!/usr/bin/env python3
"""A Newton failure ends the run with exit code 3 and a diagnosis (time, step, residual history,
the worst node and joint), and nothing already computed is lost: the CSV and the HDF5/XDMF hold
every step up to the last converged one. Forced by allowing only 3 Newton iterations on the
slider-crank at h = 5e-3, where some steps need 4 (docs/figures/paper_numbers.md: max 4).

usage: newton_failure.py ALPHAFLEX SCENE OUTDIR
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np

exe, scene, out = sys.argv[1:4]
r = subprocess.run([exe, "run", scene, "-o", out, "--set", "solver.newton.max_iter=3"],
                   capture_output=True, text=True, timeout=300)
assert r.returncode == 3, f"exit code {r.returncode}, expected 3\n{r.stdout}\n{r.stderr}"
m = re.search(r"step (\d+) of (\d+): Newton did not converge at t = ([0-9.e-]+) s", r.stderr)
assert m, r.stderr
step, t_fail = int(m.group(1)), float(m.group(3))
for want in ("iteration", "largest equilibrium residual", "at node '", "in joint '", "last converged state"):
    assert want in r.stderr, f"'{want}' missing from:\n{r.stderr}"

name = os.path.splitext(os.path.basename(scene))[0]
csv = np.genfromtxt(os.path.join(out, name + ".csv"), delimiter=",", names=True)
assert len(csv) == step, f"{len(csv)} CSV rows, expected {step} (t = 0 ... last converged)"
with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
    groups = sorted(k for k in f if k.startswith("step_"))
    assert len(groups) == step, (len(groups), step)
    t_last = f[groups[-1]].attrs["time"][0]
assert abs(t_last - csv["t"][-1]) < 1e-12 and t_last < t_fail, (t_last, t_fail)
with open(os.path.join(out, name + ".xdmf")) as f:
    # One temporal collection per kind of thing (bodies, links, shapes, joints): each indexes every step.
    xdmf = f.read()
    collections = xdmf.count('CollectionType="Temporal"')
    assert collections >= 2, f"{collections} temporal collections"
    assert xdmf.count("<Time ") == collections * step, "XDMF does not index every written step"
print(f"Newton failure at step {step} (t = {t_fail}); {step} steps kept up to t = {t_last}")
