#!/usr/bin/env python3
"""Restarts from checkpoints (io/checkpoint.hpp) and checks that the results are those of the
uninterrupted run:

  checkpoint  the uninterrupted run writes a checkpoint every K steps (output.checkpoint_every, two
              kept: NAME.checkpoint.1.h5 is the mid-run one); a copy of its output directory is
              restarted from that checkpoint (--restart, the same -o), which cuts the results back to
              the checkpoint and runs to t_end again;
  signal      the run is stopped by SIGTERM (one rank) or SIGUSR1 (mpirun forwards it) at a random
              moment, must exit with code 5 and a checkpoint, and is restarted.

With the same number of ranks before and after, the CSV must be the same bytes and every dataset of
NAME.h5 (through its links to the parts) the same bits as the uninterrupted run's. With another
number of ranks, q and v and the sensors must agree within 1e-10 relative, or within 10x the
round-off floor measured by the same run with every load multiplied by 1 + 4.4e-16 (as
compare_ranks.py does: accelerations and multipliers of the index-3 formulation carry the round-off
of q amplified by 1/(beta h^2)).

usage: restart_check.py --exe EXE --mpirun MPIEXEC [--mpiflags '...'] --scene SCENE --outdir DIR
                        --mode checkpoint|signal --ranks N [--restart-ranks M] [--every K] [--seed S]
                        [--set key=value ...]
"""
import argparse
import filecmp
import os
import random
import shlex
import shutil
import signal
import subprocess
import sys
import time

import h5py
import numpy as np

p = argparse.ArgumentParser()
p.add_argument("--exe", required=True)
p.add_argument("--mpirun", required=True)
p.add_argument("--mpiflags", default="")
p.add_argument("--scene", required=True)
p.add_argument("--outdir", required=True)
p.add_argument("--mode", choices=["checkpoint", "signal"], required=True)
p.add_argument("--ranks", type=int, default=1)
p.add_argument("--restart-ranks", type=int, default=None)
p.add_argument("--every", type=int, default=50)
p.add_argument("--seed", type=int, default=1)
p.add_argument("--set", action="append", default=[])
a = p.parse_args()
restart_ranks = a.restart_ranks or a.ranks
name = os.path.splitext(os.path.basename(a.scene))[0]
sets = sum((["--set", s] for s in a.set), [])
# Checkpoints every K steps, two kept. (How the steps fall into part files depends on the wall
# clock; the data, read through NAME.h5's links, do not.)
sets += ["--set", f"output.checkpoint_every={a.every}", "--set", "output.checkpoint_keep=2"]


def command(ranks, out, extra=()):
    cmd = [a.exe, "run", a.scene, "-o", out] + sets + list(extra)
    if ranks > 1:
        cmd = [a.mpirun] + shlex.split(a.mpiflags) + ["-np", str(ranks)] + cmd
    return cmd


def run(ranks, out, extra=(), expect=0):
    r = subprocess.run(command(ranks, out, extra), capture_output=True, text=True, timeout=600)
    if r.returncode != expect:
        sys.exit(f"{' '.join(command(ranks, out, extra))}: exit {r.returncode}, expected {expect}\n{r.stdout}\n{r.stderr}")
    return r


def datasets(out):
    found = {}
    with h5py.File(os.path.join(out, name + ".h5"), "r") as f:
        for g in sorted(k for k in f.keys() if k.startswith("step_")):
            found[g + "/time"] = np.array(f[g].attrs["time"])
            for d in f[g].keys():
                found[g + "/" + d] = f[g][d][()]
    return found


def sensors(out):
    return np.genfromtxt(os.path.join(out, name + ".csv"), delimiter=",", names=True)


reference = os.path.abspath(os.path.join(a.outdir, "uninterrupted"))
shutil.rmtree(reference, ignore_errors=True)
t_ref = time.time()
run(a.ranks, reference)
t_ref = time.time() - t_ref  # how long the whole run takes on this machine now
restarted = os.path.abspath(os.path.join(a.outdir, "restarted"))
shutil.rmtree(restarted, ignore_errors=True)

if a.mode == "checkpoint":
    shutil.copytree(reference, restarted)
    checkpoint = os.path.join(restarted, name + ".checkpoint.1.h5")
    r = run(restart_ranks, restarted, ["--restart", checkpoint])
else:
    # Stop the run at a random moment with the signal a batch system sends, then go on from its
    # checkpoint. One rank: SIGTERM to the process; under mpirun: SIGUSR1, which mpirun forwards.
    rng = random.Random(a.seed)
    # A random moment within the run, scaled by how long the uninterrupted run took here (a fixed
    # delay was too late once small systems got fast, and machines differ).
    if t_ref < 0.5:
        sys.exit(f"the uninterrupted run takes only {t_ref:.2f} s: give it a longer solver.t_end")
    # Under a parallel ctest the load changes between the two runs (this one ran twice as fast as
    # the reference once and ended before the signal): a run that ends first is started again with
    # the moment drawn from half the range, up to three times.
    scale = t_ref
    for attempt in range(4):
        shutil.rmtree(restarted, ignore_errors=True)
        proc = subprocess.Popen(command(a.ranks, restarted), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        time.sleep(rng.uniform(0.3, 0.6) * scale)
        if proc.poll() is None:
            break
        proc.communicate()
        print(f"the run ended before the signal at {scale:.2f} s scale; again with half of it")
        scale /= 2
    else:
        sys.exit("the run ended before the signal four times: give it a longer solver.t_end")
    proc.send_signal(signal.SIGTERM if a.ranks == 1 else signal.SIGUSR1)
    try:
        out, err = proc.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        proc.kill()
        sys.exit("the run did not stop within 120 s of the signal")
    if proc.returncode != 5 or "Go on with: alphaflex run" not in err:
        sys.exit(f"stopped run: exit {proc.returncode}, expected 5 and a restart hint\n{out}\n{err}")
    print(err.strip().splitlines()[0])
    checkpoint = os.path.join(restarted, name + ".checkpoint.h5")
    r = run(restart_ranks, restarted, ["--restart", checkpoint])

if "restarted from" not in r.stdout:
    sys.exit("the restart's summary does not say where it restarted from:\n" + r.stdout)
ref_d, new_d = datasets(reference), datasets(restarted)
if sorted(ref_d) != sorted(new_d):
    missing = sorted(set(ref_d) ^ set(new_d))[:5]
    sys.exit(f"the restarted results have other datasets than the uninterrupted run's, e.g. {missing}")

if restart_ranks == a.ranks:
    if not filecmp.cmp(os.path.join(reference, name + ".csv"), os.path.join(restarted, name + ".csv"), shallow=False):
        sys.exit("the sensors (CSV) of the restarted run differ from the uninterrupted run's")
    differ = [k for k in ref_d if ref_d[k].shape != new_d[k].shape or not np.array_equal(ref_d[k], new_d[k])]
    if differ:
        sys.exit(f"{len(differ)} datasets differ in bits from the uninterrupted run's, e.g. {differ[:5]}")
    print(f"{name}: restart on {a.ranks} rank(s) ({a.mode}) gives the uninterrupted run's results bit for bit: "
          f"{len(ref_d)} datasets and the CSV")
else:
    nudged = os.path.abspath(os.path.join(a.outdir, "nudged"))
    shutil.rmtree(nudged, ignore_errors=True)
    run(a.ranks, nudged, ["--set", "load.factor=1.00000000000000044"])
    nud_d = datasets(nudged)
    ref_s, new_s, nud_s = sensors(reference), sensors(restarted), sensors(nudged)
    worst, failed = 0.0, []
    pairs = [(f"sensor {c}", ref_s[c], new_s[c], nud_s[c]) for c in ref_s.dtype.names]
    last = sorted(k.split("/")[0] for k in ref_d if k.startswith("step_"))[-1]
    pairs += [(f"final {q}", ref_d[f"{last}/{q}"], new_d[f"{last}/{q}"], nud_d[f"{last}/{q}"]) for q in ("q", "v", "lambda")]
    for label, x, y, z in pairs:
        scale = max(np.max(np.abs(x)), 1e-300)
        diff, floor = np.max(np.abs(x - y)) / scale, np.max(np.abs(x - z)) / scale
        worst = max(worst, diff)
        if diff > max(1e-10, 10 * floor):
            failed.append(f"{label}: {diff:.3e} (round-off floor {floor:.3e})")
    if failed:
        sys.exit("restart on another rank count disagrees:\n  " + "\n  ".join(failed))
    print(f"{name}: checkpoint of {a.ranks} rank(s) restarted on {restart_ranks}: largest relative difference {worst:.3e}")
