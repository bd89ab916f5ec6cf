#!/usr/bin/env python3
"""Corrupted checkpoints (issue 24, defect 4): a changed byte is found, never run through.

    checkpoint_flips.py --exe ALPHAFLEX --scene SCENE --out DIR [--np N --mpirun MPIRUN] [--flips K]
                        [--set key=value ...]

A run of SCENE writes a checkpoint at mid-run (output.checkpoint_every) and goes on to t_end: its
CSV is the reference. Then, for each of K bytes of the mid-run checkpoint (spread evenly over the
file, plus a byte inside every dataset's data, found with h5py) a copy with that byte inverted is
given to --restart. Each restart must either be refused with exit 1 and a message naming the
checkpoint file (and, for a byte in a dataset's data, that dataset), or finish with exit 0 and the
reference's sensor rows bit for bit (a byte HDF5 does not use). Never exit 0 with other results
(the issue: 1 of 12 random flips), never a crash or exit 4 (the issue: a flipped dimension asked
for 10^12 values). With --changed key=value, a restart from the checkpoint with that change of
physics (e.g. a beam's EA) must warn naming the element, and one without it must not.
"""
import os
import re
import shutil
import subprocess
import sys

import h5py

import run_options

CRASH = re.compile(r"Segmentation fault|Caught signal|PETSC ERROR|internal error|terminate called|Aborted|core dumped|"
                   r"HDF5-DIAG|bad_alloc")


def main():
    ap = run_options.parser(__doc__)
    ap.add_argument("--flips", type=int, default=40)
    ap.add_argument("--changed", default="", help="key=value: restart with this change of physics instead of flips; "
                    "the restart must warn naming the element (ELEMENT is the regex of its name)")
    ap.add_argument("--element", default=".*")
    a = ap.parse_args()
    name = run_options.prepare(a)
    pre = [a.mpirun, "--oversubscribe", "-np", str(a.np)] if a.np > 1 else []

    def run(outdir, extra):
        cmd = pre + [a.exe, "run", a.scene, "-o", outdir] + [w for s in a.set for w in ("--set", s)] + extra
        return subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=120)

    ref = os.path.join(a.out, "reference")
    r = run(ref, ["--set", "output.checkpoint_keep=2"])
    if r.returncode != 0:
        print(f"FAIL: the reference run: exit {r.returncode}\n{r.stderr}")
        return 1
    good = os.path.join(ref, name + ".checkpoint.1.h5")  # the mid-run one
    if a.changed:
        r = run(ref, ["--restart", good, "--set", a.changed])
        warn = r"warning: element '" + a.element + r"' \(\w+\) differs from the checkpoint's: its \w+"
        if r.returncode != 0 or not re.search(warn, r.stdout):
            print(f"FAIL: restart with {a.changed}: exit {r.returncode}, expected 0 and /{warn}/\n{r.stdout}\n{r.stderr}")
            return 1
        r = run(ref, ["--restart", good])
        if r.returncode != 0 or "differs from the checkpoint" in r.stdout:
            print(f"FAIL: restart without a change: exit {r.returncode} or a warning\n{r.stdout}\n{r.stderr}")
            return 1
        print(f"OK: the restart with {a.changed} warns naming the element; without it, no warning")
        return 0
    want = open(os.path.join(ref, name + ".csv"), "rb").read()
    data = bytearray(open(good, "rb").read())
    # Bytes spread over the file, and one in the data of every dataset (its middle).
    positions = sorted({(k * len(data)) // a.flips for k in range(a.flips)})
    inside = {}
    with h5py.File(good, "r") as f:
        def visit(path, obj):
            if isinstance(obj, h5py.Dataset) and obj.size > 0:
                info = obj.id.get_chunk_info(0) if obj.chunks else None
                start, size = (info.byte_offset, info.size) if info else (obj.id.get_offset(), obj.id.get_storage_size())
                if start is not None and size:
                    inside[start + size // 2] = "/" + path
        f.visititems(visit)
    positions = sorted(set(positions) | set(inside))
    refused = same = 0
    for pos in positions:
        d = os.path.join(a.out, f"flip_{pos}")
        shutil.copytree(ref, d)
        bad = bytearray(data)
        bad[pos] ^= 0xFF
        ck = os.path.join(d, name + ".checkpoint.1.h5")
        open(ck, "wb").write(bad)
        r = run(d, ["--restart", ck])
        what = f"byte {pos}" + (f" (in the data of {inside[pos]})" if pos in inside else "")
        if CRASH.search(r.stderr) or r.returncode not in (0, 1):
            print(f"FAIL: {what}: exit {r.returncode}\n{r.stderr}")
            return 1
        if r.returncode == 1:
            if ck not in r.stderr:
                print(f"FAIL: {what}: refused without naming the checkpoint file\n{r.stderr}")
                return 1
            if pos in inside and inside[pos] not in r.stderr:
                print(f"FAIL: {what}: refused without naming the dataset {inside[pos]}\n{r.stderr}")
                return 1
            refused += 1
        else:
            if pos in inside:
                print(f"FAIL: {what}: a changed value of a dataset was not found (exit 0)")
                return 1
            if open(os.path.join(d, name + ".csv"), "rb").read() != want:
                print(f"FAIL: {what}: exit 0 with results other than the uninterrupted run's")
                return 1
            same += 1
        shutil.rmtree(d)
    print(f"OK: {len(positions)} flipped bytes ({len(inside)} in datasets): {refused} refused naming the file "
          f"(and the dataset), {same} unused by HDF5 (results bit-identical)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
